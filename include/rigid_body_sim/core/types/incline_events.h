// The events of a body on an incline (the roller, the block), written once: its two grip kinds in its own
// words, then the lap's (it passes an end of its slope; it starts again from its initial conditions).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "rigid_body_sim/core/event.h"

namespace rigid_body_sim {

// Indices into an incline type's kEventKinds.
enum InclineEvent : std::size_t { kGripped, kLostGrip, kFinished, kLapRestarted };

constexpr std::array<EventKind, 4> inclineEventKinds(EventKind gripped, EventKind lost_grip) {
  return {
      gripped, lost_grip,
      EventKind{"finished",
                "its centre passed an end of its slope; values: lap_time (s since its lap started), speed "
                "(m/s along the slope), closed_form (the lap's time in closed form, when the lap ran as "
                "configured), place (in a race; ties share one)",
                EventRole::Finish},
      EventKind{"lap_restarted",
                "it started again from its initial conditions; value cause: lap (off an end of its "
                "slope), race (the race's next lap), reset, reconfigure, spawn or config",
                EventRole::Restart}};
}

// Calls report(kind, offset, model at that instant, values) for each event of a step, in time order.
template <class Model, class Report>
void forEachInclineEvent(const Model& model, const typename Model::StepEvents& happened, double dt,
                         Report&& report) {
  const auto at = [&](const typename Model::Progress& progress) {
    Model then = model;
    then.restore(progress);
    return then;
  };
  if (happened.started_slipping) report(kLostGrip, 0.0, at(happened.at_start), std::vector<EventValue>{});
  // A grip after the centre left its slope happened off it (the body restarts at the step's end): none.
  if (happened.stuck_at && !(happened.left_at && *happened.left_at < *happened.stuck_at)) {
    report(kGripped, *happened.stuck_at, at(happened.at_stuck), std::vector<EventValue>{});
  }
  if (happened.left_at) {
    report(kFinished, *happened.left_at, at(happened.at_left),
           std::vector<EventValue>{EventValue{"speed", happened.arrival_speed}});
  }
  if (happened.restarted)
    report(kLapRestarted, dt, model, std::vector<EventValue>{EventValue{"cause", 0.0, "lap"}});
}

// The base of an incline body type: its forEachEvent, the world's way to its events.
template <class Model>
struct InclineEvents {
  template <class Report>
  static void forEachEvent(const Model& model, const typename Model::StepEvents& happened, double dt,
                           Report&& report) {
    forEachInclineEvent(model, happened, dt, report);
  }
};

}  // namespace rigid_body_sim
