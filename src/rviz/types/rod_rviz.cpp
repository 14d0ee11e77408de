// The rod in the panel: the height of each end (where the floor's springs push) and whether one is down. Its
// events (an end's contact, a restart) mark nothing: a bounce shows in the heights.
#include <cmath>

#include "rigid_body_sim/core/rod.h"
#include "rigid_body_sim/rviz/body_type_rviz.h"

namespace rigid_body_sim {
namespace {

class RodRviz : public RvizBodyTypeOf<RodType> {
 public:
  std::vector<ChartSpec> charts() const override {
    return {{"height of each end",
             "y (m)",
             {{"y_end_plus", "y + (L/2) sin \u03b8"}, {"y_end_minus", "y \u2212 (L/2) sin \u03b8"}}}};
  }
  QString potentialZero() const override { return "at floor level"; }
  void setParameters(const dynamic_reconfigure::Config& config) override {
    const auto mass = parameterOf(config, "mass"), length = parameterOf(config, "length");
    known_ = mass && length;
    if (!known_) return;
    params_.mass = *mass;
    params_.length = *length;
  }

 protected:
  void plotState(const RodState& state, PlotSink& sink) override {
    if (!known_) {
      sink.energies(state.t, state.energy, std::nullopt);
      return;
    }
    const double rise = 0.5 * params_.length * std::sin(state.theta);  // of the + end above the centre
    sink.append(0, 0, state.t, state.y + rise);
    sink.append(0, 1, state.t, state.y - rise);
    const Rod rod(params_, RodMotion{state.x, state.y, state.theta, state.vx, state.vy, state.omega});
    sink.energies(state.t, state.energy, rod.kineticEnergy());
  }
  QString motion(const RodState& state) const override {
    const QString energy = energyText(state.energy, potentialZero());
    if (!known_) return energy;  // a replay: no length to tell
    const double lowest_end = state.y - 0.5 * params_.length * std::abs(std::sin(state.theta));
    return QString(lowest_end < 0 ? "on the floor" : "in the air") + " \u00b7 " + energy;
  }

 private:
  RodParams params_;
  bool known_ = false;
};

}  // namespace

template <>
std::unique_ptr<RvizBodyType> makeRvizBodyType<RodType>() {
  return std::make_unique<RodRviz>();
}

}  // namespace rigid_body_sim
