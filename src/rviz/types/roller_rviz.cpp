// A roller in the panel: v and -omega R on one chart (equal while it rolls), each slip-to-roll instant and
// each finish marked there from its event, and the friction force.
#include <optional>

#include "rigid_body_sim/core/roller.h"
#include "rigid_body_sim/rviz/body_type_rviz.h"
#include "rigid_body_sim/rviz/fixed_text.h"

namespace rigid_body_sim {
namespace {

class RollerRviz : public RvizBodyTypeOf<RollerType> {
 public:
  std::vector<ChartSpec> charts() const override {
    return {{"speeds (equal while rolling)",
             "speed (m/s)",
             {{"v", "v"},
              {"minus_omega_r", "\u2212\u03c9R"},
              {"slip_to_roll", "slip \u2192 roll", true},
              {"finished", "finished", true}}},
            {"friction on the body, along the slope", "F (N)", {{"friction", "friction"}}}};
  }
  QString potentialZero() const override { return "at the slope's top"; }
  void setParameters(const dynamic_reconfigure::Config& config) override {
    const auto mass = parameterOf(config, "mass"), radius = parameterOf(config, "radius"),
               c = parameterOf(config, "inertia_factor"), angle = parameterOf(config, "incline_angle"),
               length = parameterOf(config, "incline_length"), mu_s = parameterOf(config, "mu_s"),
               mu_d = parameterOf(config, "mu_d");
    known_ = mass && radius && c && angle && length && mu_s && mu_d;
    if (!known_) return;
    params_.shape = Shape::Custom;  // the server gives c itself: the shape's, or a custom one
    params_.inertia_factor = *c;
    params_.mass = *mass;
    params_.radius = *radius;
    params_.incline_angle = *angle;
    params_.incline_length = *length;
    params_.mu_s = *mu_s;
    params_.mu_d = *mu_d;
  }
  std::optional<Verdict> critical() const override {
    if (!known_) return std::nullopt;
    const QString slope = degreesText(params_.incline_angle, 1);
    return Verdict{QString("critical angle %1 for \u03bcs %2: ")
                           .arg(degreesText(criticalAngle(params_.mu_s, params_.inertia_factor), 1),
                                numberText(params_.mu_s)) +
                       (Roller::canRoll(params_) ? "can roll without slipping (slope " + slope + ")"
                                                 : "slips (slope " + slope + " above it)"),
                   "rolling holds while tan(slope) <= mu_s (1 + c) / c, with c = I / (M R^2)"};
  }
  // On the speeds chart at v then: each slip-to-roll instant (since the reset, as the t axis counts) and
  // each finish (its lap time, place and closed form).
  void plotEvent(const Event& event, PlotSink& sink) const override {
    const auto v = eventNumber(event.state, "v");
    if (!v) return;
    if (event.kind == RollerType::kEventKinds[kGripped].name) {
      sink.mark(0, 2, event.t, *v,
                QString("slip \u2192 roll at %1 s").arg(fixed(event.t - sink.origin(), 3)));
    } else if (event.kind == RollerType::kEventKinds[kFinished].name) {
      sink.mark(0, 3, event.t, *v, finishNote(event));
    }
  }

 protected:
  // Rolling means v = -omega R (RollerState.msg): v and -omega R coincide then.
  void plotState(const RollerState& state, PlotSink& sink) override {
    sink.append(0, 0, state.t, state.v);
    if (known_) sink.append(0, 1, state.t, -state.omega * params_.radius);
    sink.append(1, 0, state.t, state.friction);
    const RollerInitial now{state.x, state.v, state.theta, state.omega};
    sink.energies(state.t, state.energy,
                  known_ ? std::optional(Roller(params_, now).kineticEnergy()) : std::nullopt);
  }
  QString motion(const RollerState& state) const override {
    return QString::fromStdString(state.mode) + " \u00b7 " + energyText(state.energy, potentialZero());
  }

 private:
  RollerParams params_;
  bool known_ = false;
};

}  // namespace

template <>
std::unique_ptr<RvizBodyType> makeRvizBodyType<RollerType>() {
  return std::make_unique<RollerRviz>();
}

}  // namespace rigid_body_sim
