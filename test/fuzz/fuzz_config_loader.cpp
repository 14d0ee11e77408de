// libFuzzer target: any text given to the config loader either loads into a config that validates, or is
// refused with a ConfigError of one line. Any other exception, a crash, a leak or undefined behaviour
// (under ASan + UBSan) is a failure.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/io/config_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const rigid_body_sim::WorldConfig config = rigid_body_sim::parseWorldConfigText(text, "fuzz");
    // What loads must validate again (the node re-validates).
    rigid_body_sim::validate(config, rigid_body_sim::node_interface::ownNames());
    rigid_body_sim::slowRunWarnings(config);
  } catch (const rigid_body_sim::ConfigError& error) {
    const std::string message = error.what();
    if (message.empty() || message.find('\n') != std::string::npos) {
      std::fprintf(stderr, "refusal is not one line: [%s]\n", message.c_str());
      std::abort();
    }
  }
  return 0;  // anything else thrown escapes: libFuzzer reports it as a crash
}
