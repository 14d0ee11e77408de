// What each body type shows in the rviz panel, as its own file (src/rviz/types/<type>_rviz.cpp) defines it:
// its charts on the Plots tab beside the energy chart every body has, what each of its states adds to them,
// what each of its events (the node's ~events) marks on them, and the line its section shows. BodyPlots and
// BodySection show every body from these alone: only a type's own file names its event kinds.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QString>

#include <dynamic_reconfigure/Config.h>
#include <ros/ros.h>

#include "rigid_body_sim/Event.h"
#include "rigid_body_sim/core/event.h"
#include "rigid_body_sim/ros/body_types_ros.h"

namespace rigid_body_sim {

// A line on a chart (plot.<key> in the panel's layout lines), or marks at events' instants, each with its
// note, the last one's shown beside it (plot.<key>.note).
struct TrackSpec {
  std::string key;
  QString name;  // the legend's
  bool marks = false;
};

struct ChartSpec {
  QString title;
  QString y_title;  // with its unit
  std::vector<TrackSpec> tracks;
};

// Where a body type's states and events go on the Plots tab: the charts its type lists (by their index and
// their tracks'), then the energy chart every body has.
class PlotSink {
 public:
  virtual ~PlotSink() = default;
  virtual void append(std::size_t chart, std::size_t track, double t, double value) = 0;
  // A mark at an event's instant t (a track of marks), with its note.
  virtual void mark(std::size_t chart, std::size_t track, double t, double value, const QString& note) = 0;
  // The energy chart: the total (the state's), the kinetic (none while the body's parameters are not
  // known, as in a replay) and the potential, what remains of the total.
  virtual void energies(double t, double total, std::optional<double> kinetic) = 0;
  virtual double origin() const = 0;  // t of the last reset or config: the charts' t axis starts there
};

// One body's face in the panel, by its type.
class RvizBodyType {
 public:
  // A body's critical angle and whether its slope is above it (text), and what holds it (why).
  struct Verdict {
    QString text;
    QString why;
  };

  virtual ~RvizBodyType() = default;
  virtual QString unit(const std::string& key) const = 0;  // as the description gives it; "" for none
  virtual std::vector<ChartSpec> charts() const = 0;       // its own, above the energy chart
  virtual QString potentialZero() const = 0;  // where its potential energy is 0 ("at floor level")
  // Its parameters, from its reconfigure server's updates. A replay has no server: what needs them is not
  // drawn then.
  virtual void setParameters(const dynamic_reconfigure::Config& config) = 0;
  // Its critical angle from its parameters, if it has one.
  virtual std::optional<Verdict> critical() const { return std::nullopt; }
  // What an event of its body marks on its charts (sink.mark), by the event's kind; nothing for a kind it
  // does not draw.
  virtual void plotEvent(const Event& /*event*/, PlotSink& /*sink*/) const {}
  // Its states on `topic`: those `take` lets through to `sink` (a queue for every state between two of
  // rviz's spins), or the newest one's t and the line its section shows.
  virtual ros::Subscriber plot(ros::NodeHandle& nh, const std::string& topic,
                               std::function<bool(double)> take, PlotSink& sink) = 0;
  virtual ros::Subscriber describe(ros::NodeHandle& nh, const std::string& topic,
                                   std::function<void(double, const QString&)> show) = 0;
};

// The subscriptions of a type with state message StateMsg; the type's own file defines the rest.
template <class Type>
class RvizBodyTypeOf : public RvizBodyType {
 public:
  using StateMsg = typename RosMessages<Type>::StateMsg;

  QString unit(const std::string& key) const override {
    const auto* found = findKey(Type::description().keys, key);
    return found ? QString::fromUtf8(found->unit) : QString();
  }

  ros::Subscriber plot(ros::NodeHandle& nh, const std::string& topic, std::function<bool(double)> take,
                       PlotSink& sink) override {
    return nh.subscribe<StateMsg>(topic, 100, [this, take, &sink](const typename StateMsg::ConstPtr& state) {
      if (take(state->t)) plotState(*state, sink);
    });
  }
  ros::Subscriber describe(ros::NodeHandle& nh, const std::string& topic,
                           std::function<void(double, const QString&)> show) override {
    return nh.subscribe<StateMsg>(
        topic, 1, [this, show](const typename StateMsg::ConstPtr& state) { show(state->t, motion(*state)); });
  }

 protected:
  virtual void plotState(const StateMsg& state, PlotSink& sink) = 0;
  virtual QString motion(const StateMsg& state) const = 0;  // "rolling · E = 1.234 J (...)"
};

// Each type's, defined in its src/rviz/types/<type>_rviz.cpp: a type without one does not link.
template <class Type>
std::unique_ptr<RvizBodyType> makeRvizBodyType();

// The body type whose state message is `state_type` ("rigid_body_sim/RodState"); null for none.
std::unique_ptr<RvizBodyType> rvizBodyTypeOf(const std::string& state_type);

// The parameter `name` of a reconfigure config's doubles, ints, bools or strs; null if it has none.
template <class Parameter>
const Parameter* parameterNamed(const std::vector<Parameter>& parameters, const std::string& name) {
  for (const auto& p : parameters) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

// The value of the number `name` in a reconfigure config, if it has one.
inline std::optional<double> parameterOf(const dynamic_reconfigure::Config& config, const std::string& name) {
  const auto* p = parameterNamed(config.doubles, name);
  return p ? std::optional(p->value) : std::nullopt;
}

// "E = 1.234 J (potential 0 with its centre <zero>)": every section's energy.
QString energyText(double energy, const QString& zero);

// What the world does with an event of this kind (core/event.h: a finish, a restart, or neither), from its
// type's kinds; None for a type or kind it does not know.
EventRole eventRole(const Event& event);

// The number or the text named `name` among an event's fields (its state or its values), if it has one.
std::optional<double> eventNumber(const std::vector<EventField>& fields, const std::string& name);
std::optional<std::string> eventText(const std::vector<EventField>& fields, const std::string& name);

// A finish's note from its values: "finished in 1.7492 s", in a race its place first ("2nd in 1.7492 s"),
// then the closed form's time when the event gives it ("(closed form 1.7492 s)").
QString finishNote(const Event& event);

}  // namespace rigid_body_sim
