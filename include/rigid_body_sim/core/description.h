// The one exported description: every body type's keys (name, kind, unit, range or choices, default,
// meaning, runtime level, whether a lesson page may change it), its state fields and frames, and the world's
// keys, as one JSON document. The build writes it (describe_body_types) into the package's Python package,
// where the .cfg files, the Python package, the web page and the docs read it.
#pragma once

#include <string>

namespace rigid_body_sim {

std::string bodyTypesJson();

}  // namespace rigid_body_sim
