// sim_node's markers (markers.test: config/demo.yaml at wall pace, the default marker rate of 10 Hz): the
// latched ~scene arrives at once, the same once more a second or two later (for a viewer whose transforms
// came late), and again only when a body's look changes; ~markers comes at the marker
// rate, its trail pieces carry only the points since the last piece and join up into the bodies' paths as
// the core World computes them; no marker carries a non-finite number.
#include <algorithm>
#include <cmath>
#include <mutex>

#include <visualization_msgs/MarkerArray.h>

#include "node_test_util.h"
#include "rigid_body_sim/ros/scene.h"

using namespace rigid_body_sim;
using visualization_msgs::Marker;
using visualization_msgs::MarkerArray;

namespace {

constexpr double kMarkerRate = 10.0;  // the default, below demo.yaml's publish_rate of 50
constexpr double kTimeout = 20.0;

// Every message of one MarkerArray topic, in arrival order.
class MarkerLog {
 public:
  MarkerLog(ros::NodeHandle& nh, const std::string& topic)
      : sub_(nh.subscribe<MarkerArray>(topic, 1000, [this](const MarkerArray::ConstPtr& msg) {
          std::lock_guard<std::mutex> lock(mutex_);
          arrays_.push_back(*msg);
          cv_.notify_all();
        })) {}
  ~MarkerLog() { sub_.shutdown(); }

  bool waitCount(std::size_t count, double timeout = kTimeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    return cv_.wait_for(lock, std::chrono::duration<double>(timeout),
                        [&] { return arrays_.size() >= count; });
  }
  std::vector<MarkerArray> arrays() {
    std::lock_guard<std::mutex> lock(mutex_);
    return arrays_;
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return arrays_.size();
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<MarkerArray> arrays_;
  ros::Subscriber sub_;
};

bool finite(const Marker& m) {
  double sum = m.pose.position.x + m.pose.position.y + m.pose.position.z + m.pose.orientation.x +
               m.pose.orientation.y + m.pose.orientation.z + m.pose.orientation.w + m.scale.x + m.scale.y +
               m.scale.z;
  for (const auto& p : m.points) sum += p.x + p.y + p.z;
  return std::isfinite(sum);
}

// The world positions of body `index` at every publication of the core World, up to `until` seconds.
std::vector<Eigen::Vector3d> pathOf(const WorldConfig& config, std::size_t index, double until) {
  World world(config);
  const auto steps_per_publication = std::llround(config.rate / config.publish_rate);
  std::vector<Eigen::Vector3d> path;
  while (world.time() <= until) {
    const auto placements = placeBodies(world.bodies());
    path.push_back((placements[index].world_from_frame * frameFromBody(world.bodies()[index])).translation());
    for (int s = 0; s < steps_per_publication; ++s) world.step();
  }
  return path;
}

}  // namespace

TEST(Markers, SceneLatchedAndResentOnlyOnChangeTrailsIncrementalAtTheMarkerRate) {
  ros::NodeHandle nh;
  WorldConfig config = loadWorldConfigFile(test::configPath());
  // The node reads its bodies from the parameter server, which orders them by name; so do the placements.
  std::sort(config.bodies.begin(), config.bodies.end(),
            [](const BodyConfig& a, const BodyConfig& b) { return a.name < b.name; });
  std::size_t rod_index = 0;
  while (config.bodies.at(rod_index).name != "rod") ++rod_index;
  MarkerLog scene(nh, "/sim/scene");
  ASSERT_TRUE(scene.waitCount(1)) << "the latched scene";
  const MarkerArray first_scene = scene.arrays().front();
  ASSERT_FALSE(first_scene.markers.empty());
  EXPECT_EQ(first_scene.markers.front().action, Marker::DELETEALL);
  std::size_t bodies = 0;
  int rod_slot = -1;
  for (const auto& m : first_scene.markers) {
    EXPECT_TRUE(finite(m)) << m.ns << " " << m.id;
    if (m.ns == "body") {
      ++bodies;
      EXPECT_TRUE(m.frame_locked);
      if (m.header.frame_id == "rod") rod_slot = m.id;
    }
  }
  ASSERT_GE(rod_slot, 0);
  EXPECT_EQ(bodies, config.bodies.size());
  ASSERT_TRUE(scene.waitCount(2, 10.0)) << "the scene once more, within two seconds of joining";
  EXPECT_EQ(scene.arrays().back(), first_scene);

  MarkerLog markers(nh, "/sim/markers");
  ASSERT_TRUE(markers.waitCount(25)) << "2.5 s of markers at 10 Hz";
  const auto arrays = markers.arrays();
  EXPECT_EQ(scene.count(), 2u) << "the scene is sent again only when it changes";

  // At the marker rate: consecutive stamps 1 / marker_rate apart.
  for (std::size_t i = 1; i < arrays.size(); ++i) {
    const double gap =
        (arrays[i].markers.at(0).header.stamp - arrays[i - 1].markers.at(0).header.stamp).toSec();
    EXPECT_NEAR(gap, 1.0 / kMarkerRate, 1e-6) << i;
  }
  // The rod's trail pieces join up into its path (the core World's), from where this subscriber joined.
  std::vector<Eigen::Vector3d> joined;
  for (const auto& array : arrays) {
    for (const auto& m : array.markers) {
      EXPECT_TRUE(finite(m)) << m.ns << " " << m.id;
      if (m.ns != "trail" || m.id / MarkerOptions().ring() != rod_slot) continue;
      EXPECT_LE(m.points.size(), static_cast<std::size_t>(config.publish_rate / kMarkerRate) + 1);
      if (!joined.empty()) {
        EXPECT_EQ(Eigen::Vector3d(m.points[0].x, m.points[0].y, m.points[0].z), joined.back()) << "a gap";
      }
      for (std::size_t p = joined.empty() ? 0 : 1; p < m.points.size(); ++p) {
        joined.emplace_back(m.points[p].x, m.points[p].y, m.points[p].z);
      }
    }
  }
  ASSERT_GE(joined.size(), 50u);
  const auto path = pathOf(config, rod_index, 120.0);
  auto start = std::find(path.begin(), path.end(), joined.front());
  ASSERT_NE(start, path.end()) << "the first trail point is no point of the rod's path";
  ASSERT_GE(static_cast<std::size_t>(path.end() - start), joined.size());
  EXPECT_TRUE(std::equal(joined.begin(), joined.end(), start))
      << "the trail is the rod's path, sample by sample";

  // A new look (a roller's radius) sends the scene again; a new friction does not.
  ASSERT_TRUE(ros::service::waitForService("/sim/sphere/set_parameters", 10000));
  bool called = false;
  test::callReconfigure("sphere", {{"mu_d", 0.1}}, {}, &called);
  ASSERT_TRUE(called);
  const std::size_t before = markers.count();
  ASSERT_TRUE(markers.waitCount(before + 5));
  EXPECT_EQ(scene.count(), 2u) << "mu_d does not change the look";
  test::callReconfigure("sphere", {{"radius", 0.2}}, {}, &called);
  ASSERT_TRUE(called);
  ASSERT_TRUE(scene.waitCount(3)) << "a new radius is a new scene";
  const MarkerArray second = scene.arrays().back();
  EXPECT_EQ(second.markers.front().action, Marker::DELETEALL);
  EXPECT_NE(second, first_scene);
}

RBS_ROSTEST_MAIN("test_node_markers")
