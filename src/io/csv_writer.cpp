#include "rigid_body_sim/io/csv_writer.h"

#include <filesystem>
#include <stdexcept>

namespace rigid_body_sim {

namespace {

std::string joinNumbers(std::initializer_list<double> values) {
  std::string row;
  for (const double value : values) {
    if (!row.empty()) row += ',';
    row += formatNumber(value);
  }
  return row;
}

std::string rodRow(double t, const Rod& rod) {
  const auto& s = rod.state();
  return joinNumbers({t, s.x, s.y, s.theta, s.vx, s.vy, s.omega, rod.energy()});
}

std::string rollerRow(double t, const Roller& roller) {
  const auto& s = roller.state();
  return joinNumbers({t, s.x, s.v, s.theta, s.omega}) + "," + toString(roller.mode()) + "," +
         joinNumbers({roller.frictionForce(), roller.normalForce(), roller.energy()});
}

}  // namespace

std::string csvHeader(const Body& body) {
  if (std::holds_alternative<Rod>(body.model)) return "t,x,y,theta,vx,vy,omega,energy";
  return "t,x,v,theta,omega,mode,friction,normal,energy";
}

std::string csvRow(double t, const Body& body) {
  if (const auto* rod = std::get_if<Rod>(&body.model)) return rodRow(t, *rod);
  return rollerRow(t, std::get<Roller>(body.model));
}

CsvWriter::CsvWriter(const std::string& out_dir, const std::vector<Body>& bodies) {
  std::filesystem::create_directories(out_dir);
  for (const auto& body : bodies) {
    File file;
    file.final_path = (std::filesystem::path(out_dir) / (body.name + ".csv")).string();
    file.temp_path = file.final_path + ".tmp";
    file.stream = std::make_unique<std::ofstream>(file.temp_path);
    if (!*file.stream) throw std::runtime_error("cannot write '" + file.temp_path + "'");
    *file.stream << csvHeader(body) << '\n';
    files_.push_back(std::move(file));
  }
}

CsvWriter::~CsvWriter() {
  if (committed_) return;
  for (auto& file : files_) {
    file.stream->close();
    std::error_code ignored;
    std::filesystem::remove(file.temp_path, ignored);
  }
}

void CsvWriter::write(double t, const std::vector<Body>& bodies) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    *files_[i].stream << csvRow(t, bodies[i]) << '\n';
  }
}

void CsvWriter::commit() {
  for (auto& file : files_) {
    file.stream->close();
    if (file.stream->fail()) throw std::runtime_error("cannot write '" + file.temp_path + "'");
    std::filesystem::rename(file.temp_path, file.final_path);
  }
  committed_ = true;
}

}  // namespace rigid_body_sim
