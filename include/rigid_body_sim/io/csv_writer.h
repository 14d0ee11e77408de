// One CSV file per body, in the contract's columns, and events.csv: what happened, an event a row. Files are
// written under a temporary name and renamed when complete, so that a failed run never leaves a
// half-written file behind.
#pragma once

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "rigid_body_sim/core/world.h"

namespace rigid_body_sim {

std::string csvHeader(const Body& body);
std::string csvRow(double t, const Body& body);

// events.csv: t,body,type,kind,values,state. values and state are "name=value" pairs separated by spaces,
// numbers as formatNumber writes them (they read back bit for bit), texts as they are.
inline constexpr const char* kEventsFile = "events.csv";
std::string eventsCsvHeader();
std::string eventsCsvRow(const BodyEvent& event);

class CsvWriter {
 public:
  // Opens DIR/<body>.csv.tmp for every body and DIR/events.csv.tmp and writes the headers; throws
  // std::runtime_error, leaving no .tmp file behind.
  CsvWriter(const std::string& out_dir, const std::vector<Body>& bodies);
  ~CsvWriter();  // removes the temporary files of an uncommitted run
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  // A row for each body; a body not seen before gets its file (a replay's spawned bodies). Throws
  // std::runtime_error for a name that comes back as another type of body (one header per file).
  void write(double t, const std::vector<Body>& bodies);
  void write(const std::vector<BodyEvent>& events);  // a row each in events.csv
  // Flushes and renames every file to its final name; throws std::runtime_error on a write error.
  void commit();

 private:
  struct File {
    std::string name;
    std::size_t type;  // the index of its type in the list of body types (AnyModel)
    std::string final_path;
    std::string temp_path;
    std::unique_ptr<std::ofstream> stream;
  };
  File& fileOf(const Body& body);  // opens it on first sight
  File open(const std::string& file_name, const std::string& header) const;
  std::vector<File*> all();  // events.csv and the bodies' files
  std::string out_dir_;
  void removeTemporaries();
  std::vector<File> files_;
  File events_;
  bool committed_ = false;
};

}  // namespace rigid_body_sim
