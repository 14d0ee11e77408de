// The state messages against the core's table of fields (core/state_fields.h), for every body type: after
// header and t, the fields of its message are the CSV's columns in the CSV's order, of the table's types (a
// text is a string) and units (the unit closing a field's comment), and a message's bytes carry the values.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <ostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
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

// A world of one body of `Type`, launched fast enough to slip (a round body) and stepped a while.
template <class Type>
World oneBodyWorld() {
  WorldConfig config;
  typename Type::Config body{};
  if constexpr (std::is_same_v<Type, RollerType>) body.initial.v0 = 3.0;  // slipping first
  config.bodies = {{"body", body}};
  World world(config);
  for (int i = 0; i < 1234; ++i) world.step();
  return world;
}

// A message's fields after its header, read back from its serialized bytes by its definition: {name: the
// number, or the text}. What a subscriber reads, whatever code filled the message.
std::vector<std::pair<std::string, StateField>> readBack(const std::string& definition,
                                                         const std::vector<std::uint8_t>& bytes) {
  std::vector<std::pair<std::string, StateField>> fields;
  std::size_t at = 0;
  const auto take = [&](void* out, std::size_t n) {
    std::memcpy(out, bytes.data() + at, n);
    at += n;
  };
  const auto text = [&] {
    std::uint32_t length = 0;
    take(&length, 4);
    std::string value(reinterpret_cast<const char*>(bytes.data() + at), length);
    at += length;
    return value;
  };
  for (const MsgField& field : fieldsOf(definition)) {
    StateField value{""};
    if (field.type == "Header") {
      at += 12;  // seq, stamp
      text();    // frame_id
      continue;
    }
    if (field.type == "string") {
      value.text = text();
    } else {
      take(&value.number, 8);
    }
    fields.emplace_back(field.name, value);
  }
  EXPECT_EQ(at, bytes.size());
  return fields;
}

}  // namespace

TEST(StateMessages, FieldsAreTheCoreTableInItsOrderWithItsTypesAndUnits) {
  BodyTypes::forEach([](auto type) {
    using Type = decltype(type);
    using Msg = typename RosMessages<Type>::StateMsg;
    EXPECT_EQ(fieldsOf(ros::message_traits::definition<Msg>()), expectedFields(Type::kStateFields))
        << Type::kName;
  });
}

TEST(StateMessages, CarryTheValuesOfTheCoreFields) {
  BodyTypes::forEach([](auto type) {
    using Type = decltype(type);
    using Msg = typename RosMessages<Type>::StateMsg;
    const World world = oneBodyWorld<Type>();
    const auto& model = std::get<typename Type::Model>(world.bodies()[0].model);
    const Msg msg = toStateMsg(world.time(), model);
    std::vector<std::uint8_t> bytes(ros::serialization::serializationLength(msg));
    ros::serialization::OStream out(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    ros::serialization::serialize(out, msg);
    const auto sent = readBack(ros::message_traits::definition<Msg>(), bytes);
    const auto fields = stateFields(model);
    ASSERT_EQ(sent.size(), fields.size() + 1) << Type::kName;
    EXPECT_EQ(sent[0].first, "t");
    EXPECT_EQ(sent[0].second.number, world.time()) << Type::kName;
    for (std::size_t i = 0; i < fields.size(); ++i) {
      EXPECT_EQ(sent[i + 1].first, fields[i].name) << Type::kName;
      EXPECT_EQ(sent[i + 1].second.text, fields[i].text) << Type::kName << ' ' << fields[i].name;
      if (fields[i].text.empty())
        EXPECT_EQ(sent[i + 1].second.number, fields[i].number) << Type::kName << ' ' << fields[i].name;
    }
  });
}
