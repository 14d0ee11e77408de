// dynamic_reconfigure configs <-> core body configs, for every body type (ros/body_types_ros.h names its
// config). Pure functions: the node validates what they return.
#pragma once

#include <string>

#include <boost/pointer_cast.hpp>

#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/ros/body_types_ros.h"

namespace rigid_body_sim {

namespace reconfigure_detail {

// The member of a reconfigure request that holds a key: a double for a number, a string for a text; neither
// for a key the .cfg does not serve (a rod's seed, which is written as theta0). test_reconfigure checks that
// the .cfg holds exactly the description's written keys, with their defaults, levels and meanings, and no
// ranges of its own. (Type names: clang-format 14 and 19 space `Request::*field` apart.)
template <class Request>
using NumberMember = double Request::*;
template <class Request>
using TextMember = std::string Request::*;

template <class Request>
struct Member {
  NumberMember<Request> number = nullptr;
  TextMember<Request> text = nullptr;
};

template <class Request>
Member<Request> memberNamed(const std::string& name) {
  using Number = typename Request::template ParamDescription<double>;
  using Text = typename Request::template ParamDescription<std::string>;
  Member<Request> member;
  for (const auto& description : Request::__getParamDescriptions__()) {
    if (description->name != name) continue;
    if (const auto number = boost::dynamic_pointer_cast<const Number>(description))
      member.number = number->field;
    if (const auto text = boost::dynamic_pointer_cast<const Text>(description)) member.text = text->field;
  }
  return member;
}

template <class Request, class Config>
Request requestOf(const Config& config) {
  Request request;
  for (const auto& key : bodyType<Config>().keys) {
    const Member<Request> member = memberNamed<Request>(key.name);
    if (member.number) request.*member.number = key.number(config);
    if (member.text) request.*member.text = key.text(config);
  }
  return request;
}

// The keys whose requested value differs from the current one, in the description's order (a roller's shape
// before its inertia_factor: a new named shape brings its own c, an unchanged one keeps the requested c for
// validation to judge).
template <class Request, class Config>
Config configOf(const std::string& body, const Request& request, const Config& current) {
  const Request now = requestOf<Request>(current);
  Config out = current;
  for (const auto& key : bodyType<Config>().keys) {
    const Member<Request> member = memberNamed<Request>(key.name);
    if (member.number && request.*member.number != now.*member.number) {
      key.field(out) = request.*member.number;
    }
    if (member.text && request.*member.text != now.*member.text) {
      setKeyText(body, key, request.*member.text, out);
    }
  }
  return out;
}

}  // namespace reconfigure_detail

// The request that shows a config's keys (each key the type's .cfg serves).
template <class Config>
typename RosBodyType<TypeOfConfig<Config>>::Reconfigure toReconfigure(const Config& config) {
  return reconfigure_detail::requestOf<typename RosBodyType<TypeOfConfig<Config>>::Reconfigure>(config);
}

// The body config a reconfigure request asks for, starting from the current one (gravity is kept).
// A named shape brings its own c; changing c without shape custom is left for validation to refuse.
// Throws ConfigError for a name that no enum allows.
template <class Config>
Config fromReconfigure(const std::string& body,
                       const typename RosBodyType<TypeOfConfig<Config>>::Reconfigure& request,
                       const Config& current) {
  return reconfigure_detail::configOf(body, request, current);
}

}  // namespace rigid_body_sim
