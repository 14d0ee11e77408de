// The scene's markers against the core World: the latched scene changes only with the bodies' look, the
// trail pieces carry only the points added since the last piece and join up into the trajectory, and no
// marker carries a non-finite number.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/ros/scene.h"
#include "rigid_body_sim/ros/snapshot.h"

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
  EXPECT_EQ(inNamespace(markers, "floor").size(), 2u);  // the world's and the rod's unbounded one
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
      EXPECT_TRUE(m.ns == "label" || m.ns == "board" ? m.id == 0 : m.id / options.ring() == 0)
          << m.ns << " " << m.id;
    }
  }
  EXPECT_EQ(deleted, options.ring() + 2);  // its ring of trail pieces, its label and its board (a roller's)

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

// A lesson's boards: a roller's gives its critical angle (the core's, in degrees to 0.1) in place of its
// energy; a rod's label is as always. A roller's label is its name.
TEST(Scene, LabelsGiveTheCriticalAngleWhenAsked) {
  const World world(demoConfig());
  MarkerOptions options;
  options.critical_angles = true;
  Scene lesson("world", "", world.bodies(), options);
  Scene plain("world", "", world.bodies());
  const auto byBody = [](const MarkerArray& changes) {
    std::map<std::string, std::string> texts;
    for (const char* ns : {"label", "board"}) {
      for (const Marker* m : inNamespace(changes, ns)) {
        if (m->text.find(':') != std::string::npos) texts[m->text.substr(0, m->text.find(':'))] = m->text;
      }
    }
    return texts;
  };
  std::set<std::string> labels;
  const MarkerArray sent = lesson.changes(ros::Time(1.0), world.bodies());
  for (const Marker* m : inNamespace(sent, "label")) labels.insert(m->text.substr(0, m->text.find("\nE = ")));
  EXPECT_EQ(labels, (std::set<std::string>{"ball", "hoop", "rod:"}));
  const auto asked = byBody(lesson.changes(ros::Time(1.0), world.bodies()));
  const auto usual = byBody(plain.changes(ros::Time(1.0), world.bodies()));
  ASSERT_EQ(asked.size(), 3u);
  EXPECT_EQ(asked.at("rod"), usual.at("rod"));
  EXPECT_EQ(usual.at("rod").rfind("rod:\nE = ", 0), 0u) << usual.at("rod");
  // ball: a sphere with mu_s 0.3, tan(phi_c) = 3.5 * 0.3; hoop: a ring, tan(phi_c) = 2 * 0.3
  EXPECT_EQ(asked.at("ball"), "ball: slipping\ncritical angle 46.4 deg");
  EXPECT_EQ(asked.at("hoop"), "hoop: rolling\ncritical angle 31.0 deg");
  EXPECT_EQ(usual.at("hoop").rfind("hoop: rolling\nE = ", 0), 0u) << usual.at("hoop");
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
  for (const Marker* m : inNamespace(changes, "board")) texts[m->text.substr(0, m->text.find(':'))] = m->text;
  EXPECT_EQ(texts.at("sphere"), "sphere: 1st, 2.0439 s\n(closed form 2.0439 s)");
  EXPECT_EQ(texts.at("ring").rfind("ring: rolling\nE = ", 0), 0u) << texts.at("ring");
}

// A body whose fixed frame moved (a steeper slope) loses its trail: its path so far would float where the
// old slope was. The others keep theirs (the hoop's lane is the furthest: no other lane moves back).
TEST(Scene, ABodyWhoseSlopeMovedStartsItsTrailAfresh) {
  World world(demoConfig());
  const MarkerOptions options{2.0, 10.0};
  Scene scene("world", "", world.bodies(), options);
  stepAndSend(world, scene, 3);

  WorldConfig steeper = demoConfig();
  std::get<RollerConfig>(steeper.bodies[2].config).params.incline_angle =
      0.5;  // the hoop's, the furthest lane
  const World moved(steeper);
  scene.rebuild(moved.bodies());
  scene.sample(moved.bodies());
  const MarkerArray after = scene.changes(ros::Time(2.0), moved.bodies());
  std::map<int, int> deleted;  // by the slot of the trail (id / ring)
  for (const Marker* m : inNamespace(after, "trail")) {
    if (m->action == Marker::DELETE) ++deleted[m->id / options.ring()];
  }
  ASSERT_EQ(deleted.size(), 1u) << "only the hoop's trail goes";
  EXPECT_EQ(deleted.begin()->second, options.ring());
  const int hoop_slot = deleted.begin()->first;
  for (const Marker* m : inNamespace(after, "trail")) {
    if (m->action == Marker::ADD) EXPECT_NE(m->id / options.ring(), hoop_slot) << "one point is no strip yet";
  }
  EXPECT_EQ(inNamespace(after, "trail").size(), static_cast<std::size_t>(options.ring()) + 2)
      << "the hoop's ring of deletions and a piece for each of the other two";
}

namespace {

// A slope's top and lower end in the world (its frame's origin and x = L).
std::pair<Eigen::Vector3d, Eigen::Vector3d> slopeEnds(const BodyPlacement& placement) {
  return {placement.world_from_frame.translation(),
          placement.world_from_frame * Eigen::Vector3d(placement.slope_length, 0.0, 0.0)};
}

// The slope's height over world x (between its ends), seen from the side.
double heightAt(const std::pair<Eigen::Vector3d, Eigen::Vector3d>& ends, double x) {
  const auto& [top, bottom] = ends;
  const double run = bottom.x() - top.x();
  return run > 1e-12 ? top.z() + (bottom.z() - top.z()) * (x - top.x()) / run : top.z();
}

}  // namespace

// Angles across the key's whole range [0, pi/2) on each of three slopes, of a race's and the demo's lengths:
// seen from the side, each further lane stands nowhere below a nearer one where both are (a steeper one
// ends 0.8 m beyond a shallower one, or wholly before it), or lies back as far as a view looking down
// 0.5 rad needs; the lanes never overlap and the first top is at x = 0.
TEST(Scene, LanesNeverCrossWhateverTheAngles) {
  // The key's range [0, pi/2): k pi / 48 for k = 0 ... 23, and the largest double below pi / 2.
  std::vector<double> angles;
  for (int k = 0; k < 24; ++k) angles.push_back(kPi / 48 * k);
  angles.push_back(std::nextafter(kPi / 2, 0.0));
  const std::size_t n = angles.size();
  long checked = 0;
  for (const double long_slope : {5.0, 15.0}) {
    for (std::size_t a = 0; a < n; ++a) {
      for (std::size_t b = 0; b < n; ++b) {
        for (std::size_t c = 0; c < n; c += 2) {
          WorldConfig config;
          const double lengths[] = {5.0, long_slope, 2.0};
          const std::size_t picks[] = {a, b, c};
          config.bodies.push_back({"rod", RodConfig{}});
          for (int k = 0; k < 3; ++k) {
            RollerConfig roller;
            roller.params.incline_angle = angles[picks[k]];
            roller.params.incline_length = lengths[k];
            config.bodies.push_back({"r" + std::to_string(k), roller});
          }
          const World world(config);
          auto placements = placeBodies(world.bodies());
          placements.erase(placements.begin());  // the rod's
          std::sort(placements.begin(), placements.end(), [](const BodyPlacement& p, const BodyPlacement& q) {
            return p.world_from_frame.translation().y() < q.world_from_frame.translation().y();
          });
          double first_top = std::numeric_limits<double>::infinity();
          for (std::size_t i = 0; i < placements.size(); ++i) {
            const auto nearer = slopeEnds(placements[i]);
            first_top = std::min(first_top, nearer.first.x());
            for (std::size_t j = i + 1; j < placements.size(); ++j) {
              const auto further = slopeEnds(placements[j]);
              ASSERT_GE(further.first.y() - nearer.first.y(), 0.5 - 1e-12);
              const double from = std::max(nearer.first.x(), further.first.x());
              const double to = std::min(nearer.second.x(), further.second.x());
              // Where both are, the further slope stands above, or its lane lies back by 1/tan(0.5) m for
              // every metre the nearer one stands higher (a long shallow slope nearer: the demo's bowler).
              double higher = 0.0;
              for (int s = 0; s <= 20 && from + 1e-9 < to; ++s) {  // more than a point
                const double x = from + (to - from) * s / 20;
                higher = std::max(higher, heightAt(nearer, x) - heightAt(further, x));
                ++checked;
              }
              const double back = further.first.y() - nearer.first.y() - 0.5;
              ASSERT_GE(back + 1e-9, higher / std::tan(0.5))
                  << "angles " << angles[a] << ", " << angles[b] << ", " << angles[c];
            }
          }
          ASSERT_NEAR(first_top, 0.0, 1e-12);
        }
      }
    }
  }
  EXPECT_GT(checked, 100000);
}

// The text's rod on its unbounded floor, published for a minute: its ground frame is always at a whole
// metre within half a metre of the rod, and its floor marker, drawn there, always reaches 10 m beyond it.
TEST(Scene, AnUnboundedFloorIsUnderTheRodThroughoutARun) {
  WorldConfig config;
  config.bodies = {{"rod", RodConfig{}}};
  World world(config);
  const SnapshotBuilder snapshots("world", "", world.bodies());
  const Marker* ground = nullptr;
  for (const auto& m : snapshots.scene().sceneMarkers().markers) {
    if (m.ns == "floor" && m.header.frame_id == "rod_ground") ground = &m;
  }
  ASSERT_NE(ground, nullptr);
  EXPECT_TRUE(ground->frame_locked);
  double furthest = 0.0;
  for (int publication = 0; publication <= 60 * 50; ++publication) {
    const double t = world.time();
    const Snapshot snapshot = snapshots.build(t, ros::Time(1.0 + t), world.bodies());
    ASSERT_EQ(snapshot.tf.transforms.size(), 2u);
    const auto& body = snapshot.tf.transforms[0].transform.translation;
    const auto& frame = snapshot.tf.transforms[1];
    EXPECT_EQ(frame.child_frame_id, "rod_ground");
    EXPECT_EQ(frame.header.stamp, snapshot.tf.transforms[0].header.stamp);
    const double x = frame.transform.translation.x;
    ASSERT_EQ(x, std::round(x)) << "t = " << t;
    ASSERT_LE(std::abs(body.x - x), 0.5 + 1e-9) << "t = " << t;
    ASSERT_LE(std::abs(body.x - (x + ground->pose.position.x)) + 10.0, 0.5 * ground->scale.x) << "t = " << t;
    ASSERT_EQ(frame.transform.translation.y, 0.0);
    furthest = std::max(furthest, body.x);
    for (int step = 0; step < kStepsPerPublication; ++step) world.step();
  }
  EXPECT_GT(furthest, 100.0) << "the rod goes far beyond the world's 40 m floor";
}

// A bounded floor is drawn where it is: no ground frame.
TEST(Scene, ABoundedFloorHasNoGroundFrame) {
  WorldConfig config;
  RodConfig rod;
  rod.params.floor_length = 10.0;
  config.bodies = {{"rod", rod}};
  const World world(config);
  const SnapshotBuilder snapshots("world", "", world.bodies());
  EXPECT_EQ(snapshots.build(0.0, ros::Time(1.0), world.bodies()).tf.transforms.size(), 1u);
  for (const auto& m : snapshots.scene().sceneMarkers().markers) EXPECT_NE(m.header.frame_id, "rod_ground");
}

namespace {

// rviz's Orbit view (as test/pictures/picture_check.py's Camera): screen coordinates up to a scale, which
// leaves apart what is apart.
struct OrbitView {
  Eigen::Vector3d eye, forward, right, up;
  explicit OrbitView(const std::string& file) {
    const YAML::Node view = YAML::LoadFile(file)["Visualization Manager"]["Views"]["Current"];
    const Eigen::Vector3d focal(view["Focal Point"]["X"].as<double>(), view["Focal Point"]["Y"].as<double>(),
                                view["Focal Point"]["Z"].as<double>());
    const double distance = view["Distance"].as<double>();
    const double pitch = view["Pitch"].as<double>();
    const double yaw = view["Yaw"].as<double>();
    eye = focal + distance * Eigen::Vector3d(std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch),
                                             std::sin(pitch));
    forward = (focal - eye).normalized();
    right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
    up = right.cross(forward);
  }
  Eigen::Vector2d project(const Eigen::Vector3d& point) const {
    const Eigen::Vector3d rel = point - eye;
    return Eigen::Vector2d(rel.dot(right), rel.dot(up)) / rel.dot(forward);
  }
};

// Whether two convex polygons (vertices in any order around) have a separating line: an edge's normal.
bool apart(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
  const auto separated_by_an_edge_of = [&](const std::vector<Eigen::Vector2d>& poly) {
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d edge = poly[(i + 1) % poly.size()] - poly[i];
      const Eigen::Vector2d normal(-edge.y(), edge.x());
      double a_min = INFINITY, a_max = -INFINITY, b_min = INFINITY, b_max = -INFINITY;
      for (const auto& p : a) a_min = std::min(a_min, p.dot(normal)), a_max = std::max(a_max, p.dot(normal));
      for (const auto& p : b) b_min = std::min(b_min, p.dot(normal)), b_max = std::max(b_max, p.dot(normal));
      if (a_max < b_min || b_max < a_min) return true;
    }
    return false;
  };
  return separated_by_an_edge_of(a) || separated_by_an_edge_of(b);
}

// A slope's top face (0.4 m wide, as drawn) on screen: its four corners, in order around.
std::vector<Eigen::Vector2d> topFace(const OrbitView& view, const BodyPlacement& placement) {
  std::vector<Eigen::Vector2d> face;
  const double corners[4][2] = {
      {0.0, -0.2}, {placement.slope_length, -0.2}, {placement.slope_length, 0.2}, {0.0, 0.2}};
  for (const auto& [x, z] : corners)
    face.push_back(view.project(placement.world_from_frame * Eigen::Vector3d(x, 0, z)));
  return face;
}

}  // namespace

// Through the cameras of the saved views with slopes (the demo's, incline.launch's, the lesson's races),
// three slopes of the views' lengths at every angle of the key's range: no slope's top face meets
// another's on screen.
TEST(Scene, LanesStayApartInTheSavedViewsWhateverTheAngles) {
  std::vector<double> angles;
  for (int k = 0; k < 24; ++k) angles.push_back(kPi / 48 * k);
  angles.push_back(std::nextafter(kPi / 2, 0.0));
  for (const char* file : {"sim.rviz", "incline.rviz", "lesson_race.rviz", "lesson_above.rviz"}) {
    const OrbitView view(std::string(RBS_RVIZ_DIR) + "/" + file);
    for (const double first_length : {5.0, 3.5}) {
      for (const double a : angles) {
        for (const double b : angles) {
          for (const double c : angles) {
            WorldConfig config;
            const double picks[] = {a, b, c};
            for (int k = 0; k < 3; ++k) {
              RollerConfig roller;
              roller.params.radius = 0.15;
              roller.params.incline_angle = picks[k];
              roller.params.incline_length = k == 0 ? first_length : 5.0;
              config.bodies.push_back({"r" + std::to_string(k), roller});
            }
            const World world(config);
            const auto placements = placeBodies(world.bodies());
            for (std::size_t i = 0; i < placements.size(); ++i) {
              for (std::size_t j = i + 1; j < placements.size(); ++j) {
                ASSERT_TRUE(apart(topFace(view, placements[i]), topFace(view, placements[j])))
                    << file << ": angles " << a << ", " << b << ", " << c << "; lanes " << i << ", " << j;
              }
            }
          }
        }
      }
    }
  }
}
