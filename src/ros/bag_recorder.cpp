#include "rigid_body_sim/ros/bag_recorder.h"

#include <cmath>
#include <cstdio>

#include <boost/make_shared.hpp>

// Built with AddressSanitizer (gcc's -fsanitize=address, or clang's): its LeakSanitizer is there.
#if defined(__SANITIZE_ADDRESS__)
#define RBS_LEAK_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RBS_LEAK_SANITIZER 1
#endif
#endif
#ifdef RBS_LEAK_SANITIZER
#include <sanitizer/lsan_interface.h>
#endif

#include "rigid_body_sim/core/node_interface.h"
#include "rigid_body_sim/ros/command_log.h"
#include "rigid_body_sim/ros/messages.h"

namespace rigid_body_sim {

namespace {

std::string stateTopic(const std::string& node_namespace, const std::string& body) {
  return node_namespace + "/" + node_interface::stateTopic(body);
}

std::string nodeTopic(const std::string& node_namespace, const char* name) {
  return node_namespace + "/" + name;
}

// rosbag stores a given connection header as it is: without type, md5sum and definition, Python's rosbag
// (rosbag info, scripts) cannot read the bag. Latched: a player hands the message to late subscribers as a
// live node would.
template <class Message>
boost::shared_ptr<ros::M_string> latchedHeader(const std::string& callerid) {
  auto header = boost::make_shared<ros::M_string>();
  (*header)["type"] = ros::message_traits::datatype<Message>();
  (*header)["md5sum"] = ros::message_traits::md5sum<Message>();
  (*header)["message_definition"] = ros::message_traits::definition<Message>();
  (*header)["latching"] = "1";
  (*header)["callerid"] = callerid;
  return header;
}

// LeakSanitizer ignores what is allocated while one of these lives (nothing without the sanitizer).
struct LeaksIgnored {
#ifdef RBS_LEAK_SANITIZER
  LeaksIgnored() { __lsan_disable(); }
  ~LeaksIgnored() { __lsan_enable(); }
#endif
};

// rosbag::Bag's destructor closes the bag, writing its index; after a failed write that write fails too,
// and a throw from a destructor ends the process. A failed bag is never destroyed: it is kept here
// (reachable, so no leak to report) until the process ends, which closes its file.
std::vector<std::unique_ptr<rosbag::Bag>>& keptUnclosed() {
  static auto* const kept = new std::vector<std::unique_ptr<rosbag::Bag>>();
  return *kept;
}

void keepUnclosed(std::unique_ptr<rosbag::Bag> bag) { keptUnclosed().push_back(std::move(bag)); }

}  // namespace

bool anyBagKeptUnclosed() { return !keptUnclosed().empty(); }

std::unique_ptr<rosbag::Bag> newBag() {
  [[maybe_unused]] const LeaksIgnored ignored;
  return std::make_unique<rosbag::Bag>();  // made in place: rosbag's move constructor loses its streams
}

template <class Write>
void BagRecorder::guarded(Write&& write) {
  if (failed_)
    throw rosbag::BagIOException("'" + path_ + ".active' is no longer written after a write error");
  try {
    write(*bag_);
  } catch (const rosbag::BagException& error) {
    failed_ = true;
    keepUnclosed(std::move(bag_));
    throw rosbag::BagIOException("writing '" + path_ + ".active' failed (" + error.what() +
                                 "): the recording ends there, unindexed (rosbag reindex recovers it)");
  }
}

BagRecorder::BagRecorder(const std::string& path, const WorldConfig& config, const std::vector<Body>& bodies,
                         BagOptions options)
    : path_(path),
      node_namespace_(std::move(options.node_namespace)),
      snapshots_(config.world_frame, std::move(options.frame_prefix), bodies, options.markers),
      marker_rate_(options.markers.pieces_rate),
      bag_(newBag()) {
  bag_->open(path_ + ".active", rosbag::bagmode::Write);  // a failure here leaves no file
  // LZ4 chunks, as `rosbag record --lz4` (sim.launch) writes: a bag 2.6 times smaller (demo.yaml with
  // markers, 39 kB a simulated second instead of 102), read by every rosbag (roslz4 is rosbag's dependency).
  bag_->setCompression(rosbag::compression::LZ4);
  const ros::Time start = simStamp(0.0);
  WorldCommand config_command;
  config_command.kind = WorldCommand::Kind::Config;
  config_command.world = config;
  guarded([&](rosbag::Bag& bag) {
    bag.write(node_namespace_ + "/" + node_interface::kCommands, start,
              toMessage(config_command, 0, 0.0, start, config.world_frame),
              latchedHeader<rigid_body_sim::Command>(node_namespace_));
    tf2_msgs::TFMessage message;
    message.transforms = snapshots_.staticTransforms(start);
    bag.write("/tf_static", start, message, latchedHeader<tf2_msgs::TFMessage>(node_namespace_));
    bag.write(nodeTopic(node_namespace_, node_interface::kScene), start, snapshots_.scene().sceneMarkers(),
              latchedHeader<visualization_msgs::MarkerArray>(node_namespace_));
  });
}

BagRecorder::~BagRecorder() {
  // An unfinished recording stays as <path>.active, the way `rosbag record` leaves one.
  if (!bag_) return;
  try {
    bag_->close();
  } catch (const rosbag::BagException&) {
    keepUnclosed(std::move(bag_));
  }
}

void BagRecorder::write(const World& world) {
  const double t = world.time();
  const ros::Time stamp = simStamp(t);
  const Snapshot snapshot = snapshots_.build(t, stamp, world.bodies());
  guarded([&](rosbag::Bag& bag) {
    bag.write("/tf", stamp, snapshot.tf);
    // The trails grow at every sample and are written at the marker rate, as the node publishes them.
    Scene& scene = snapshots_.scene();
    scene.sample(world.bodies());
    const auto marker_instant = static_cast<long long>(std::floor(t * marker_rate_ + 1e-9));
    if (marker_instant > last_marker_instant_) {
      bag.write(nodeTopic(node_namespace_, node_interface::kMarkers), stamp,
                scene.changes(stamp, world.bodies()));
      last_marker_instant_ = marker_instant;
    }
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
      const std::string topic = stateTopic(node_namespace_, world.bodies()[i].name);
      std::visit([&](const auto& msg) { bag.write(topic, stamp, msg); }, snapshot.states[i]);
    }
  });
}

// As the node logs a change: the command, then the scene and fixed frames of a changed set of bodies.
void BagRecorder::applied(const WorldCommand& command, std::size_t index, const World& world) {
  const ros::Time stamp = simStamp(world.time());
  const bool new_look = command.kind == WorldCommand::Kind::Spawn ||
                        command.kind == WorldCommand::Kind::Delete ||
                        command.kind == WorldCommand::Kind::Reconfigure;
  guarded([&](rosbag::Bag& bag) {
    bag.write(node_namespace_ + "/" + node_interface::kCommands, stamp,
              toMessage(command, static_cast<std::uint32_t>(index), world.time(), stamp,
                        world.config().world_frame),
              latchedHeader<rigid_body_sim::Command>(node_namespace_));
    if (!new_look) return;
    if (snapshots_.scene().rebuild(world.bodies())) {
      bag.write(nodeTopic(node_namespace_, node_interface::kScene), stamp, snapshots_.scene().sceneMarkers(),
                latchedHeader<visualization_msgs::MarkerArray>(node_namespace_));
    }
    tf2_msgs::TFMessage message;
    message.transforms = snapshots_.staticTransforms(stamp);
    bag.write("/tf_static", stamp, message, latchedHeader<tf2_msgs::TFMessage>(node_namespace_));
  });
}

void BagRecorder::happened(const std::vector<BodyEvent>& events, const World&) {
  guarded([&](rosbag::Bag& bag) {
    for (const auto& event : events) {
      const ros::Time stamp = simStamp(event.t);
      bag.write(nodeTopic(node_namespace_, node_interface::kEvents), stamp, toEventMsg(event, stamp));
    }
  });
}

void BagRecorder::commit() {
  if (!bag_ && !failed_) return;  // committed before
  guarded([](rosbag::Bag& bag) { bag.close(); });
  bag_.reset();
  if (std::rename((path_ + ".active").c_str(), path_.c_str()) != 0) {
    throw rosbag::BagException("cannot rename '" + path_ + ".active' to '" + path_ + "'");
  }
}

SinkOpener bagOpener(BagOptions options) {
  return [options](const std::string& path, const WorldConfig& config, const std::vector<Body>& bodies) {
    return std::make_unique<BagRecorder>(path, config, bodies, options);
  };
}

}  // namespace rigid_body_sim
