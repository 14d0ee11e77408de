#include "rigid_body_sim/ros/reconfigure.h"

namespace rigid_body_sim {

RodReconfigureConfig toReconfigure(const RodConfig& config) {
  RodReconfigureConfig out;
  out.k = config.params.k;
  out.mass = config.params.mass;
  out.length = config.params.length;
  out.integrator = toString(config.params.integrator);
  out.x0 = config.initial.x;
  out.y0 = config.initial.y;
  out.vx0 = config.initial.vx;
  out.vy0 = config.initial.vy;
  out.theta0 = config.initial.theta;
  out.omega0 = config.initial.omega;
  return out;
}

RollerReconfigureConfig toReconfigure(const RollerConfig& config) {
  RollerReconfigureConfig out;
  out.shape = toString(config.params.shape);
  out.inertia_factor = config.params.inertia_factor;
  out.radius = config.params.radius;
  out.mass = config.params.mass;
  out.incline_angle = config.params.incline_angle;
  out.incline_length = config.params.incline_length;
  out.mu_s = config.params.mu_s;
  out.mu_d = config.params.mu_d;
  out.x0 = config.initial.x0;
  out.v0 = config.initial.v0;
  out.theta0 = config.initial.theta0;
  out.omega0 = config.initial.omega0;
  return out;
}

RodConfig fromReconfigure(const std::string& body, const RodReconfigureConfig& request,
                          const RodConfig& current) {
  RodConfig out = current;
  out.params.k = request.k;
  out.params.mass = request.mass;
  out.params.length = request.length;
  const auto integrator = integratorFromString(request.integrator);
  if (!integrator) {
    throw ConfigError(body, "integrator", "'" + request.integrator + "'",
                      "euler_cromer, velocity_verlet or rk4");
  }
  out.params.integrator = *integrator;
  out.initial = {request.x0, request.y0, request.theta0, request.vx0, request.vy0, request.omega0};
  return out;
}

RollerConfig fromReconfigure(const std::string& body, const RollerReconfigureConfig& request,
                             const RollerConfig& current) {
  RollerConfig out = current;
  if (request.shape == "custom") {
    out.params.shape = Shape::Custom;
    out.params.inertia_factor = request.inertia_factor;
  } else {
    const auto shape = shapeFromString(request.shape);
    if (!shape) {
      throw ConfigError(body, "shape", "'" + request.shape + "'",
                        "sphere, cylinder, ring, spherical_shell or custom");
    }
    // A new named shape brings its own c; an unchanged one keeps the requested c for validation.
    const bool shape_changed = *shape != current.params.shape;
    out.params.shape = *shape;
    out.params.inertia_factor = shape_changed ? inertiaFactorOf(*shape) : request.inertia_factor;
  }
  out.params.radius = request.radius;
  out.params.mass = request.mass;
  out.params.incline_angle = request.incline_angle;
  out.params.incline_length = request.incline_length;
  out.params.mu_s = request.mu_s;
  out.params.mu_d = request.mu_d;
  out.initial = {request.x0, request.v0, request.theta0, request.omega0};
  return out;
}

bool initialChanged(const RodConfig& a, const RodConfig& b) {
  const RodMotion& p = a.initial;
  const RodMotion& q = b.initial;
  return p.x != q.x || p.y != q.y || p.theta != q.theta || p.vx != q.vx || p.vy != q.vy || p.omega != q.omega;
}

bool initialChanged(const RollerConfig& a, const RollerConfig& b) {
  const RollerInitial& p = a.initial;
  const RollerInitial& q = b.initial;
  return p.x0 != q.x0 || p.v0 != q.v0 || p.theta0 != q.theta0 || p.omega0 != q.omega0;
}

}  // namespace rigid_body_sim
