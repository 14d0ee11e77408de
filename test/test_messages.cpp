// The state messages against the core's table of fields (core/state_fields.h): after header and t, the
// fields of RodState and RollerState are the CSV's columns in the CSV's order, of the table's types (a text
// is a string) and units (the unit closing a field's comment), with the same values.
#include <gtest/gtest.h>

#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/ros/messages.h"

using namespace rigid_body_sim;

namespace {

// A field of a message definition: its type, its name and the unit its comment gives (" (m)"), or "".
struct MsgField {
  std::string type;
  std::string name;
  std::string unit;
  bool operator==(const MsgField& other) const {
    return type == other.type && name == other.name && unit == other.unit;
  }
};

std::ostream& operator<<(std::ostream& out, const MsgField& field) {
  return out << field.type << ' ' << field.name << " (" << field.unit << ')';
}

// The fields of a message definition: its own lines (before the definitions of nested types), without
// comments and constants (NAME=value).
std::vector<MsgField> fieldsOf(const std::string& definition) {
  std::vector<MsgField> fields;
  std::istringstream lines(definition);
  for (std::string line; std::getline(lines, line) && line.rfind("===", 0) != 0;) {
    std::istringstream words(line);
    MsgField field;
    if (!(words >> field.type >> field.name) || field.type[0] == '#' ||
        field.name.find('=') != std::string::npos) {
      continue;
    }
    // The unit: " (unit)" closing the comment or its first clause (before a ';').
    const std::size_t comment = line.find('#');
    const std::size_t end =
        line.find(';', comment) == std::string::npos ? line.size() : line.find(';', comment);
    const std::size_t open = line.rfind(" (", end);
    if (comment != std::string::npos && open != std::string::npos && open > comment && line[end - 1] == ')') {
      field.unit = line.substr(open + 2, end - open - 3);
    }
    fields.push_back(field);
  }
  return fields;
}

template <class Table>
std::vector<MsgField> expectedFields(const Table& table) {
  std::vector<MsgField> fields = {{"Header", "header", ""}, {"float64", "t", "s"}};
  for (const auto& field : table)
    fields.push_back({field.text ? "string" : "float64", field.name, field.unit});
  return fields;
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

TEST(StateMessages, FieldsAreTheCoreTableInItsOrderWithItsTypesAndUnits) {
  EXPECT_EQ(fieldsOf(ros::message_traits::definition<RodState>()), expectedFields(RodType::kStateFields));
  EXPECT_EQ(fieldsOf(ros::message_traits::definition<RollerState>()),
            expectedFields(RollerType::kStateFields));
}

TEST(StateMessages, CarryTheValuesOfTheCoreFields) {
  const World world = demoWorld();
  const Rod& rod = std::get<Rod>(world.bodies()[0].model);
  const RodState rod_msg = toStateMsg(world.time(), rod);
  const auto rod_fields = stateFields(rod);
  const double rod_values[] = {rod_msg.x,  rod_msg.y,     rod_msg.theta, rod_msg.vx,
                               rod_msg.vy, rod_msg.omega, rod_msg.energy};
  for (std::size_t i = 0; i < rod_fields.size(); ++i) EXPECT_EQ(rod_values[i], rod_fields[i].number) << i;

  const Roller& ball = std::get<Roller>(world.bodies()[1].model);
  const RollerState ball_msg = toStateMsg(world.time(), ball);
  const auto ball_fields = stateFields(ball);
  const double ball_values[] = {ball_msg.x, ball_msg.v,        ball_msg.theta,  ball_msg.omega,
                                0.0,        ball_msg.friction, ball_msg.normal, ball_msg.energy};
  for (std::size_t i = 0; i < ball_fields.size(); ++i) {
    if (ball_fields[i].text.empty()) EXPECT_EQ(ball_values[i], ball_fields[i].number) << i;
  }
  EXPECT_EQ(ball_msg.mode, ball_fields[4].text);
  EXPECT_EQ(rod_msg.t, world.time());
}
