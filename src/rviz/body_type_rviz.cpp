#include "rigid_body_sim/rviz/body_type_rviz.h"

#include <cstdlib>

#include <ros/message_traits.h>

#include "rigid_body_sim/rviz/fixed_text.h"

namespace rigid_body_sim {

namespace {

// "1st", "2nd", "3rd", "4th" ... "11th", "12th", "13th", "21st".
QString ordinal(int place) {
  const int last = std::abs(place) % 10;
  const bool teen = std::abs(place) % 100 / 10 == 1;
  const char* suffix = teen ? "th" : last == 1 ? "st" : last == 2 ? "nd" : last == 3 ? "rd" : "th";
  return QString::number(place) + suffix;
}

}  // namespace

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

EventRole eventRole(const Event& event) {
  EventRole role = EventRole::None;
  BodyTypes::forEach([&](auto type) {
    using Type = decltype(type);
    if (event.type != Type::kName) return;
    for (const EventKind& kind : Type::kEventKinds) {
      if (event.kind == kind.name) role = kind.role;
    }
  });
  return role;
}

std::optional<double> eventNumber(const std::vector<EventField>& fields, const std::string& name) {
  for (const auto& field : fields) {
    if (field.name == name && field.text.empty()) return field.number;
  }
  return std::nullopt;
}

std::optional<std::string> eventText(const std::vector<EventField>& fields, const std::string& name) {
  for (const auto& field : fields) {
    if (field.name == name && !field.text.empty()) return field.text;
  }
  return std::nullopt;
}

QString finishNote(const Event& event) {
  const auto place = eventNumber(event.values, "place"), lap_time = eventNumber(event.values, "lap_time"),
             closed_form = eventNumber(event.values, "closed_form");
  QString note = place ? ordinal(static_cast<int>(*place)) : QString("finished");
  if (lap_time) note += QString(" in %1 s").arg(fixed(*lap_time, 4));
  if (closed_form) note += QString(" (closed form %1 s)").arg(fixed(*closed_form, 4));
  return note;
}

}  // namespace rigid_body_sim
