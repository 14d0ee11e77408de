// Writes the exported description of the body types (core/description.h) to the file its one argument
// names: the build runs it, and the .cfg files, the Python package and the web page read what it writes.
#include <fstream>
#include <iostream>

#include "rigid_body_sim/core/description.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: describe_body_types OUT.json\n";
    return 2;
  }
  std::ofstream out(argv[1]);
  out << rigid_body_sim::bodyTypesJson();
  out.close();
  if (!out) {
    std::cerr << "describe_body_types: cannot write " << argv[1] << "\n";
    return 1;
  }
  return 0;
}
