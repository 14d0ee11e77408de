// The block in the panel: its speed along the slope, each instant it came to rest and each finish marked
// there from its event, and the friction on it.
#include <cmath>
#include <optional>

#include "rigid_body_sim/core/block.h"
#include "rigid_body_sim/rviz/body_type_rviz.h"
#include "rigid_body_sim/rviz/fixed_text.h"

namespace rigid_body_sim {
namespace {

class BlockRviz : public RvizBodyTypeOf<BlockType> {
 public:
  std::vector<ChartSpec> charts() const override {
    return {{"speed along the slope",
             "speed (m/s)",
             {{"v", "v"}, {"came_to_rest", "came to rest", true}, {"finished", "finished", true}}},
            {"friction on the block, along the slope", "F (N)", {{"friction", "friction"}}}};
  }
  QString potentialZero() const override { return "at the slope's top"; }
  void setParameters(const dynamic_reconfigure::Config& config) override {
    const auto mass = parameterOf(config, "mass"), angle = parameterOf(config, "incline_angle"),
               mu_s = parameterOf(config, "mu_s");
    known_ = mass && angle && mu_s;
    if (!known_) return;
    params_.mass = *mass;
    params_.incline_angle = *angle;
    params_.mu_s = *mu_s;
  }
  std::optional<Verdict> critical() const override {
    if (!known_) return std::nullopt;
    const QString slope = degreesText(params_.incline_angle, 1);
    return Verdict{QString("critical angle %1 for \u03bcs %2: ")
                           .arg(degreesText(std::atan(params_.mu_s), 1), numberText(params_.mu_s)) +
                       (Block::canStick(params_) ? "stays put at rest (slope " + slope + ")"
                                                 : "slides from rest (slope " + slope + " above it)"),
                   "a block at rest stays while tan(slope) <= mu_s"};
  }

  // On the speed chart at v then: each instant it came to rest (since the reset, as the t axis counts) and
  // each finish (its lap time, place and closed form).
  void plotEvent(const Event& event, PlotSink& sink) const override {
    const auto v = eventNumber(event.state, "v");
    if (!v) return;
    if (event.kind == BlockType::kEventKinds[kGripped].name) {
      sink.mark(0, 1, event.t, *v, QString("came to rest at %1 s").arg(fixed(event.t - sink.origin(), 3)));
    } else if (event.kind == BlockType::kEventKinds[kFinished].name) {
      sink.mark(0, 2, event.t, *v, finishNote(event));
    }
  }

 protected:
  void plotState(const BlockState& state, PlotSink& sink) override {
    sink.append(0, 0, state.t, state.v);
    sink.append(1, 0, state.t, state.friction);
    const BlockInitial now{state.x, state.v};
    sink.energies(state.t, state.energy,
                  known_ ? std::optional(Block(params_, now).kineticEnergy()) : std::nullopt);
  }
  QString motion(const BlockState& state) const override {
    return QString::fromStdString(state.mode) + " \u00b7 " + energyText(state.energy, potentialZero());
  }

 private:
  BlockParams params_;
  bool known_ = false;
};

}  // namespace

template <>
std::unique_ptr<RvizBodyType> makeRvizBodyType<BlockType>() {
  return std::make_unique<BlockRviz>();
}

}  // namespace rigid_body_sim
