// The state messages against the core's list of fields (core/state_fields.h): after header and t, the
// fields of RodState and RollerState are the CSV's columns in the CSV's order, with the same values.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/ros/messages.h"

using namespace rigid_body_sim;

namespace {

// The field names of a message definition: its own lines (before the definitions of nested types), without
// comments and constants (NAME=value).
std::vector<std::string> fieldsOf(const std::string& definition) {
  std::vector<std::string> names;
  std::istringstream lines(definition);
  for (std::string line; std::getline(lines, line) && line.rfind("===", 0) != 0;) {
    std::istringstream words(line);
    std::string type;
    std::string name;
    if (words >> type >> name && type[0] != '#' && name.find('=') == std::string::npos) names.push_back(name);
  }
  return names;
}

std::vector<std::string> expectedFields(BodyKind kind) {
  std::vector<std::string> names = {"header", "t"};
  for (const auto& name : stateFieldNames(kind)) names.push_back(name);
  return names;
}

World demoWorld() {
  WorldConfig config;
  RollerConfig ball;
  ball.initial.v0 = 3.0;  // slipping first
  config.bodies = {{"rod", RodConfig{}}, {"ball", ball}};
  World world(config);
  for (int i = 0; i < 1234; ++i) world.step();
  return world;
}

}  // namespace

TEST(StateMessages, FieldsAreTheCoreListInItsOrder) {
  EXPECT_EQ(fieldsOf(ros::message_traits::definition<RodState>()), expectedFields(BodyKind::Rod));
  EXPECT_EQ(fieldsOf(ros::message_traits::definition<RollerState>()), expectedFields(BodyKind::Roller));
}

TEST(StateMessages, CarryTheValuesOfTheCoreFields) {
  const World world = demoWorld();
  const Rod& rod = std::get<Rod>(world.bodies()[0].model);
  const RodState rod_msg = toRodStateMsg(world.time(), rod);
  const auto rod_fields = stateFields(rod);
  const double rod_values[] = {rod_msg.x,  rod_msg.y,     rod_msg.theta, rod_msg.vx,
                               rod_msg.vy, rod_msg.omega, rod_msg.energy};
  for (std::size_t i = 0; i < rod_fields.size(); ++i) EXPECT_EQ(rod_values[i], rod_fields[i].number) << i;

  const Roller& ball = std::get<Roller>(world.bodies()[1].model);
  const RollerState ball_msg = toRollerStateMsg(world.time(), ball);
  const auto ball_fields = stateFields(ball);
  const double ball_values[] = {ball_msg.x, ball_msg.v,        ball_msg.theta,  ball_msg.omega,
                                0.0,        ball_msg.friction, ball_msg.normal, ball_msg.energy};
  for (std::size_t i = 0; i < ball_fields.size(); ++i) {
    if (ball_fields[i].text.empty()) EXPECT_EQ(ball_values[i], ball_fields[i].number) << i;
  }
  EXPECT_EQ(ball_msg.mode, ball_fields[4].text);
  EXPECT_EQ(rod_msg.t, world.time());
}
