// The body types, registered once. Everything that treats bodies differently reads this list: the
// variants of configs and models, the `type` names a config file takes, the loader and writer, the world,
// the state fields, and (ros/body_types_ros.h) the messages, reconfigure servers and looks. A type is a
// bundle in core/types/ (its config, keys, state fields, frames); code that handles every type dispatches
// with std::visit, so that a type without its case does not compile.
#pragma once

#include <cstddef>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "rigid_body_sim/core/types/block_type.h"
#include "rigid_body_sim/core/types/rod_type.h"
#include "rigid_body_sim/core/types/roller_type.h"

namespace rigid_body_sim {

template <class... Types>
struct BodyTypeList {
  using Configs = std::variant<typename Types::Config...>;
  using Models = std::variant<typename Types::Model...>;
  using Progresses =
      std::variant<typename Types::Model::Progress...>;  // what a step changes (Model::progress)
  // Calls f(Type{}) for each type, in the list's order.
  template <class F>
  static void forEach(F&& f) {
    (f(Types{}), ...);
  }
};

// The registration: one line a type.
using BodyTypes = BodyTypeList<RodType, RollerType, BlockType>;

using AnyBodyConfig = BodyTypes::Configs;
using AnyModel = BodyTypes::Models;

namespace detail {
template <class Config, class... Types>
struct TypeOfConfigIn;
template <class Config, class First, class... Rest>
struct TypeOfConfigIn<Config, First, Rest...>
    : std::conditional_t<std::is_same_v<Config, typename First::Config>, std::common_type<First>,
                         TypeOfConfigIn<Config, Rest...>> {};
template <class Model, class... Types>
struct TypeOfModelIn;
template <class Model, class First, class... Rest>
struct TypeOfModelIn<Model, First, Rest...>
    : std::conditional_t<std::is_same_v<Model, typename First::Model>, std::common_type<First>,
                         TypeOfModelIn<Model, Rest...>> {};
template <class List, class T, bool ByModel>
struct Lookup;
template <class... Types, class T>
struct Lookup<BodyTypeList<Types...>, T, false> : TypeOfConfigIn<T, Types...> {};
template <class... Types, class T>
struct Lookup<BodyTypeList<Types...>, T, true> : TypeOfModelIn<T, Types...> {};
}  // namespace detail

// The type a config or a model belongs to: TypeOfConfig<RodConfig> is RodType.
template <class Config>
using TypeOfConfig = typename detail::Lookup<BodyTypes, std::decay_t<Config>, false>::type;
template <class Model>
using TypeOfModel = typename detail::Lookup<BodyTypes, std::decay_t<Model>, true>::type;

// The description of a config's type: bodyType<RodConfig>() is RodType::description().
template <class Config>
const BodyType<Config>& bodyType() {
  return TypeOfConfig<Config>::description();
}

// The `type` names, in the list's order ("rod", "roller", "block").
const std::vector<std::string>& bodyTypeNames();

// A set of lambdas as one visitor: std::visit(Overloaded{[](const Rod&) {...}, ...}, model).
template <class... Fs>
struct Overloaded : Fs... {
  using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

}  // namespace rigid_body_sim
