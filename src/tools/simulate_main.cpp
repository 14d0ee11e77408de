// simulate CONFIG.yaml [--duration S] [--sample-rate HZ] [--out-dir DIR] [--bag FILE]
// Runs the node's physics without a ROS master and writes DIR/<body>.csv (and a bag on request).
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "rigid_body_sim/adapters/config_loader.h"
#include "rigid_body_sim/adapters/offline_run.h"

int main(int argc, char** argv) {
  CLI::App app{"Offline rigid_body_sim run: CSV per body, optional bag, no ROS master needed.", "simulate"};
  std::string config_path;
  rigid_body_sim::OfflineOptions options;
  app.add_option("CONFIG", config_path, "YAML configuration (the node's parameters)")->required();
  app.add_option("--duration", options.duration, "simulated seconds")->capture_default_str();
  app.add_option("--sample-rate", options.sample_rate,
                 "samples per simulated second, a divisor of rate (default: publish_rate)");
  app.add_option("--out-dir", options.out_dir, "folder for <body>.csv")->capture_default_str();
  app.add_option("--bag", options.bag, "also write what the node would publish into this bag");
  CLI11_PARSE(app, argc, argv);

  try {
    const auto config = rigid_body_sim::loadWorldConfigFile(config_path);
    const auto summary = rigid_body_sim::runOffline(config, options);
    std::cout << rigid_body_sim::formatSummary(summary);
  } catch (const std::exception& error) {
    std::cerr << "simulate: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
