// sim_node's interactive markers (~interactive): this node sends what rviz sends when a marker is dragged
// and dropped (POSE_UPDATE, then MOUSE_UP on /sim/interactive/feedback). A drop sets the body's initial
// conditions through its reconfigure server (which then shows them) and restarts it exactly as the core
// World restarts it; a refused drop (off the slope, under the floor, a rod turned by a quaternion that is no
// rotation) logs one WARN line, puts the marker back and changes nothing.
#include <cmath>

#include <dynamic_reconfigure/Config.h>
#include <rosgraph_msgs/Log.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>
#include <visualization_msgs/InteractiveMarkerInit.h>
#include <visualization_msgs/InteractiveMarkerUpdate.h>

#include "node_test_util.h"
#include "rigid_body_sim/ros/interactive_controls.h"

using namespace rigid_body_sim;
using namespace rigid_body_sim::test;
using visualization_msgs::InteractiveMarkerFeedback;

namespace {

// What the node publishes besides states: marker poses, server values, its WARN lines.
class Watcher {
 public:
  explicit Watcher(ros::NodeHandle& nh) {
    subs_.push_back(nh.subscribe<visualization_msgs::InteractiveMarkerUpdate>(
        "/sim/interactive/update", 100,
        [this](const visualization_msgs::InteractiveMarkerUpdate::ConstPtr& u) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& m : u->markers) poses_[m.name] = m.pose;
          for (const auto& p : u->poses) poses_[p.name] = p.pose;
          cv_.notify_all();
        }));
    subs_.push_back(nh.subscribe<visualization_msgs::InteractiveMarkerInit>(  // the latched full state
        "/sim/interactive/update_full", 1,
        [this](const visualization_msgs::InteractiveMarkerInit::ConstPtr& u) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& m : u->markers) poses_[m.name] = m.pose;
          cv_.notify_all();
        }));
    for (const std::string body : {"rod", "sphere"}) {
      subs_.push_back(nh.subscribe<dynamic_reconfigure::Config>(
          "/sim/" + body + "/parameter_updates", 10,
          [this, body](const dynamic_reconfigure::Config::ConstPtr& c) {
            std::lock_guard<std::mutex> lock(mutex_);
            values_[body] = *c;
            cv_.notify_all();
          }));
    }
    subs_.push_back(
        nh.subscribe<rosgraph_msgs::Log>("/rosout", 100, [this](const rosgraph_msgs::Log::ConstPtr& l) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (l->name == "/sim" && l->level == rosgraph_msgs::Log::WARN) warnings_.push_back(l->msg);
          cv_.notify_all();
        }));
  }
  ~Watcher() {
    for (auto& s : subs_) s.shutdown();
  }

  bool waitFor(const std::function<bool()>& pred, double timeout = 5.0) {
    std::unique_lock<std::mutex> lock(mutex_);
    return cv_.wait_for(lock, std::chrono::duration<double>(timeout), pred);
  }
  // Under the lock (in waitFor's predicates) or after it.
  std::map<std::string, geometry_msgs::Pose> poses_;
  std::map<std::string, dynamic_reconfigure::Config> values_;
  std::vector<std::string> warnings_;
  std::mutex mutex_;

 private:
  std::condition_variable cv_;
  std::vector<ros::Subscriber> subs_;
};

geometry_msgs::Pose pose(double x, double y, double theta = 0.0) {
  geometry_msgs::Pose p;
  p.position.x = x;
  p.position.y = y;
  p.orientation.z = std::sin(theta / 2);
  p.orientation.w = std::cos(theta / 2);
  return p;
}

// What rviz sends for a drag that ends at `at`: a pose update, then the release there.
void drop(ros::Publisher& feedback, const std::string& marker, const std::string& frame,
          const geometry_msgs::Pose& at) {
  InteractiveMarkerFeedback f;
  f.header.frame_id = frame;
  f.client_id = "/rviz/InteractiveMarkers";
  f.marker_name = marker;
  f.control_name = "move";
  f.pose = at;
  f.event_type = InteractiveMarkerFeedback::POSE_UPDATE;
  feedback.publish(f);
  f.event_type = InteractiveMarkerFeedback::MOUSE_UP;
  f.mouse_point_valid = true;
  f.mouse_point = at.position;
  feedback.publish(f);
}

// Steps the node (paused) and `world` by n; every body's last state must equal the world's, exactly.
void stepAndCompare(StateCollector& c, World& world, std::uint32_t n, const std::string& what) {
  c.clear();
  bool called = false;
  const Step s = callStep(n, &called);
  ASSERT_TRUE(called && s.response.success) << what << ": " << s.response.message;
  for (std::uint32_t i = 0; i < n; ++i) world.step();
  ASSERT_EQ(world.time(), s.response.t) << what;
  ASSERT_TRUE(c.waitAllAt(world, s.response.t, 5.0)) << what << ": no state of every body at the end";
  for (const auto& body : world.bodies()) {
    if (std::holds_alternative<Rod>(body.model)) {
      expectSameState(expectedRod(world, body.name), c.rod(body.name).back(), what + " " + body.name);
    } else {
      expectSameState(expectedRoller(world, body.name), c.roller(body.name).back(), what + " " + body.name);
    }
  }
}

Rod& rodOf(World& w) { return std::get<Rod>(w.find("rod")->model); }
Roller& sphereOf(World& w) { return std::get<Roller>(w.find("sphere")->model); }

}  // namespace

TEST(SimNodeInteractive, DropsSetInitialConditionsLikeAReconfigure) {
  ros::NodeHandle nh;
  const WorldConfig config = loadWorldConfigFile(configPath());
  World world(config);
  StateCollector c(nh, world);
  Watcher watch(nh);
  ros::Publisher feedback = nh.advertise<InteractiveMarkerFeedback>("/sim/interactive/feedback", 10);
  ASSERT_TRUE(c.waitConnected(10.0));
  ASSERT_TRUE(ros::service::waitForService("/sim/step", 10000));
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(10.0);
  while (feedback.getNumSubscribers() == 0 && ros::WallTime::now() < end) ros::WallDuration(0.02).sleep();
  ASSERT_GT(feedback.getNumSubscribers(), 0u) << "nobody listens on /sim/interactive/feedback";
  ASSERT_TRUE(watch.waitFor(
      [&] {
        return watch.poses_.count("rod") && watch.poses_.count("sphere/velocity") &&
               watch.values_.count("rod") && watch.values_.count("sphere");
      },
      10.0))
      << "no interactive markers or server values";
  {  // the markers start at the config's initial conditions, in the bodies' fixed frames
    const RodMotion start = rodOf(world).initial();
    std::lock_guard<std::mutex> lock(watch.mutex_);
    EXPECT_EQ(start.x, watch.poses_["rod"].position.x);
    EXPECT_EQ(start.y, watch.poses_["rod"].position.y);
    EXPECT_NEAR(start.theta,
                2 * std::atan2(watch.poses_["rod"].orientation.z, watch.poses_["rod"].orientation.w), 1e-12);
    EXPECT_EQ(start.x + start.vx * kVelocityArrowScale, watch.poses_["rod/velocity"].position.x);
    EXPECT_EQ(start.y + start.vy * kVelocityArrowScale, watch.poses_["rod/velocity"].position.y);
  }

  // Paused, and the local World brought to the node's step (step(1) tells the time).
  ASSERT_TRUE(callEmpty("/sim/pause"));
  bool called = false;
  const Step s = callStep(1, &called);
  ASSERT_TRUE(called && s.response.success);
  for (std::int64_t i = 0, n = stepIndex(s.response.t, config.rate); i < n; ++i) world.step();
  stepAndCompare(c, world, 1, "before any drop");

  // --- the rod placed at (1.5, 2.5) turned to 0.7 rad, then thrown at (3, -1) m/s
  drop(feedback, "rod", "rod_floor", pose(1.5, 2.5, 0.7));
  ASSERT_TRUE(watch.waitFor([&] { return doubleOf(watch.values_["rod"], "x0") == 1.5; }))
      << "the rod's server does not show the drop";
  const double theta0 = doubleOf(watch.values_["rod"], "theta0");
  EXPECT_NEAR(0.7, theta0, 1e-12);
  EXPECT_EQ(2.5, doubleOf(watch.values_["rod"], "y0"));
  RodMotion rod_initial = rodOf(world).initial();
  rod_initial.x = 1.5;
  rod_initial.y = 2.5;
  rod_initial.theta = theta0;
  rodOf(world).setInitial(rod_initial);
  stepAndCompare(c, world, 1, "one step after the rod's drop");
  EXPECT_NEAR(2.5, c.rod("rod").back().y, 1e-3);

  drop(feedback, "rod/velocity", "rod_floor", pose(1.5 + 3 * kVelocityArrowScale, 2.5 - kVelocityArrowScale));
  ASSERT_TRUE(watch.waitFor([&] { return doubleOf(watch.values_["rod"], "vx0") == 3.0; }))
      << "the rod's server does not show the thrown velocity";
  EXPECT_EQ(-1.0, doubleOf(watch.values_["rod"], "vy0"));
  EXPECT_EQ(1.5, doubleOf(watch.values_["rod"], "x0"));  // the place stays
  rod_initial.vx = 3.0;
  rod_initial.vy = -1.0;
  rodOf(world).setInitial(rod_initial);
  stepAndCompare(c, world, 800, "after the rod's throw (it reaches the floor)");

  // --- the sphere put 1 m down its slope and launched at 2 m/s
  drop(feedback, "sphere", "sphere_slope", pose(1.0, 0.1));
  ASSERT_TRUE(watch.waitFor([&] { return doubleOf(watch.values_["sphere"], "x0") == 1.0; }));
  drop(feedback, "sphere/velocity", "sphere_slope", pose(1.0 + 2 * kVelocityArrowScale, 0.1));
  ASSERT_TRUE(watch.waitFor([&] { return doubleOf(watch.values_["sphere"], "v0") == 2.0; }));
  RollerInitial sphere_initial = sphereOf(world).initial();
  sphere_initial.x0 = 1.0;
  sphere_initial.v0 = 2.0;
  sphereOf(world).setInitial(sphere_initial);
  stepAndCompare(c, world, 300, "after the sphere's drop and launch");

  // --- refused: the sphere dropped off its slope (x0 < 0): one WARN line, the marker back, nothing changed
  std::size_t warnings = 0;
  {
    std::lock_guard<std::mutex> lock(watch.mutex_);
    warnings = watch.warnings_.size();
    watch.poses_.erase("sphere");
  }
  const auto sphere_before = watch.values_["sphere"];
  drop(feedback, "sphere", "sphere_slope", pose(-1.0, 0.1));
  ASSERT_TRUE(watch.waitFor([&] { return watch.warnings_.size() > warnings; })) << "no WARN line";
  EXPECT_NE(std::string::npos, watch.warnings_.back().find("body 'sphere', key 'x0': value -1"))
      << watch.warnings_.back();
  ASSERT_TRUE(watch.waitFor([&] { return watch.poses_.count("sphere") > 0; }))
      << "the marker was not put back";
  EXPECT_EQ(1.0, watch.poses_["sphere"].position.x);
  stepAndCompare(c, world, 300, "after the refused drop");
  EXPECT_EQ(sphere_before.doubles.size(), watch.values_["sphere"].doubles.size());
  EXPECT_EQ(1.0, doubleOf(watch.values_["sphere"], "x0"));
  {
    std::lock_guard<std::mutex> lock(watch.mutex_);
    EXPECT_EQ(warnings + 1, watch.warnings_.size()) << "a refused drop logs exactly one line";
    warnings = watch.warnings_.size();
    watch.poses_.erase("rod");
  }

  // --- refused: the rod dropped under the floor (y0 < 0), likewise
  drop(feedback, "rod", "rod_floor", pose(1.0, -0.5, 0.2));
  ASSERT_TRUE(watch.waitFor([&] { return watch.warnings_.size() > warnings; })) << "no WARN line";
  EXPECT_NE(std::string::npos, watch.warnings_.back().find("body 'rod', key 'y0': value -0.5"))
      << watch.warnings_.back();
  ASSERT_TRUE(watch.waitFor([&] { return watch.poses_.count("rod") > 0; })) << "the marker was not put back";
  EXPECT_EQ(1.5, watch.poses_["rod"].position.x);
  EXPECT_EQ(2.5, watch.poses_["rod"].position.y);
  stepAndCompare(c, world, 300, "after the refused drop under the floor");
  EXPECT_EQ(2.5, doubleOf(watch.values_["rod"], "y0"));
  {
    std::lock_guard<std::mutex> lock(watch.mutex_);
    EXPECT_EQ(warnings + 1, watch.warnings_.size()) << "a refused drop logs exactly one line";
    warnings = watch.warnings_.size();
    watch.poses_.erase("rod");
  }

  // --- refused: the rod dropped with the zero quaternion, which is no turn at all (theta0 would be read as
  // 0)
  geometry_msgs::Pose no_turn = pose(2.0, 3.0);
  no_turn.orientation = geometry_msgs::Quaternion();
  drop(feedback, "rod", "rod_floor", no_turn);
  ASSERT_TRUE(watch.waitFor([&] { return watch.warnings_.size() > warnings; })) << "no WARN line";
  EXPECT_NE(std::string::npos,
            watch.warnings_.back().find("drop of marker 'rod' refused: its orientation (0, 0, 0, 0)"))
      << watch.warnings_.back();
  ASSERT_TRUE(watch.waitFor([&] { return watch.poses_.count("rod") > 0; })) << "the marker was not put back";
  EXPECT_EQ(1.5, watch.poses_["rod"].position.x);
  stepAndCompare(c, world, 300, "after the drop with no turn");
  EXPECT_EQ(1.5, doubleOf(watch.values_["rod"], "x0"));
  std::lock_guard<std::mutex> lock(watch.mutex_);
  EXPECT_EQ(warnings + 1, watch.warnings_.size()) << "a refused drop logs exactly one line";
}

RBS_ROSTEST_MAIN("test_node_interactive")
