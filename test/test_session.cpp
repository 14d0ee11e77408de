// Session: the run loop's one order (the state of a count is handed out at most once, before the commands
// at that count apply), checked against a plain World stepped and changed by hand; and the replay, which
// runs through it, against the same.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/io/csv_writer.h"
#include "rigid_body_sim/run/replay.h"
#include "rigid_body_sim/run/session.h"
#include "test_util.h"

using namespace rigid_body_sim;
using rigid_body_sim::test::FolderTest;
using rigid_body_sim::test::rodAndBall;
using rigid_body_sim::test::slurp;

namespace {

constexpr std::int64_t kStepsPerSample = 4;

// Every body's reported fields, numbers in shortest round-trip form: equal texts are equal bits.
std::string stateOf(const World& world) {
  std::string text = std::to_string(world.stepCount());
  const auto add = [&text](const auto& fields) {
    for (const auto& field : fields)
      text += "," + (field.text.empty() ? formatNumber(field.number) : field.text);
  };
  for (const auto& body : world.bodies()) {
    text += " " + body.name + ":";
    if (const auto* rod = std::get_if<Rod>(&body.model)) add(stateFields(*rod));
    if (const auto* roller = std::get_if<Roller>(&body.model)) add(stateFields(*roller));
  }
  return text;
}

std::string sampleLine(const World& world) { return "sample " + stateOf(world); }

std::string appliedLine(const WorldCommand& command, std::size_t index, const World& world) {
  return "applied " + std::to_string(index) + " " + toString(command.kind) + " at " +
         std::to_string(command.step) + " -> " + stateOf(world);
}

// What a session hands out, one line each.
class Recorder : public SampleSink {
 public:
  void write(const World& world) override { lines.push_back(sampleLine(world)); }
  void applied(const WorldCommand& command, std::size_t index, const World& world) override {
    lines.push_back(appliedLine(command, index, world));
  }
  void happened(const std::vector<BodyEvent>& happened, const World&) override {
    events.insert(events.end(), happened.begin(), happened.end());
  }
  std::vector<std::string> lines;
  std::vector<BodyEvent> events;
};

WorldCommand commandOf(WorldCommand::Kind kind, const std::string& body = "") {
  WorldCommand command;
  command.kind = kind;
  command.body = body;
  return command;
}

WorldCommand setState(const std::string& body, const std::string& field, double value) {
  WorldCommand command = commandOf(WorldCommand::Kind::SetState, body);
  command.state = {{field, value}};
  return command;
}

WorldCommand reset() { return commandOf(WorldCommand::Kind::Reset); }

WorldCommand spawn(const std::string& name) {
  WorldCommand command = commandOf(WorldCommand::Kind::Spawn, name);
  RollerConfig hoop;
  hoop.params.shape = Shape::Ring;
  hoop.params.inertia_factor = 1.0;
  hoop.initial.x0 = 0.5;
  command.config = {name, hoop};
  return command;
}

WorldCommand deleteOf(const std::string& body) { return commandOf(WorldCommand::Kind::Delete, body); }

// The truth: a plain World, changed by hand at its current step. Returns the command as applied.
WorldCommand applyNow(World& world, WorldCommand command) {
  command.step = world.stepCount();
  world.apply(command);
  return command;
}

void steps(World& world, int count) {
  for (int i = 0; i < count; ++i) world.step();
}

// A session of rodAndBall() sampled every kStepsPerSample steps into `recorder`.
struct Recorded {
  Recorded() : session(rodAndBall(), {}, kStepsPerSample) { session.addSink(recorder); }
  Recorder recorder;
  Session session;
};

}  // namespace

TEST(Session, AdvanceSamplesExactlyAtMultiplesOfItsPeriod) {
  Recorded run;
  std::vector<std::int64_t> hooked;
  const StepHook note_count = [&hooked](World& world) { hooked.push_back(world.stepCount()); };
  EXPECT_TRUE(run.session.sampleNow());
  run.session.advance(6, note_count);  // in pieces that end off the grid and on it
  run.session.advance(1, note_count);
  run.session.advance(5, note_count);
  run.session.advance(0, note_count);

  World truth(rodAndBall());
  std::vector<std::string> expected{sampleLine(truth)};
  for (int j = 1; j <= 3; ++j) {
    steps(truth, kStepsPerSample);
    expected.push_back(sampleLine(truth));
  }
  EXPECT_EQ(run.recorder.lines, expected);
  EXPECT_EQ(hooked, (std::vector<std::int64_t>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
  EXPECT_TRUE(run.session.sampled());
  run.session.advance();
  EXPECT_FALSE(run.session.sampled());
  EXPECT_FALSE(run.session.atSamplingInstant());
  EXPECT_EQ(run.recorder.lines.size(), 4u);
}

TEST(Session, CommandAtAnInstantNotYetSampledComesAfterTheSampleOfTheOldState) {
  Recorded run;
  WorldCommand lift = setState("rod", "y", 2.0);
  lift.step = 12345;  // the session sets the step it applies at
  EXPECT_EQ(run.session.apply(lift), 1u);

  World truth(rodAndBall());
  const std::string before = sampleLine(truth);
  const WorldCommand applied = applyNow(truth, lift);
  EXPECT_EQ(run.recorder.lines, (std::vector<std::string>{before, appliedLine(applied, 1, truth)}));
  EXPECT_FALSE(run.session.sampleNow());  // count 0 is handed out: never a second state at one t
}

TEST(Session, CommandAtACountAlreadySampledIsNotSampledAgain) {
  Recorded run;
  run.session.sampleNow();
  run.session.advance(kStepsPerSample);
  run.session.apply(reset());
  run.session.advance(kStepsPerSample);

  World truth(rodAndBall());
  std::vector<std::string> expected{sampleLine(truth)};
  steps(truth, kStepsPerSample);
  expected.push_back(sampleLine(truth));
  const WorldCommand applied = applyNow(truth, reset());
  expected.push_back(appliedLine(applied, 1, truth));
  steps(truth, kStepsPerSample);
  expected.push_back(sampleLine(truth));
  EXPECT_EQ(run.recorder.lines, expected);
}

TEST(Session, TwoCommandsAtOneCountOneSampleBothAppliedInOrder) {
  Recorded run;
  // At a pending instant: one sample, then both (the reset undoes the lift only in this order).
  const WorldCommand lift = setState("rod", "y", 2.0);
  EXPECT_EQ(run.session.apply(lift), 1u);
  EXPECT_EQ(run.session.apply(reset()), 2u);
  // Off the grid: no sample; the spawned body can only be moved after its spawn.
  run.session.advance(kStepsPerSample + 2);
  EXPECT_EQ(run.session.apply(spawn("hoop")), 3u);
  EXPECT_EQ(run.session.apply(setState("hoop", "v", 1.5)), 4u);
  run.session.advance(2);

  World truth(rodAndBall());
  std::vector<std::string> expected{sampleLine(truth)};
  std::size_t index = 0;
  const auto apply = [&](const WorldCommand& command) {
    const WorldCommand applied = applyNow(truth, command);
    expected.push_back(appliedLine(applied, ++index, truth));
  };
  apply(lift);
  apply(reset());
  steps(truth, kStepsPerSample);
  expected.push_back(sampleLine(truth));
  steps(truth, 2);
  apply(spawn("hoop"));
  apply(setState("hoop", "v", 1.5));
  steps(truth, 2);
  expected.push_back(sampleLine(truth));
  EXPECT_EQ(run.recorder.lines, expected);
}

TEST(Session, RefusalChangesNothingAndNoSinkHearsOfIt) {
  Recorded run;
  run.session.sampleNow();
  run.session.advance(2);
  const std::vector<std::string> lines = run.recorder.lines;
  EXPECT_THROW(run.session.apply(deleteOf("nope")), ConfigError);
  EXPECT_THROW(run.session.apply(setState("rod", "y", -1.0)), ConfigError);
  EXPECT_EQ(run.recorder.lines, lines);
  EXPECT_EQ(run.session.commandsApplied(), 0u);

  World truth(rodAndBall());
  steps(truth, 2);
  EXPECT_EQ(stateOf(run.session.world()), stateOf(truth));
  EXPECT_EQ(run.session.apply(reset()), 1u);  // the log has no gap
}

// The state of a pending instant is that count's whatever the command: handed out even when it is refused.
TEST(Session, RefusalAtAPendingInstantHandsOutOnlyTheSample) {
  Recorded run;
  EXPECT_THROW(run.session.apply(deleteOf("nope")), ConfigError);
  EXPECT_EQ(run.recorder.lines, (std::vector<std::string>{sampleLine(World(rodAndBall()))}));
}

TEST(Session, PausedCommandsStillApplyAndSampleNowHandsOutOnce) {
  Recorded run;
  run.session.sampleNow();
  run.session.advance(kStepsPerSample + 1);  // paused off the grid: the caller stops advancing
  const std::size_t before = run.recorder.lines.size();
  run.session.apply(setState("rod", "y", 2.0));
  run.session.apply(setState("ball", "v", 1.0));
  EXPECT_EQ(run.recorder.lines.size(), before + 2);  // applied, applied: no sample
  EXPECT_TRUE(run.session.sampleNow());              // what a ~step's end shows
  EXPECT_FALSE(run.session.sampleNow());
  run.session.apply(reset());
  EXPECT_FALSE(run.session.sampleNow());  // this count is handed out: the reset shows with the next step

  World truth(rodAndBall());
  steps(truth, kStepsPerSample + 1);
  applyNow(truth, setState("rod", "y", 2.0));
  applyNow(truth, setState("ball", "v", 1.0));
  EXPECT_EQ(run.recorder.lines[before + 2], sampleLine(truth));
  applyNow(truth, reset());
  steps(truth, kStepsPerSample - 1);
  run.session.advance(kStepsPerSample - 1);
  EXPECT_EQ(run.recorder.lines.back(), sampleLine(truth));
  EXPECT_EQ(run.recorder.lines.size(), before + 5);
}

TEST(Session, RefusesANonPositivePeriodAndStepsBack) {
  EXPECT_THROW(Session(rodAndBall(), {}, 0), std::invalid_argument);
  Recorded run;
  EXPECT_THROW(run.session.advance(-1), std::invalid_argument);
  EXPECT_EQ(run.session.world().stepCount(), 0);
}

using SessionReplay = FolderTest;

// Every command at its step; the CSV rows are the hand-run world's at every sampling instant, taken before
// the commands at that count.
TEST_F(SessionReplay, AppliesEveryCommandAtItsStep) {
  std::vector<WorldCommand> commands(1);
  commands[0].kind = WorldCommand::Kind::Config;
  commands[0].world = rodAndBall();
  const auto at = [&commands](std::int64_t step, WorldCommand command) {
    command.step = step;
    commands.push_back(command);
  };
  at(0, setState("rod", "vy", 1.5));
  at(6, spawn("hoop"));
  at(8, reset());
  at(8, setState("hoop", "x", 1.0));
  at(11, deleteOf("ball"));
  at(25, reset());  // after the duration: not applied
  OfflineOptions options;
  options.duration = 0.02;    // 20 steps at rate 1000
  options.sample_rate = 250;  // every 4 steps
  options.out_dir = dir_.string();
  const ReplaySummary summary = replayRun(commands, options);

  World truth(rodAndBall());
  std::map<std::string, std::string> files;
  std::size_t next = 1;
  for (std::int64_t count = 0; count <= 20; ++count) {
    for (const auto& body : truth.bodies()) {
      if (count % kStepsPerSample != 0) continue;
      if (!files.count(body.name)) files[body.name] = csvHeader(body) + "\n";  // a file from its first row
      files[body.name] += csvRow(truth.time(), body) + "\n";
    }
    for (; next < commands.size() && commands[next].step == count; ++next) truth.apply(commands[next]);
    if (count < 20) truth.step();
  }
  for (const auto& [name, text] : files) EXPECT_EQ(slurp(dir_ / (name + ".csv")), text) << name;
  EXPECT_EQ(summary.commands_applied, 5u);
  EXPECT_EQ(summary.steps, 20);
  EXPECT_EQ(summary.bodies, (std::vector<std::string>{"rod", "ball", "hoop"}));
}
