#include "rigid_body_sim/rviz/body_type_rviz.h"

#include <ros/message_traits.h>

#include "rigid_body_sim/rviz/fixed_text.h"

namespace rigid_body_sim {

std::unique_ptr<RvizBodyType> rvizBodyTypeOf(const std::string& state_type) {
  std::unique_ptr<RvizBodyType> found;
  BodyTypes::forEach([&](auto type) {
    using Type = decltype(type);
    if (ros::message_traits::datatype<typename RosMessages<Type>::StateMsg>() == state_type)
      found = makeRvizBodyType<Type>();
  });
  return found;
}

QString energyText(double energy, const QString& zero) {
  return QString("E = %1 J (potential 0 with its centre %2)").arg(fixed(energy, 3), zero);
}

}  // namespace rigid_body_sim
