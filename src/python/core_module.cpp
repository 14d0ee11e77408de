// rigid_body_sim.core: the exact core from Python (pybind11). A World is a run Session (run/session.h) that
// Python steps, samples and changes through World::apply, as the node does; configs go through the config
// loader, runs through the offline run's sampling, sweeps through runSweep. Nothing here knows a body type:
// every body is visited through the variants, its fields and keys read from the core's tables.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "rigid_body_sim/core/description.h"
#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/io/config_loader.h"
#include "rigid_body_sim/io/config_writer.h"
#include "rigid_body_sim/run/offline_run.h"
#include "rigid_body_sim/run/sweep.h"

namespace py = pybind11;  // py::module, not module_: Noetic's pybind11 2.4 has only that name

namespace rigid_body_sim {

namespace {

// What Python gives as a config or a body: YAML text, or a dict dumped to YAML text by Python's yaml, so
// that both are read by the one loader.
std::string yamlText(const py::object& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    return py::module::import("yaml")
        .attr("safe_dump")(value, py::arg("default_flow_style") = true, py::arg("sort_keys") = false)
        .cast<std::string>();
  }
  throw py::type_error("expected YAML text (str) or a dict, not " +
                       std::string(Py_TYPE(value.ptr())->tp_name));
}

// A key's value from Python as a config file writes it: a number in its shortest round-trip form, a text as
// it is.
std::string keyText(const py::handle& value) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  return formatNumber(value.cast<double>());
}

// One body's samples: t and every state field, numbers or texts, in the table's order.
struct BodySamples {
  std::string name;
  std::vector<const char*> fields;
  std::vector<bool> is_text;
  std::vector<std::vector<double>> numbers;     // by field (empty for a text field)
  std::vector<std::vector<std::string>> texts;  // by field (empty for a number field)
};

py::dict valueDict(const std::vector<EventValue>& values) {
  py::dict out;
  for (const auto& value : values) {
    if (value.text.empty()) {
      out[py::str(value.name)] = value.number;
    } else {
      out[py::str(value.name)] = value.text;
    }
  }
  return out;
}

// Events as Python records: {"t", "body", "type", "kind", "values": {name: value}, "state": {field: value}}.
py::list eventRecords(const std::vector<BodyEvent>& events) {
  py::list out;
  for (const auto& event : events) {
    py::dict record;
    record["t"] = event.t;
    record["body"] = event.body;
    record["type"] = event.type;
    record["kind"] = event.kind;
    record["values"] = valueDict(event.values);
    record["state"] = valueDict(event.state);
    out.append(record);
  }
  return out;
}

void sample(const Body& body, BodySamples& out) {
  std::visit(
      [&](const auto& model) {
        const auto& table = stateFieldTable(model);
        if (out.fields.empty()) {
          out.name = body.name;
          for (const auto& def : table) {
            out.fields.push_back(def.name);
            out.is_text.push_back(def.text != nullptr);
          }
          out.numbers.resize(table.size());
          out.texts.resize(table.size());
        }
        const auto fields = stateFields(model);
        for (std::size_t k = 0; k < fields.size(); ++k) {
          if (out.is_text[k]) {
            out.texts[k].push_back(fields[k].text);
          } else {
            out.numbers[k].push_back(fields[k].number);
          }
        }
      },
      body.model);
}

py::array_t<double> toArray(const std::vector<double>& values) {
  py::array_t<double> array(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), array.mutable_data());
  return array;
}

py::object toArray(const std::vector<std::string>& values) {
  return py::module::import("numpy").attr("array")(py::cast(values), py::arg("dtype") = "str");
}

// {field: value} of a body now.
py::dict stateDict(const Body& body) {
  py::dict state;
  std::visit(
      [&](const auto& model) {
        for (const auto& field : stateFields(model)) {
          if (field.text.empty()) {
            state[field.name] = field.number;
          } else {
            state[field.name] = field.text;
          }
        }
      },
      body.model);
  return state;
}

// The one exported description of the body types (core/description.h), the document describe_body_types
// writes into body_types.json, parsed by Python's json: the same dicts and lists json.load gives of the file.
py::object bodyTypes() { return py::module::import("json").attr("loads")(bodyTypesJson()); }

// The bag writer of `simulate --bag` (ros/bag_recorder.h), from rigid_body_sim._bag: that module links the
// ros layer, this one does not, so that a World without a bag loads no ROS library (simulate hands a run with
// --bag over to simulate_ros the same way).
SinkOpener bagOpener() {
  static const char* const kName = "rigid_body_sim.SinkOpener";
  const py::object capsule = py::module::import("rigid_body_sim._bag").attr("opener")();
  void* const opener = PyCapsule_GetPointer(capsule.ptr(), kName);
  if (!opener) throw py::error_already_set();
  return *static_cast<const SinkOpener*>(opener);
}

// The CSV text of a sweep as arrays by column: numbers as float64 (an empty cell, a roller that never went
// from slipping to rolling, as nan), a column with a text in it as str.
py::dict sweepColumns(const std::string& csv) {
  std::istringstream lines(csv);
  std::string line;
  std::vector<std::string> header;
  std::getline(lines, line);
  for (std::istringstream cells(line); std::getline(cells, line, ',');) header.push_back(line);
  std::vector<std::vector<std::string>> cells(header.size());
  while (std::getline(lines, line)) {
    std::istringstream row(line);
    for (auto& column : cells) {
      std::string cell;
      std::getline(row, cell, ',');
      column.push_back(cell);
    }
  }
  py::dict out;
  for (std::size_t c = 0; c < header.size(); ++c) {
    std::vector<double> numbers;
    bool all_numbers = true;
    for (const auto& cell : cells[c]) {
      char* end = nullptr;
      const double value = std::strtod(cell.c_str(), &end);
      if (cell.empty()) {
        numbers.push_back(NAN);
      } else if (end == cell.c_str() + cell.size()) {
        numbers.push_back(value);
      } else {
        all_numbers = false;
        break;
      }
    }
    out[py::str(header[c])] = all_numbers ? py::object(toArray(numbers)) : toArray(cells[c]);
  }
  return out;
}

// A folder of its own under the system's temporary folder, removed with it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "rigid_body_sim_sweep.XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary folder for the sweep");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

class PyWorld {
 public:
  // The loader's refusal (the line `simulate --check` prints after "simulate: ") is a ValueError.
  explicit PyWorld(const py::object& config)
      : loaded_(load(config)), session_(loaded_, node_interface::ownNames(), 1) {}

  double t() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return session_.world().time();
  }
  std::int64_t steps() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return session_.world().stepCount();
  }
  double dt() const { return session_.world().dt(); }  // fixed by the config

  std::vector<std::string> bodies() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> names;
    for (const auto& body : session_.world().bodies()) names.push_back(body.name);
    return names;
  }

  void step(std::int64_t n) {
    if (n < 0) throw py::value_error("cannot step " + std::to_string(n) + " steps");
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    session_.advance(n);
  }

  // The events handed out since the last call (steps, runs, changes), oldest first, as records.
  py::list events() {
    std::vector<BodyEvent> taken;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      taken.swap(unread_);
      std::vector<BodyEvent> newer = session_.takeEvents();
      taken.insert(taken.end(), newer.begin(), newer.end());
    }
    return eventRecords(taken);
  }

  py::dict state(const std::string& name) {
    std::lock_guard<std::mutex> lock(mutex_);
    return stateDict(body(name));
  }

  // Samples every body at t now and every rate / sample_rate steps for `duration` s, as `simulate` samples
  // from t = 0: options checked as its options (one line), the last sample at the last multiple of
  // 1 / sample_rate not after the duration. With a bag path, writes at every sample what `simulate --bag`
  // writes (through the same BagRecorder), from a World as loaded: its config, then its states from t = 0.
  py::object run(double duration, std::optional<double> sample_rate, const py::object& bag,
                 bool with_events) {
    std::string bag_path;
    SinkOpener open_bag;
    if (!bag.is_none()) {
      bag_path = py::module::import("os").attr("fspath")(bag).cast<std::string>();
      open_bag = bagOpener();  // imported with the GIL held
    }
    std::vector<BodySamples> bodies;
    std::vector<double> times;
    std::vector<BodyEvent> happened;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      OfflineOptions options;
      options.duration = duration;
      options.sample_rate = sample_rate.value_or(0.0);
      const WorldConfig& config = session_.world().config();
      try {
        validate(options, config);
      } catch (const ConfigError& error) {
        throw py::value_error(error.what());
      }
      const World& world = session_.world();
      if (!bag_path.empty() && (world.stepCount() != 0 || session_.commandsApplied() != 0)) {
        throw py::value_error(
            "a bag is the run of a World as loaded (t = 0, nothing changed), as simulate "
            "--bag writes it; this one is at t = " +
            formatNumber(world.time()) + " after " + std::to_string(session_.commandsApplied()) +
            " change(s)");
      }
      // Opened before the first sample, with the config as loaded: simulate's RunFiles opens it so.
      const std::unique_ptr<SampleSink> sink = openSink(bag_path, loaded_, world.bodies(), open_bag);
      const std::int64_t every = stepsPerSample(options, config);
      const std::int64_t last = lastSample(config, options);
      bodies.resize(world.bodies().size());
      times.reserve(static_cast<std::size_t>(last + 1));
      for (std::int64_t j = 0; j <= last; ++j) {
        if (j > 0) session_.advance(every);
        std::vector<BodyEvent> events = session_.takeEvents();
        if (sink && !events.empty()) sink->happened(events, world);
        happened.insert(happened.end(), events.begin(), events.end());
        times.push_back(world.time());
        for (std::size_t b = 0; b < bodies.size(); ++b) sample(world.bodies()[b], bodies[b]);
        if (sink) sink->write(world);
      }
      if (sink) sink->commit();
      if (!with_events) unread_.insert(unread_.end(), happened.begin(), happened.end());  // for events()
    }
    py::dict out;
    for (const auto& body : bodies) {
      py::dict fields;
      fields["t"] = toArray(times);
      for (std::size_t k = 0; k < body.fields.size(); ++k) {
        fields[body.fields[k]] =
            body.is_text[k] ? toArray(body.texts[k]) : py::object(toArray(body.numbers[k]));
      }
      out[py::str(body.name)] = fields;
    }
    if (!with_events) return std::move(out);
    return py::make_tuple(out, eventRecords(happened));
  }

  // The changes of the node's services and reconfigure servers, through the one path (Session::apply).
  void set(const std::string& name, const py::kwargs& keys) {
    std::vector<KeyText> texts;
    for (const auto& [key, value] : keys)
      texts.push_back({key.cast<std::string>(), keyText(value), py::isinstance<py::str>(value)});
    change(WorldCommand::Kind::Reconfigure, name, [&](const World& world, WorldCommand& command) {
      command.config = withKeys(bodyConfig(world, name), texts);
    });
  }

  void setState(const std::string& name, const py::kwargs& fields) {
    std::vector<StateValue> state;
    for (const auto& [field, value] : fields)
      state.push_back({field.cast<std::string>(), value.cast<double>()});
    change(WorldCommand::Kind::SetState, name,
           [&](const World&, WorldCommand& command) { command.state = state; });
  }

  void spawn(const std::string& name, const py::object& body) {
    const std::string text = yamlText(body);
    change(WorldCommand::Kind::Spawn, name,
           [&](const World&, WorldCommand& command) { command.config = parseBodyText(name, text); });
  }

  void remove(const std::string& name) {
    change(WorldCommand::Kind::Delete, name, [](const World&, WorldCommand&) {});
  }

  void reset() {
    change(WorldCommand::Kind::Reset, "", [](const World&, WorldCommand&) {});
  }

  // What ~get_config returns: the world as it runs, a config file sim_node and simulate load as it is.
  std::string config() {
    std::lock_guard<std::mutex> lock(mutex_);
    return toYaml(session_.world().config());
  }

  // simulate CONFIG --sweep SPEC ... on the running world's config: runSweep's own run and file, read back.
  py::dict sweep(const std::vector<std::string>& specs, double duration, std::optional<double> sample_rate,
                 unsigned jobs) {
    std::string csv;
    {
      py::gil_scoped_release release;
      WorldConfig base;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        base = session_.world().config();
      }
      TempDir dir;
      OfflineOptions options;
      options.duration = duration;
      options.sample_rate = sample_rate.value_or(0.0);
      options.out_dir = dir.path();
      SweepOptions sweep;
      sweep.jobs = jobs;
      try {
        for (const auto& spec : specs) sweep.axes.push_back(parseSweepAxis(spec, base));
        const SweepResult result = runSweep(base, sweep, options);
        std::ifstream file(result.path);
        csv.assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
      } catch (const ConfigError& error) {
        throw py::value_error(error.what());
      }
    }
    return sweepColumns(csv);
  }

 private:
  static WorldConfig load(const py::object& config) {
    try {
      if (py::isinstance(config, py::module::import("os").attr("PathLike"))) {
        return loadWorldConfigFile(py::module::import("os").attr("fspath")(config).cast<std::string>());
      }
      return parseWorldConfigText(yamlText(config), "(python)");
    } catch (const ConfigError& error) {
      throw py::value_error(error.what());
    }
  }

  const Body& body(const std::string& name) const {
    for (const auto& body : session_.world().bodies()) {
      if (body.name == name) return body;
    }
    throw py::key_error("no body named '" + name + "'");
  }

  static const BodyConfig& bodyConfig(const World& world, const std::string& name) {
    for (const auto& body : world.config().bodies) {
      if (body.name == name) return body;
    }
    throw ConfigError(name, "name", "'" + name + "'", "a body of the world");
  }

  // The body's config with `keys` set as a reconfigure request sets them: in the order of its type's keys (a
  // roller's shape before its inertia_factor), each read from its text as a config file's.
  // A key's value from Python as text; `quoted` when it came as a str, which a number key refuses as it
  // refuses a quoted value in a file.
  struct KeyText {
    std::string name;
    std::string text;
    bool quoted;
  };
  static BodyConfig withKeys(BodyConfig body, const std::vector<KeyText>& keys) {
    std::visit(
        [&](auto& config) {
          using Config = std::decay_t<decltype(config)>;
          const auto& type = bodyType<Config>();
          for (const auto& [name, text, quoted] : keys) {
            if (!findKey(type.keys, name)) {
              std::vector<std::string> known;
              for (const auto& key : type.keys) known.emplace_back(key.name);
              throw ConfigError(body.name, name, "'" + text + "'",
                                "no such key; known keys: " + oneOf(known));
            }
          }
          for (const auto& key : type.keys) {
            for (const auto& [name, text, quoted] : keys) {
              if (name != key.name) continue;
              if (quoted && key.isNumber()) throw quotedTextRefusal(body.name, name, text, key.allowed());
              setKeyText(body.name, key, text, config);
            }
          }
        },
        body.config);
    return body;
  }

  // Builds the command on the running world and applies it; a refusal is a ValueError with the node's line
  // and leaves the world as it was.
  template <class Build>
  void change(WorldCommand::Kind kind, const std::string& name, const Build& build) {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    try {
      WorldCommand command;
      command.kind = kind;
      command.body = name;
      build(session_.world(), command);
      session_.apply(command);
    } catch (const ConfigError& error) {
      throw py::value_error(refusalLine(toString(kind), name, error.what()));
    }
  }

  const WorldConfig loaded_;  // the config as loaded: the one a bag starts with
  Session session_;
  std::vector<BodyEvent> unread_;  // a run's events, until events() reads them
  mutable std::mutex mutex_;       // a world used from several Python threads: one call at a time
};

}  // namespace

}  // namespace rigid_body_sim

PYBIND11_MODULE(core, m) {
  using rigid_body_sim::PyWorld;
  m.doc() =
      "The exact core of rigid_body_sim: worlds run, changed and swept as simulate and sim_node do them.";

  py::class_<PyWorld>(m, "World",
                      "A world of bodies on one clock, from a config (YAML text, a dict or a path).")
      .def(py::init<const py::object&>(), py::arg("config"))
      .def_property_readonly("t", &PyWorld::t, "simulated time (s): the step count over rate")
      .def_property_readonly("steps", &PyWorld::steps, "steps taken")
      .def_property_readonly("dt", &PyWorld::dt, "the step (s): 1 / rate")
      .def_property_readonly("bodies", &PyWorld::bodies, "the bodies' names, in order")
      .def("step", &PyWorld::step, py::arg("n") = 1, "take n steps")
      .def("state", &PyWorld::state, py::arg("name"), "{field: value} of a body now (the CSV's columns)")
      .def(
          "run", &PyWorld::run, py::arg("duration") = 10.0, py::arg("sample_rate") = py::none(),
          py::arg("bag") = py::none(), py::arg("events") = false,
          "step `duration` s, sampling every body now and at every 1 / sample_rate (None: publish_rate): "
          "{body: {field: numpy array}}, simulate's CSV columns bit for bit; with `bag` (a path), from a "
          "World as loaded, also the bag simulate --bag writes; with events=True, (samples, the run's events "
          "as events() gives them), events.csv's rows")
      .def("events", &PyWorld::events,
           "what happened since the last call (steps, runs, changes), oldest first: [{\"t\", \"body\", "
           "\"type\", \"kind\", \"values\": {name: value}, \"state\": {field: value}}], the exact instants")
      .def("set", &PyWorld::set, py::arg("name"), "set keys of a body, as a reconfigure does")
      .def("set_state", &PyWorld::setState, py::arg("name"), "move a body now (settable state fields)")
      .def("spawn", &PyWorld::spawn, py::arg("name"), py::arg("body"), "a new body (YAML map text or dict)")
      .def("delete", &PyWorld::remove, py::arg("name"), "a body away")
      .def("reset", &PyWorld::reset, "every body back to its initial conditions; time goes on")
      .def("config", &PyWorld::config, "the world as it runs, as a config file (~get_config's text)")
      .def("sweep", &PyWorld::sweep, py::arg("specs"), py::arg("duration") = 10.0,
           py::arg("sample_rate") = py::none(), py::arg("jobs") = 0u,
           "simulate --sweep BODY.KEY=START:STOP:N ... on this world's config, on `jobs` threads (0: every "
           "core): {column: numpy array}, sweep.csv's columns");

  m.def("body_types", &rigid_body_sim::bodyTypes,
        "the body types' description, the document of body_types.json as json.load reads it: {\"types\": "
        "{type: {\"keys\": [...], \"state_fields\": [...], ...}}, \"world\": [...], \"max_bodies\": n}");
}
