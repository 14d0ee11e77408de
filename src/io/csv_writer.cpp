#include "rigid_body_sim/io/csv_writer.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "rigid_body_sim/core/state_fields.h"

namespace rigid_body_sim {

namespace {

template <std::size_t N>
std::string joinFields(double t, const std::array<StateField, N>& fields) {
  std::string row = formatNumber(t);
  for (const auto& field : fields)
    row += ',' + (field.text.empty() ? formatNumber(field.number) : field.text);
  return row;
}

// "omega = nan" for the first state field of `body` that is not finite, or empty: a CSV never holds nan or
// inf (the offline run has no NaN guard: validation leaves no known path there, and this catches any other).
std::string nonFiniteField(const Body& body) {
  return std::visit(
      [](const auto& model) {
        for (const auto& field : stateFields(model)) {
          if (field.text.empty() && !std::isfinite(field.number))
            return std::string(field.name) + " = " + formatNumber(field.number);
        }
        return std::string();
      },
      body.model);
}

}  // namespace

std::string csvHeader(const Body& body) {
  std::string header = "t";
  for (const auto& name : stateFieldNames(body)) header += "," + name;
  return header;
}

std::string csvRow(double t, const Body& body) {
  return std::visit([t](const auto& model) { return joinFields(t, stateFields(model)); }, body.model);
}

std::string eventsCsvHeader() { return "t,body,type,kind,values,state"; }

namespace {
std::string pairs(const std::vector<EventValue>& values) {
  std::string out;
  for (const auto& value : values) {
    out += (out.empty() ? "" : " ") + value.name + "=" +
           (value.text.empty() ? formatNumber(value.number) : value.text);
  }
  return out;
}
}  // namespace

std::string eventsCsvRow(const BodyEvent& event) {
  return formatNumber(event.t) + ',' + event.body + ',' + event.type + ',' + event.kind + ',' +
         pairs(event.values) + ',' + pairs(event.state);
}

CsvWriter::File CsvWriter::open(const std::string& file_name, const std::string& header) const {
  File file;
  file.final_path = (std::filesystem::path(out_dir_) / file_name).string();
  file.temp_path = file.final_path + ".tmp";
  file.stream = std::make_unique<std::ofstream>(file.temp_path);
  if (!*file.stream) throw std::runtime_error("cannot write '" + file.temp_path + "'");
  *file.stream << header << '\n';
  return file;
}

CsvWriter::CsvWriter(const std::string& out_dir, const std::vector<Body>& bodies) : out_dir_(out_dir) {
  std::filesystem::create_directories(out_dir);
  try {
    events_ = open(kEventsFile, eventsCsvHeader());
    for (const auto& body : bodies) fileOf(body);
  } catch (...) {
    removeTemporaries();  // no destructor runs for a constructor that throws
    throw;
  }
}

CsvWriter::File& CsvWriter::fileOf(const Body& body) {
  for (auto& file : files_) {
    if (file.name != body.name) continue;
    if (file.type != body.model.index()) {
      throw std::runtime_error("body '" + body.name + "' comes back as another type: its CSV has one header");
    }
    return file;
  }
  File file = open(body.name + ".csv", csvHeader(body));
  file.name = body.name;
  file.type = body.model.index();
  files_.push_back(std::move(file));
  return files_.back();
}

CsvWriter::~CsvWriter() {
  if (!committed_) removeTemporaries();
}

void CsvWriter::removeTemporaries() {
  for (File* file : all()) {
    file->stream->close();
    std::error_code ignored;
    std::filesystem::remove(file->temp_path, ignored);
  }
}

std::vector<CsvWriter::File*> CsvWriter::all() {
  std::vector<File*> files;
  if (events_.stream) files.push_back(&events_);
  for (auto& file : files_) files.push_back(&file);
  return files;
}

void CsvWriter::write(const std::vector<BodyEvent>& events) {
  for (const auto& event : events) *events_.stream << eventsCsvRow(event) << '\n';
}

void CsvWriter::write(double t, const std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    // The files of a run whose bodies never change are the bodies, in order: no look-up.
    const bool same =
        i < files_.size() && files_[i].name == bodies[i].name && files_[i].type == bodies[i].model.index();
    File& file = same ? files_[i] : fileOf(bodies[i]);
    const std::string bad = nonFiniteField(bodies[i]);
    if (!bad.empty()) {
      throw std::runtime_error("body '" + bodies[i].name + "' became non-finite by t = " + formatNumber(t) +
                               " s (" + bad + "): stopped, no file written");
    }
    *file.stream << csvRow(t, bodies[i]) << '\n';
  }
}

void CsvWriter::commit() {
  for (File* file : all()) {
    file->stream->close();
    if (file->stream->fail()) throw std::runtime_error("cannot write '" + file->temp_path + "'");
    std::filesystem::rename(file->temp_path, file->final_path);
  }
  committed_ = true;
}

}  // namespace rigid_body_sim
