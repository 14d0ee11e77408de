// The exported description of the body types (core/description.h):
//   describe_body_types OUT.json     writes it to OUT.json: the build runs it, and the .cfg files, the Python
//                                    package and the web page read what it writes
//   describe_body_types --docs DOC   writes the key tables marked in DOC again (`make figures` runs it on
//                                    docs/configuration.md; test_readme fails while a table there differs)
#include <fstream>
#include <iostream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "rigid_body_sim/core/description.h"

namespace {

bool write(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.close();
  if (!out) std::cerr << "describe_body_types: cannot write " << path << "\n";
  return static_cast<bool>(out);
}

int rewriteDocs(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    std::cerr << "describe_body_types: cannot read " << path << "\n";
    return 1;
  }
  const std::string doc{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  try {
    return write(path, rigid_body_sim::withKeyTables(doc)) ? 0 : 1;
  } catch (const std::invalid_argument& error) {
    std::cerr << "describe_body_types: " << path << ": " << error.what() << "\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--docs") return rewriteDocs(argv[2]);
  if (argc != 2 || std::string(argv[1]).rfind("--", 0) == 0) {
    std::cerr << "usage: describe_body_types OUT.json | describe_body_types --docs DOC.md\n";
    return 2;
  }
  return write(argv[1], rigid_body_sim::bodyTypesJson()) ? 0 : 1;
}
