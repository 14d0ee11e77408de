// The scene's markers against the core World: the latched scene changes only with the bodies' look, the
// trail pieces carry only the points added since the last piece and join up into the trajectory, and no
// marker carries a non-finite number.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "rigid_body_sim/ros/scene.h"

using namespace rigid_body_sim;
using visualization_msgs::Marker;
using visualization_msgs::MarkerArray;

namespace {

constexpr int kStepsPerPublication = 20;  // rate 1000, publish_rate 50
constexpr int kPublicationsPerPiece = 5;  // marker rate 10 Hz

WorldConfig demoConfig() {
  WorldConfig config;
  RollerConfig ball;
  ball.initial.v0 = 3.0;  // slipping first
  RollerConfig hoop;
  hoop.params.shape = Shape::Ring;
  hoop.params.inertia_factor = 1.0;
  config.bodies = {{"rod", RodConfig{}}, {"ball", ball}, {"hoop", hoop}};
  return config;
}

bool finite(const geometry_msgs::Point& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

bool allFinite(const MarkerArray& array) {
  for (const auto& m : array.markers) {
    const auto& q = m.pose.orientation;
    if (!finite(m.pose.position) || !std::isfinite(q.x + q.y + q.z + q.w) ||
        !std::isfinite(m.scale.x + m.scale.y + m.scale.z)) {
      return false;
    }
    for (const auto& p : m.points) {
      if (!finite(p)) return false;
    }
  }
  return true;
}

std::vector<const Marker*> inNamespace(const MarkerArray& array, const std::string& ns) {
  std::vector<const Marker*> found;
  for (const auto& m : array.markers) {
    if (m.ns == ns) found.push_back(&m);
  }
  return found;
}

// Publications of the world with their trail points, then the changes sent (all taken up to now).
void stepAndSend(World& world, Scene& scene, int publications) {
  for (int publication = 0; publication < publications; ++publication) {
    world.step();
    scene.sample(world.bodies());
  }
  scene.changes(ros::Time(1.0), world.bodies());
}

Eigen::Vector3d worldPositionOf(const World& world, std::size_t i) {
  return (placeBodies(world.bodies())[i].world_from_frame * frameFromBody(world.bodies()[i])).translation();
}

}  // namespace

TEST(Scene, StartsWithDeleteAllAndDrawsEveryBodyLockedToItsOwnFrame) {
  const World world(demoConfig());
  const Scene scene("world", "", world.bodies());
  const MarkerArray& markers = scene.sceneMarkers();
  ASSERT_FALSE(markers.markers.empty());
  EXPECT_EQ(markers.markers.front().action, Marker::DELETEALL);
  EXPECT_EQ(inNamespace(markers, "floor").size(), 1u);
  EXPECT_EQ(inNamespace(markers, "slope").size(), 2u);
  const auto bodies = inNamespace(markers, "body");
  ASSERT_EQ(bodies.size(), 3u);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    EXPECT_EQ(bodies[i]->header.frame_id, world.bodies()[i].name);
    EXPECT_TRUE(bodies[i]->frame_locked);
  }
  EXPECT_EQ(inNamespace(markers, "spoke").size(), 2u);                                 // the rollers'
  for (const auto& m : markers.markers) EXPECT_TRUE(m.header.stamp.isZero()) << m.ns;  // the latest TF
  EXPECT_TRUE(allFinite(markers));
}

TEST(Scene, DrawsInPrefixedFramesButTheWorld) {
  const World world(demoConfig());
  const Scene scene("world", "left/", world.bodies());
  for (const auto& m : scene.sceneMarkers().markers) {
    if (m.ns == "floor" && m.id == 0) {
      EXPECT_EQ(m.header.frame_id, "world");
    } else if (m.action != Marker::DELETEALL) {
      EXPECT_EQ(m.header.frame_id.rfind("left/", 0), 0u) << m.ns << " " << m.header.frame_id;
    }
  }
}

TEST(Scene, IsRebuiltOnlyWhenTheBodiesOrTheirLookChange) {
  World world(demoConfig());
  Scene scene("world", "", world.bodies());
  const MarkerArray first = scene.sceneMarkers();
  for (int i = 0; i < 2000; ++i) world.step();
  EXPECT_FALSE(scene.rebuild(world.bodies())) << "motion is TF's: the scene stays";
  EXPECT_EQ(scene.sceneMarkers(), first);

  RollerParams bigger = std::get<Roller>(world.bodies()[1].model).params();
  bigger.radius *= 2;
  std::get<Roller>(world.bodies()[1].model).setParams(bigger);
  EXPECT_TRUE(scene.rebuild(world.bodies())) << "a new radius is a new look";
  EXPECT_FALSE(scene.rebuild(world.bodies()));

  WorldConfig more = demoConfig();
  more.bodies.push_back({"rod2", RodConfig{}});
  const World larger(more);
  EXPECT_TRUE(scene.rebuild(larger.bodies()));
  EXPECT_EQ(inNamespace(scene.sceneMarkers(), "body").size(), 4u);
}

TEST(Scene, TrailPiecesCarryOnlyNewPointsAndJoinIntoTheTrajectory) {
  World world(demoConfig());
  const MarkerOptions options{8.0, 10.0};
  Scene scene("world", "", world.bodies(), options);
  std::vector<std::vector<Eigen::Vector3d>> truth(world.bodies().size());
  std::map<int, std::vector<const Marker*>> pieces_of;  // by id / ring: the body's slot
  std::vector<MarkerArray> sent;
  sent.reserve(200);
  for (int publication = 0; publication <= 200 * kPublicationsPerPiece; ++publication) {
    if (publication > 0) {
      for (int s = 0; s < kStepsPerPublication; ++s) world.step();
    }
    scene.sample(world.bodies());
    for (std::size_t i = 0; i < world.bodies().size(); ++i) truth[i].push_back(worldPositionOf(world, i));
    if (publication % kPublicationsPerPiece != 0) continue;
    sent.push_back(scene.changes(ros::Time(1.0 + world.time()), world.bodies()));
    ASSERT_TRUE(allFinite(sent.back()));
    EXPECT_EQ(inNamespace(sent.back(), "label").size(), world.bodies().size());
    for (const Marker* piece : inNamespace(sent.back(), "trail")) {
      // Only what is new (and the previous piece's last point): never near rviz's limits.
      EXPECT_LE(piece->points.size(), static_cast<std::size_t>(kPublicationsPerPiece + 1));
      pieces_of[piece->id / options.ring()].push_back(piece);
    }
  }
  ASSERT_EQ(pieces_of.size(), world.bodies().size());
  for (const auto& [slot, pieces] : pieces_of) {
    std::vector<Eigen::Vector3d> joined;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      EXPECT_EQ(pieces[k]->id, slot * options.ring() + static_cast<int>(k % options.ring()))
          << "a ring of ids";
      const auto& points = pieces[k]->points;
      for (std::size_t p = joined.empty() ? 0 : 1; p < points.size(); ++p) {
        joined.emplace_back(points[p].x, points[p].y, points[p].z);
      }
      if (k > 0) {  // each piece starts where the last one ended
        const auto& end = pieces[k - 1]->points.back();
        EXPECT_EQ(points.front().x, end.x);
        EXPECT_EQ(points.front().z, end.z);
      }
    }
    const auto& expected = truth.at(slot);  // slots follow the bodies' order
    ASSERT_EQ(joined.size(), expected.size()) << "slot " << slot;
    for (std::size_t p = 0; p < joined.size(); ++p) EXPECT_EQ(joined[p], expected[p]) << slot << " " << p;
  }
}

TEST(Scene, ARemovedBodyLosesItsTrailAndLabelAndAResetStartsTrailsAfresh) {
  World world(demoConfig());
  const MarkerOptions options{2.0, 10.0};
  Scene scene("world", "", world.bodies(), options);
  stepAndSend(world, scene, 3);

  WorldConfig fewer = demoConfig();
  fewer.bodies.erase(fewer.bodies.begin());  // the rod goes
  const World smaller(fewer);
  EXPECT_TRUE(scene.rebuild(smaller.bodies()));
  const MarkerArray after = scene.changes(ros::Time(2.0), smaller.bodies());
  int deleted = 0;
  for (const auto& m : after.markers) {
    if (m.action == Marker::DELETE) {
      ++deleted;
      EXPECT_TRUE(m.ns == "label" ? m.id == 0 : m.id / options.ring() == 0) << m.ns << " " << m.id;
    }
  }
  EXPECT_EQ(deleted, options.ring() + 1);  // its ring of trail pieces and its label

  scene.clearTrails();
  scene.sample(smaller.bodies());
  EXPECT_TRUE(inNamespace(scene.changes(ros::Time(3.0), smaller.bodies()), "trail").empty())
      << "one point after a reset is no strip yet";
  EXPECT_EQ(scene.clearMarkers(ros::Time(3.0)).markers.at(0).action, Marker::DELETEALL);
}

TEST(Scene, NoTrailsWhenTheirLengthIsZero) {
  World world(demoConfig());
  Scene scene("world", "", world.bodies(), MarkerOptions{0.0, 10.0});
  for (int publication = 0; publication < 10; ++publication) {
    world.step();
    scene.sample(world.bodies());
  }
  const MarkerArray changes = scene.changes(ros::Time(1.0), world.bodies());
  EXPECT_TRUE(inNamespace(changes, "trail").empty());
  EXPECT_EQ(inNamespace(changes, "label").size(), world.bodies().size());
}

// A lesson's labels: a roller's gives its critical angle (the core's, in degrees to 0.1) in place of its
// energy; a rod's is as always.
TEST(Scene, LabelsGiveTheCriticalAngleWhenAsked) {
  const World world(demoConfig());
  MarkerOptions options;
  options.critical_angles = true;
  Scene lesson("world", "", world.bodies(), options);
  Scene plain("world", "", world.bodies());
  const auto byBody = [](const MarkerArray& changes) {
    std::map<std::string, std::string> texts;
    for (const Marker* m : inNamespace(changes, "label"))
      texts[m->text.substr(0, m->text.find(':'))] = m->text;
    return texts;
  };
  const auto asked = byBody(lesson.changes(ros::Time(1.0), world.bodies()));
  const auto usual = byBody(plain.changes(ros::Time(1.0), world.bodies()));
  ASSERT_EQ(asked.size(), 3u);
  EXPECT_EQ(asked.at("rod"), usual.at("rod"));
  EXPECT_EQ(usual.at("rod").rfind("rod: E = ", 0), 0u) << usual.at("rod");
  // ball: a sphere with mu_s 0.3, tan(phi_c) = 3.5 * 0.3; hoop: a ring, tan(phi_c) = 2 * 0.3
  EXPECT_EQ(asked.at("ball"), "ball: slipping, critical angle 46.4 deg");
  EXPECT_EQ(asked.at("hoop"), "hoop: rolling, critical angle 31.0 deg");
  EXPECT_EQ(usual.at("hoop").rfind("hoop: rolling, E = ", 0), 0u) << usual.at("hoop");
}

// A race's labels: a finished racer's place and time beside the closed form's (the web view reads them in
// this form: test_web_protocol), the others' as always.
TEST(Scene, AFinishedRacersLabelGivesPlaceAndTimes) {
  WorldConfig config;
  config.race = true;
  RollerConfig sphere;
  sphere.params.incline_angle = 0.349;
  sphere.params.mu_s = 0.2;
  sphere.params.mu_d = 0.15;
  RollerConfig ring = sphere;
  ring.params.shape = Shape::Ring;
  ring.params.inertia_factor = 1.0;
  config.bodies = {{"sphere", sphere}, {"ring", ring}};
  World world(config);
  Scene scene("world", "", world.bodies());
  while (!world.bodies()[0].finish) world.step();  // the sphere down (2.0439 s), the ring on its way
  const MarkerArray changes = scene.changes(ros::Time(world.time()), world.bodies());
  std::map<std::string, std::string> texts;
  for (const Marker* m : inNamespace(changes, "label")) texts[m->text.substr(0, m->text.find(':'))] = m->text;
  EXPECT_EQ(texts.at("sphere"), "sphere: 1st, 2.0439 s (closed form 2.0439 s)");
  EXPECT_EQ(texts.at("ring").rfind("ring: rolling, E = ", 0), 0u) << texts.at("ring");
}

// A body whose fixed frame moved (a steeper slope) loses its trail: its path so far would float where the
// old slope was. The others keep theirs.
TEST(Scene, ABodyWhoseSlopeMovedStartsItsTrailAfresh) {
  World world(demoConfig());
  const MarkerOptions options{2.0, 10.0};
  Scene scene("world", "", world.bodies(), options);
  stepAndSend(world, scene, 3);

  WorldConfig steeper = demoConfig();
  std::get<RollerConfig>(steeper.bodies[1].config).params.incline_angle = 0.5;  // the ball's
  const World moved(steeper);
  scene.rebuild(moved.bodies());
  scene.sample(moved.bodies());
  const MarkerArray after = scene.changes(ros::Time(2.0), moved.bodies());
  std::map<int, int> deleted;  // by the slot of the trail (id / ring)
  for (const Marker* m : inNamespace(after, "trail")) {
    if (m->action == Marker::DELETE) ++deleted[m->id / options.ring()];
  }
  ASSERT_EQ(deleted.size(), 1u) << "only the ball's trail goes";
  EXPECT_EQ(deleted.begin()->second, options.ring());
  const int ball_slot = deleted.begin()->first;
  for (const Marker* m : inNamespace(after, "trail")) {
    if (m->action == Marker::ADD) EXPECT_NE(m->id / options.ring(), ball_slot) << "one point is no strip yet";
  }
  EXPECT_EQ(inNamespace(after, "trail").size(), static_cast<std::size_t>(options.ring()) + 2)
      << "the ball's ring of deletions and a piece for each of the other two";
}
