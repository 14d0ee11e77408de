#include "rigid_body_sim/ros/reconfigure.h"

#include <boost/pointer_cast.hpp>

namespace rigid_body_sim {

namespace {

// Calls visit(key, field) for every number of a .cfg: `field` is the request's member, `key` the core's
// numeric key of the same name (test_reconfigure checks that the .cfg's numbers are the core's keys, with
// their defaults and no ranges of their own). Texts (the integrator, substeps, the shape) are left to the
// caller.
template <class Request, class Config, class Visit>
void forEachNumber(const std::vector<NumericKey<Config>>& keys, Visit visit) {
  using Number = typename Request::template ParamDescription<double>;
  for (const auto& description : Request::__getParamDescriptions__()) {
    const auto number = boost::dynamic_pointer_cast<const Number>(description);
    const NumericKey<Config>* key = number ? findKey(keys, number->name) : nullptr;
    if (key) visit(*key, number->field);
  }
}

// A double field of a reconfigure request (a name: clang-format 14 and 19 space `Request::*field` apart).
template <class Request>
using NumberField = double Request::*;

template <class Request, class Config>
Request numbersOf(Config config, const std::vector<NumericKey<Config>>& keys) {
  Request request;
  forEachNumber<Request>(keys, [&](const NumericKey<Config>& key, NumberField<Request> field) {
    request.*field = key.field(config);
  });
  return request;
}

template <class Request, class Config>
void setNumbers(const Request& request, Config& config, const std::vector<NumericKey<Config>>& keys) {
  forEachNumber<Request>(keys, [&](const NumericKey<Config>& key, NumberField<Request> field) {
    key.field(config) = request.*field;
  });
}

}  // namespace

RodReconfigureConfig toReconfigure(const RodConfig& config) {
  auto request = numbersOf<RodReconfigureConfig>(config, rodNumericKeys());
  request.integrator = toString(config.params.integrator);
  request.substeps = substepsToString(config.params.substeps);
  return request;
}

RollerReconfigureConfig toReconfigure(const RollerConfig& config) {
  auto request = numbersOf<RollerReconfigureConfig>(config, rollerNumericKeys());
  request.shape = toString(config.params.shape);
  return request;
}

RodConfig fromReconfigure(const std::string& body, const RodReconfigureConfig& request,
                          const RodConfig& current) {
  RodConfig out = current;
  setNumbers(request, out, rodNumericKeys());
  const auto integrator = integratorFromString(request.integrator);
  if (!integrator) {
    throw ConfigError(body, "integrator", "'" + request.integrator + "'",
                      "euler_cromer, velocity_verlet or rk4");
  }
  out.params.integrator = *integrator;
  const auto substeps = substepsFromString(request.substeps);
  if (!substeps) throw ConfigError(body, "substeps", "'" + request.substeps + "'", substepsAllowed());
  out.params.substeps = *substeps;
  return out;
}

RollerConfig fromReconfigure(const std::string& body, const RollerReconfigureConfig& request,
                             const RollerConfig& current) {
  RollerConfig out = current;
  setNumbers(request, out, rollerNumericKeys());
  if (request.shape == "custom") {
    out.params.shape = Shape::Custom;
    return out;
  }
  const auto shape = shapeFromString(request.shape);
  if (!shape) {
    throw ConfigError(body, "shape", "'" + request.shape + "'",
                      "sphere, cylinder, ring, spherical_shell or custom");
  }
  // A new named shape brings its own c; an unchanged one keeps the requested c for validation.
  if (*shape != current.params.shape) out.params.inertia_factor = inertiaFactorOf(*shape);
  out.params.shape = *shape;
  return out;
}

}  // namespace rigid_body_sim
