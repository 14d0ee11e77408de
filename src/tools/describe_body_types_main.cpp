// The exported description of the body types (core/description.h):
//   describe_body_types OUT.json     writes it to OUT.json: the build runs it, and the .cfg files, the Python
//                                    package and the web page read what it writes
//   describe_body_types --docs DOC   writes the key tables marked in DOC again (`make figures` runs it on
//                                    docs/configuration.md; test_readme fails while a table there differs)
//   describe_body_types --check-messages MSG_DIR
//                                    fails, naming the first difference, unless each type's state message
//                                    MSG_DIR/<Type>State.msg has its state fields, in their order, after its
//                                    header and t (float64 a number, string a text): the build runs it, so
//                                    that a field declared in one and not the other fails the build
#include <algorithm>
#include <cctype>
#include <fstream>
#include <iostream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "rigid_body_sim/core/body_types.h"
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

// The fields of a .msg file as "type name", constants (a '=') and comments left out.
std::vector<std::string> messageFields(std::istream& in) {
  std::vector<std::string> fields;
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string type, name;
    if (!(words >> type >> name) || line.find('=') != std::string::npos) continue;
    fields.push_back(type + " " + name);
  }
  return fields;
}

int checkMessages(const std::string& dir) {
  int failed = 0;
  rigid_body_sim::BodyTypes::forEach([&](auto type) {
    using Type = decltype(type);
    std::string message = Type::kName;
    message[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(message[0])));
    const std::string path = dir + "/" + message + "State.msg";
    std::ifstream in(path);
    std::vector<std::string> expected{"Header header", "float64 t"};
    for (const auto& field : Type::kStateFields)
      expected.push_back(std::string(field.text ? "string " : "float64 ") + field.name);
    const std::vector<std::string> got = in ? messageFields(in) : std::vector<std::string>{};
    for (std::size_t i = 0; i < std::max(expected.size(), got.size()); ++i) {
      const std::string want = i < expected.size() ? expected[i] : "(nothing)";
      const std::string has = i < got.size() ? got[i] : "(nothing)";
      if (want == has) continue;
      std::cerr << "describe_body_types: " << path << ": field " << i + 1 << " is '" << has << "', the "
                << Type::kName << "'s state fields (kStateFields) say '" << want << "'\n";
      ++failed;
      return;
    }
  });
  return failed == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::string(argv[1]) == "--docs") return rewriteDocs(argv[2]);
  if (argc == 3 && std::string(argv[1]) == "--check-messages") return checkMessages(argv[2]);
  if (argc != 2 || std::string(argv[1]).rfind("--", 0) == 0) {
    std::cerr << "usage: describe_body_types OUT.json | --docs DOC.md | --check-messages MSG_DIR\n";
    return 2;
  }
  return write(argv[1], rigid_body_sim::bodyTypesJson()) ? 0 : 1;
}
