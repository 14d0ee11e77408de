// The block's description (every key once) and its validation.
#include "rigid_body_sim/core/types/block_type.h"

#include <cmath>

#include "key_builders.h"
#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

using namespace keys;  // NOLINT: the builders of a description's rows

namespace {
void completeBlock(const std::string&, const std::vector<std::string>&, BlockConfig&) {}
}  // namespace

std::string modeText(const Block& block) { return toString(block.mode()); }

const BodyType<BlockConfig>& BlockType::description() {
  using C = BlockConfig;
  static const BodyType<BlockConfig> type{
      BlockType::kName,
      concat<C>({{number<C>(
                     "size", "m", "edge of the cube drawn", KeyChange::Apply,
                     [](C& c) -> double& { return c.params.size; }, positive(kMaxSize))},
                 inclineKeys<C>()}),  // mass, the slope and its friction, x0 and v0: as a roller's
      completeBlock};
  return type;
}

void validate(const std::string& body, const BlockConfig& config) {
  checkRanges(body, config);
  const BlockParams& p = config.params;
  if (!gravityRange().contains(p.gravity)) {
    throw ConfigError(body, "gravity", formatNumber(p.gravity), gravityRange().describe());
  }
  checkFriction(body, p.mu_s, p.mu_d);
  checkOnSlope(body, "x0", config.initial.x0, p.incline_length);
  checkDerived(body, "mass and the initial conditions", "energy at the start",
               Block(p, config.initial).energy(), false);
}

void BlockType::checkState(const std::string& body, const Config& config, const BlockMotion& state) {
  checkOnSlope(body, "x", state.x, config.params.incline_length);
}

std::optional<double> BlockType::closedFormInstant(const Config& config, std::size_t kind) {
  if (kind != kGripped && kind != kFinished) return std::nullopt;
  const BlockRun run = closedFormRun(config.params, config.initial);
  if (kind == kFinished) return run.finish;
  // A stop where static friction does not hold is no event: the block slides back at once.
  return Block::canStick(config.params) ? run.stops : std::nullopt;
}

}  // namespace rigid_body_sim
