// What happened to a body, as data: each body type declares the kinds of event its bodies have
// (Type::kEventKinds, in its own files); a model's step tells which happened and where inside the step, with
// the model's progress at that instant; the world turns them into BodyEvents (with the body's state fields
// at that instant) and collects them. Every face (topic, bag, CSV, Python, the panel, the page) reads these.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace rigid_body_sim {

// What the world does with an event of a kind, beside collecting it. The world reads roles, never names.
enum class EventRole {
  None,
  Finish,   // the centre passed an end of its track: a lap's time (and, in a race, its place)
  Restart,  // back to its initial conditions: a new lap starts at this instant
};

// One kind of event of a body type: its name (as topics, CSV files and Python give it) and what it means.
struct EventKind {
  const char* name;
  const char* meaning;
  EventRole role = EventRole::None;
};

// A number or a text that an event carries: a state field at its instant, or what its kind adds.
struct EventValue {
  std::string name;
  double number = 0.0;
  std::string text = {};  // not empty for a text (a mode, a rod's end)
};

struct BodyEvent {
  double t = 0.0;  // simulated s since the start: the exact instant (closed form, or the end of the step)
  std::string body;
  std::string type;                // the body's type name
  std::string kind;                // a name of its type's kEventKinds
  std::vector<EventValue> state;   // the body's state fields at t, in its table's order
  std::vector<EventValue> values;  // what the kind adds: a finish's lap_time, speed, place, closed_form ...
};

// A value among an event's values or state fields by name; null when it has none of that name.
const EventValue* findValue(const std::vector<EventValue>& values, const std::string& name);

// What one step of a model tells: up to kMax events, each as the index of its kind in the type's
// kEventKinds, its offset in [0, dt] into the step, the model's progress at that instant and what the kind
// adds. Fixed in size: a step with no event costs a counter.
template <class Progress>
struct StepEvents {
  static constexpr std::size_t kMax = 4;
  struct Entry {
    std::size_t kind;
    double offset;
    Progress at;
    const char* value_name = nullptr;  // one text value the kind adds ("end" of a rod), or none
    const char* value_text = nullptr;
  };
  std::array<Entry, kMax> entries{};
  std::size_t count = 0;

  void add(std::size_t kind, double offset, const Progress& at, const char* value_name = nullptr,
           const char* value_text = nullptr) {
    if (count < kMax) entries[count++] = Entry{kind, offset, at, value_name, value_text};
  }
  bool empty() const { return count == 0; }
  const Entry* begin() const { return entries.data(); }
  const Entry* end() const { return entries.data() + count; }
};

// The index of the kind named `name` in a type's kEventKinds (a compile-time lookup for the type's own
// files); kinds.size() when there is none of that name.
template <std::size_t N>
constexpr std::size_t kindIndex(const std::array<EventKind, N>& kinds, const char* name) {
  for (std::size_t i = 0; i < N; ++i) {
    const char* a = kinds[i].name;
    const char* b = name;
    while (*a != '\0' && *a == *b) ++a, ++b;
    if (*a == *b) return i;
  }
  return N;
}

}  // namespace rigid_body_sim
