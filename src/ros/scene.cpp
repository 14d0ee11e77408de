#include "rigid_body_sim/ros/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <utility>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/names.h"
#include "rigid_body_sim/core/state_fields.h"
#include "rigid_body_sim/ros/messages.h"

namespace rigid_body_sim {

std_msgs::ColorRGBA rgba(float r, float g, float b, float a) {
  std_msgs::ColorRGBA color;
  color.r = r;
  color.g = g;
  color.b = b;
  color.a = a;
  return color;
}

namespace {

// --- placement (m) -------------------------------------------------------------------------------
constexpr double kRodPlaneSpacing = 1.5;  // between the planes of successive rods
constexpr double kFirstLaneY = 1.0;       // world y of the first roller's lane
constexpr double kMinLaneSpacing = 0.5;   // between roller lanes
constexpr double kLaneRadii = 3.0;        // a lane is at least this many of the largest radius wide
// Lanes are as far apart as a roller's name tag needs (laneSpacing), up to kMaxTagSpacing, beside a slope
// up to kMaxTagAngle. Beside a steeper one they are not: its bodies drop nearly straight down the screen,
// past any tag beside, and lanes further apart than the least no longer stand apart on screen in
// perspective (test_scene: at 1.4 rad with 2 m).
constexpr double kMaxTagSpacing = 3.0;
constexpr double kMaxTagAngle = 0.8;  // rad
// A steeper slope's lower end lies this much further along x than a shallower nearer one's: in perspective
// (the saved views: from the front, looking down 0.5 rad) its top face then stays above the nearer lane's,
// even nearly upright (checked for every angle in test_scene and by the picture tests' projections).
constexpr double kSteeperStagger = 0.8;
constexpr double kMaxStagger = 7.0;  // m of x a slope's top may move from x = 0 to keep lanes apart
constexpr double kViewPitch = 0.5;   // rad: the saved views look down this much, from the front
constexpr double kGridCell = 1.0;    // rviz's Grid display's cell (m): a ground frame moves by whole cells

// --- the look (m, and RGBA in [0, 1]) ------------------------------------------------------------
constexpr double kFloorLength = 40.0;  // along world x
constexpr double kFloorBehind = 2.0;   // of floor behind x = 0
constexpr double kFloorMargin = 1.0;   // of floor beyond the outermost lane on either side
constexpr double kFloorThickness = 0.02;
constexpr double kBoundedFloorWidth = 0.8;    // across a rod's plane
constexpr double kBoundedFloorRaise = 0.005;  // its top above the floor's, so that both show
constexpr double kSlopeThickness = 0.05;
constexpr double kSlopeWidth = 0.8 * kMinLaneSpacing;
constexpr double kSpokeLength = 2.02;  // of the radius: just out of the body
constexpr double kSpokeWidth = 0.25;   // of the radius
constexpr double kTrailWidth = 0.01;
constexpr float kTrailAlpha = 0.6f;
constexpr double kLabelAbove = 0.25;  // between a rod's top and its label
constexpr double kLabelHeight = 0.22;
constexpr double kTagGap = 0.05;    // between a roller and its name tag, on its right
constexpr double kClearance = 0.1;  // seen by the views, between a lane's body or tag and another lane's
constexpr double kBoardGap = 0.2;   // between a body at the first slope's top and the boards, uphill of it
constexpr double kBoardLines = 2.0;
constexpr double kLineHeight = 1.2;  // of rviz's text, over its height
// rviz's text: a glyph's width over the text's height, with a margin (measured 0.5 to 0.56, wider where
// the system's font is: Debian 13's), so that the room left for a text (lanes, boards) holds it.
constexpr double kGlyphWidth = 0.6;

// Marker namespaces: fixed, so that a user can toggle them in rviz.
const char* const kNsFloor = "floor";
const char* const kNsSlope = "slope";
const char* const kNsBody = "body";
const char* const kNsSpoke = "spoke";
const char* const kNsTrail = "trail";
const char* const kNsLabel = "label";
const char* const kNsBoard = "board";

// Of its longest line.
double textWidth(const std::string& text) {
  std::size_t longest = 0;
  for (std::size_t from = 0; from <= text.size();) {
    const std::size_t end = std::min(text.find('\n', from), text.size());
    longest = std::max(longest, end - from);
    from = end + 1;
  }
  return kGlyphWidth * kLabelHeight * static_cast<double>(longest);
}

const std_msgs::ColorRGBA kFloorColour = rgba(0.75f, 0.75f, 0.75f);
const std_msgs::ColorRGBA kBoundedFloorColour = rgba(0.5f, 0.5f, 0.5f);
const std_msgs::ColorRGBA kSlopeColour = rgba(0.55f, 0.4f, 0.25f);
const std_msgs::ColorRGBA kSpokeColour = rgba(0.1f, 0.1f, 0.1f);
const std_msgs::ColorRGBA kLabelColour = rgba(1, 1, 1);

// Every body's look, as its type gives it (ros/types/<type>_ros.h).
BodyLook lookOf(const Body& body) {
  return std::visit([](const auto& model) { return RosBodyType<TypeOfModel<decltype(model)>>::look(model); },
                    body.model);
}
std_msgs::ColorRGBA bodyColour(const Body& body) { return lookOf(body).colour; }
std::optional<Incline> inclineOf(const Body& body) { return lookOf(body).incline; }
double radiusOf(const Body& body) { return lookOf(body).radius; }
double reachOf(const Body& body) { return lookOf(body).reach; }

visualization_msgs::Marker marker(const char* ns, int id, int type, const std::string& frame,
                                  const ros::Time& stamp) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  // What a type ignores stays 0: rviz before 1.14.5 (Debian 11, Noetic's first) flags a display with a
  // warning for a line's scale.y or z, or a text's scale.x or y.
  using visualization_msgs::Marker;
  if (type == Marker::LINE_STRIP || type == Marker::LINE_LIST) m.scale.y = m.scale.z = 0.0;
  if (type == Marker::POINTS) m.scale.z = 0.0;
  if (type == Marker::TEXT_VIEW_FACING) m.scale.x = m.scale.y = 0.0;
  return m;
}

// A marker of the latched scene: stamped 0 (the latest transform), so that a late viewer draws it at once.
// Frame-locked: rviz places it by the latest transform of its frame at every frame it draws, not once on
// arrival, so that a slope whose fixed frame moved (a new angle or length) is drawn where its new frame is
// even when the scene reaches rviz before the new static transform.
visualization_msgs::Marker sceneMarker(const char* ns, int id, int type, const std::string& frame) {
  auto m = marker(ns, id, type, frame, ros::Time());
  m.frame_locked = true;
  return m;
}

// A plane frame whose y axis is the world's z, tilted down by `tilt` about its own z.
Eigen::Isometry3d uprightPlane(const Eigen::Vector3d& origin, double tilt) {
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  frame.translate(origin);
  frame.rotate(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitX()) *
               Eigen::AngleAxisd(-tilt, Eigen::Vector3d::UnitZ()));
  return frame;
}

// What the lanes keep apart: the largest roller and the widest name tag.
struct LaneLoad {
  double radius = 0.0;
  double tag = 0.0;
};

LaneLoad laneLoad(const std::vector<Body>& bodies) {
  LaneLoad load;
  for (const auto& body : bodies) {
    if (!inclineOf(body)) continue;
    load.radius = std::max(load.radius, radiusOf(body));
    load.tag = std::max(load.tag, textWidth(body.name));
  }
  return load;
}

double leastSpacing(const LaneLoad& load) { return std::max(kMinLaneSpacing, kLaneRadii * load.radius); }

// Between two lanes side by side, so that the saved views (from the front, looking down kViewPitch) see
// each body and its tag (on its right, at its height) kClearance from the other lane's, wherever each is
// on its slope: the other body, as far along x as a tag and two bodies reach, is lower on screen by its
// drop on the steeper slope (no more than that slope's height), and the lanes lie that much further apart.
double laneSpacing(const LaneLoad& load, double steeper_angle, double steeper_height) {
  const double reach = load.tag + 2.0 * load.radius + kTagGap + kClearance;
  const double least = leastSpacing(load);
  if (steeper_angle > kMaxTagAngle) return least;
  const double drop = std::min(reach * std::tan(steeper_angle), steeper_height);
  const double across = std::max(load.radius, 0.5 * kLabelHeight) + 0.5 * kLabelHeight + kClearance;
  const double clear = (across + drop * std::cos(kViewPitch)) / std::sin(kViewPitch);
  return std::max(least, std::min(clear, kMaxTagSpacing));
}

// Its shape, drawn in the body's own frame and locked to it: TF moves it, not the marker stream.
visualization_msgs::Marker bodyMarker(const Body& body, const std::string& frame, int id) {
  const BodyShape shape = std::visit(
      [](const auto& model) { return RosBodyType<TypeOfModel<decltype(model)>>::shape(model); }, body.model);
  auto m = sceneMarker(kNsBody, id, shape.type, frame);
  m.scale.x = shape.scale.x();
  m.scale.y = shape.scale.y();
  m.scale.z = shape.scale.z();
  m.pose.orientation.x = shape.orientation.x();
  m.pose.orientation.y = shape.orientation.y();
  m.pose.orientation.z = shape.orientation.z();
  m.pose.orientation.w = shape.orientation.w();
  for (const auto& point : shape.points) m.points.push_back(toPoint(point));
  m.color = bodyColour(body);
  return m;
}

// The spoke (BodyLook::spoke), along the body's x.
visualization_msgs::Marker spokeMarker(const Body& body, const std::string& frame, int id) {
  const double r = radiusOf(body);
  auto spoke = sceneMarker(kNsSpoke, id, visualization_msgs::Marker::CUBE, frame);
  spoke.scale.x = kSpokeLength * r;
  spoke.scale.y = kSpokeWidth * r;
  spoke.scale.z = kSpokeLength * r;
  spoke.color = kSpokeColour;
  spoke.frame_locked = true;
  return spoke;
}

// "1st", "2nd", "3rd", "4th" ... "11th", "12th", "13th", "21st".
std::string ordinal(int place) {
  const int tens = place % 100;
  const int last = place % 10;
  const char* suffix = (tens >= 11 && tens <= 13) || last == 0 || last > 3 ? "th"
                       : last == 1                                         ? "st"
                       : last == 2                                         ? "nd"
                                                                           : "rd";
  return std::to_string(place) + suffix;
}

// A racer over the line: its place and time beside the closed form's (the text's formulas, 16.3.2).
std::string finishText(const Body& body, const RaceFinish& finish) {
  char text[96];
  if (finish.closed_form) {
    std::snprintf(text, sizeof text, "%s, %.4f s\n(closed form %.4f s)", ordinal(finish.place).c_str(),
                  finish.time, *finish.closed_form);
  } else {
    std::snprintf(text, sizeof text, "%s, %.4f s", ordinal(finish.place).c_str(), finish.time);
  }
  return body.name + ": " + text;
}

// A rod's label and a roller's board, in two lines (half as wide: the demo's view holds the lanes, their
// boards and the rod beside them).
std::string labelText(const Body& body, bool critical_angle) {
  if (body.finish) return finishText(body, *body.finish);
  char energy[48];
  const double e = energyOf(body);
  std::snprintf(energy, sizeof energy, "E = %.3f J", std::abs(e) < 5e-4 ? 0.0 : e);  // never "-0.000"
  if (!inclineOf(body)) return body.name + ":\n" + energy;
  std::string mode;
  std::visit(
      [&](const auto& model) {
        for (const auto& field : stateFields(model)) mode += field.text;  // its one text field
      },
      body.model);
  const std::optional<double> critical_tangent = lookOf(body).critical_tangent;
  const std::string head = body.name + ": " + mode + "\n";
  if (!critical_angle || !critical_tangent) return head + energy;
  // Section 16.3.2's, for its mu_s and shape, in place of the energy (the panel plots it): a class sees
  // why one body slips.
  char critical[48];
  std::snprintf(critical, sizeof critical, "critical angle %.1f deg",
                std::atan(*critical_tangent) * 180 / kPi);
  return head + critical;
}

visualization_msgs::Marker floorMarker(const std::string& world_frame,
                                       const std::vector<BodyPlacement>& placements) {
  double min_y = 0.0;
  double max_y = 0.0;
  for (const auto& placement : placements) {
    min_y = std::min(min_y, placement.world_from_frame.translation().y());
    max_y = std::max(max_y, placement.world_from_frame.translation().y());
  }
  auto floor = sceneMarker(kNsFloor, 0, visualization_msgs::Marker::CUBE, world_frame);
  floor.pose.position.x = kFloorLength / 2 - kFloorBehind;
  floor.pose.position.y = (min_y + max_y) / 2;
  floor.pose.position.z = -kFloorThickness / 2;
  floor.scale.x = kFloorLength;
  floor.scale.y = max_y - min_y + 2 * kFloorMargin;
  floor.scale.z = kFloorThickness;
  floor.color = kFloorColour;
  return floor;
}

// A rod's bounded floor: a darker strip over x in [0, floor_length] of its floor frame (ids after the
// floor's 0).
visualization_msgs::Marker boundedFloorMarker(const BodyPlacement& placement, int id) {
  const double floor_length = placement.floor_length;
  auto strip = sceneMarker(kNsFloor, id, visualization_msgs::Marker::CUBE, placement.frame);
  strip.pose.position.x = floor_length / 2;
  strip.pose.position.y = kBoundedFloorRaise - kFloorThickness / 2;
  strip.scale.x = floor_length;
  strip.scale.y = kFloorThickness;
  strip.scale.z = kBoundedFloorWidth;
  strip.color = kBoundedFloorColour;
  return strip;
}

// A rod's unbounded floor, in its ground frame: as long as the world's floor, centred under the rod's
// rounded x, raised as a bounded one (above the world's floor where both are) in the floor's colour.
visualization_msgs::Marker groundMarker(const BodyPlacement& placement, int id) {
  auto ground = sceneMarker(kNsFloor, id, visualization_msgs::Marker::CUBE, placement.ground_frame);
  ground.pose.position.y = placement.world_from_frame.translation().y();
  ground.pose.position.z = kBoundedFloorRaise - kFloorThickness / 2;
  ground.scale.x = kFloorLength;
  ground.scale.y = 2 * kFloorMargin;
  ground.scale.z = kFloorThickness;
  ground.color = kFloorColour;
  return ground;
}

visualization_msgs::Marker slopeMarker(const BodyPlacement& placement, int id) {
  const double length = placement.slope_length;
  auto slope = sceneMarker(kNsSlope, id, visualization_msgs::Marker::CUBE, placement.frame);
  slope.pose.position.x = length / 2;
  slope.pose.position.y = -kSlopeThickness / 2;
  slope.scale.x = length;
  slope.scale.y = kSlopeThickness;
  slope.scale.z = kSlopeWidth;
  slope.color = kSlopeColour;
  return slope;
}

// White text of kLabelHeight in the world frame, centred on its position (rviz's), facing the view.
visualization_msgs::Marker textMarker(const char* ns, int id, const std::string& text, const ros::Time& stamp,
                                      const std::string& frame) {
  auto m = marker(ns, id, visualization_msgs::Marker::TEXT_VIEW_FACING, frame, stamp);
  m.text = text;
  m.scale.z = kLabelHeight;
  m.color = kLabelColour;
  return m;
}

visualization_msgs::Marker deleteAll(const std::string& frame, const ros::Time& stamp) {
  auto m = marker("", 0, visualization_msgs::Marker::CUBE, frame, stamp);
  m.action = visualization_msgs::Marker::DELETEALL;
  return m;
}

// Where each roller's board ends (its right end's centre; a rod's entry unused): in its lane's plane, before
// the first slope's top, clear of every body there; at its body's height at its slope's top, or higher, so
// that, seen from the front looking down kViewPitch, it stands a board and kClearance above the nearer
// lane's board.
std::vector<Eigen::Vector3d> boardEnds(const std::vector<BodyPlacement>& placements, const LaneLoad& load) {
  std::vector<std::size_t> lanes;
  double first_top = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < placements.size(); ++i) {
    if (placements[i].slope_length <= 0.0) continue;
    lanes.push_back(i);
    first_top = std::min(first_top, placements[i].world_from_frame.translation().x());
  }
  std::sort(lanes.begin(), lanes.end(), [&](std::size_t a, std::size_t b) {
    return placements[a].world_from_frame.translation().y() <
           placements[b].world_from_frame.translation().y();
  });
  std::vector<Eigen::Vector3d> ends(placements.size(), Eigen::Vector3d::Zero());
  const double board_height = kBoardLines * kLineHeight * kLabelHeight;
  const Eigen::Vector3d* nearer = nullptr;
  for (const std::size_t i : lanes) {
    const Eigen::Vector3d top = placements[i].world_from_frame.translation();
    Eigen::Vector3d end(first_top - load.radius - kBoardGap, top.y(), top.z() + load.radius);
    if (nearer) {
      const double above = board_height + kClearance - (end.y() - nearer->y()) * std::sin(kViewPitch);
      end.z() = std::max(end.z(), nearer->z() + above / std::cos(kViewPitch));
    }
    ends[i] = end;
    nearer = &ends[i];
  }
  return ends;
}

Eigen::Vector3d worldPosition(const BodyPlacement& placement, const Body& body) {
  return (placement.world_from_frame * frameFromBody(body)).translation();
}

}  // namespace

// A slope seen from the side: its top x, its lower end x, the tangent of its angle.
struct Profile {
  double top_x;
  double end_x;
  double tangent;
  double heightAt(double x) const { return std::isfinite(tangent) ? tangent * (end_x - x) : 0.0; }
};

// How far a nearer slope stands above a further one where both are: the larger difference at the ends of
// their common stretch (both are straight), 0 without one.
double standsAbove(const Profile& nearer, const Profile& further) {
  const double from = std::max(nearer.top_x, further.top_x);
  const double to = std::min(nearer.end_x, further.end_x);
  if (from > to) return 0.0;
  return std::max(
      {0.0, nearer.heightAt(from) - further.heightAt(from), nearer.heightAt(to) - further.heightAt(to)});
}

std::vector<Lane> placeLanes(const std::vector<Body>& bodies) {
  struct Slope {
    std::size_t roller;  // its place among the rollers
    double angle;
    double run;     // m along x
    double height;  // m
  };
  std::vector<Slope> slopes;
  for (const auto& body : bodies) {
    if (const auto incline = inclineOf(body)) {
      slopes.push_back({slopes.size(), incline->angle,
                        std::max(0.0, incline->length * std::cos(incline->angle)),
                        std::max(0.0, incline->length * std::sin(incline->angle))});
    }
  }
  // Nearest the shallowest: seen from the side, a steeper slope whose lower end is at or beyond a shallower
  // one's stands above it wherever both are, as a further lane does on screen.
  std::stable_sort(slopes.begin(), slopes.end(),
                   [](const Slope& a, const Slope& b) { return a.angle < b.angle; });
  const LaneLoad load = laneLoad(bodies);
  const double least = leastSpacing(load);
  // Lanes are sorted shallowest first: of two, the further is the steeper.
  const auto spacing = [&](std::size_t nearer, std::size_t further) {
    const Slope& steeper = slopes[further].angle >= slopes[nearer].angle ? slopes[further] : slopes[nearer];
    return laneSpacing(load, steeper.angle, steeper.height);
  };
  std::vector<Lane> lanes(slopes.size());
  std::vector<std::pair<double, double>> placed;  // top x, lower end x of the lanes so far, nearest first
  for (std::size_t k = 0; k < slopes.size(); ++k) {
    const Slope& slope = slopes[k];
    // Its lower end at or beyond every nearer lane's (0.8 m beyond a shallower one's), but for a lane that
    // would move it more than kMaxStagger along (a long shallow slope nearer: the demo's bowler's): behind
    // that one its lane lies further back instead, by what the views need to see it above it (seen from
    // the side, 1/tan(0.5) m for every metre that one stands higher, beyond the least spacing) if the
    // spacing its tags need does not put it further.
    double end = slope.run;
    for (std::size_t i = 0; i < k; ++i) {
      const double beyond = placed[i].second + (slope.angle > slopes[i].angle ? kSteeperStagger : 0.0);
      if (beyond - slope.run <= kMaxStagger) end = std::max(end, beyond);
    }
    double y = kFirstLaneY;
    for (std::size_t i = 0; i < k; ++i) {
      const Profile nearer{placed[i].first, placed[i].second, std::tan(slopes[i].angle)};
      const Profile further{end - slope.run, end, std::tan(slope.angle)};
      const double back = least + standsAbove(nearer, further) / std::tan(kViewPitch);
      y = std::max(y, lanes[slopes[i].roller].y + std::max(spacing(i, k), back));
    }
    placed.emplace_back(end - slope.run, end);
    lanes[slope.roller] = {end - slope.run, y, k};
  }
  return lanes;
}

std::vector<BodyPlacement> placeBodies(const std::vector<Body>& bodies, const std::string& frame_prefix) {
  const std::vector<Lane> lanes = placeLanes(bodies);
  int rods = 0;
  int on_slopes = 0;
  std::vector<BodyPlacement> placements;
  for (const auto& body : bodies) {
    const std::string frame = frame_prefix + fixedFrameOf(body);
    const BodyLook look = lookOf(body);
    if (look.incline) {
      const Incline incline = *look.incline;
      const double top = incline.length * std::sin(incline.angle);
      const Lane& lane = lanes[static_cast<std::size_t>(on_slopes++)];
      placements.push_back(
          {frame, uprightPlane({lane.top_x, lane.y, top}, incline.angle), incline.length, 0.0, ""});
    } else {
      placements.push_back({frame, uprightPlane({0.0, -kRodPlaneSpacing * rods++, 0.0}, 0.0), 0.0,
                            look.floor_length,
                            look.floor_length > 0.0 ? "" : frame_prefix + groundFrameOf(body.name)});
    }
  }
  return placements;
}

Eigen::Isometry3d worldFromGround(const BodyPlacement& placement, const Body& body) {
  const double x = worldPosition(placement, body).x();
  Eigen::Isometry3d ground = Eigen::Isometry3d::Identity();
  ground.translate(Eigen::Vector3d(kGridCell * std::round(x / kGridCell), 0.0, 0.0));
  return ground;
}

Eigen::Isometry3d frameFromBody(const Body& body) { return lookOf(body).pose; }

int MarkerOptions::ring() const {
  if (seconds <= 0.0) return 0;
  return std::max(1, static_cast<int>(std::ceil(seconds * pieces_rate - 1e-9)));
}

Scene::Scene(std::string world_frame, std::string frame_prefix, const std::vector<Body>& bodies,
             MarkerOptions trail)
    : world_frame_(std::move(world_frame)), frame_prefix_(std::move(frame_prefix)), marker_options_(trail) {
  rebuild(bodies);
}

Scene::Trail& Scene::trailOf(const std::string& body) {
  auto found = trails_.find(body);
  if (found != trails_.end()) return found->second;
  Trail& trail = trails_[body];
  trail.slot = next_slot_++;
  return trail;
}

bool Scene::rebuild(const std::vector<Body>& bodies) {
  std::map<std::string, Eigen::Matrix4d> before;
  for (const auto& placement : placements_) before[placement.frame] = placement.world_from_frame.matrix();
  placements_ = placeBodies(bodies, frame_prefix_);
  std::map<std::string, Trail> kept;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    Trail& trail = trailOf(bodies[i].name);
    const auto was = before.find(placements_[i].frame);
    if (was != before.end() && was->second != placements_[i].world_from_frame.matrix()) {
      moved_slots_.push_back(trail.slot);
      trail = Trail{trail.slot, {}, {}, 0};
    }
    kept[bodies[i].name] = trail;
  }
  for (const auto& [name, trail] : trails_) {
    if (!kept.count(name)) removed_slots_.push_back(trail.slot);
  }
  trails_ = std::move(kept);

  const LaneLoad load = laneLoad(bodies);
  board_ends_ = boardEnds(placements_, load);

  visualization_msgs::MarkerArray scene;
  scene.markers.push_back(deleteAll(world_frame_, ros::Time()));
  scene.markers.push_back(floorMarker(world_frame_, placements_));
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const int id = trails_.at(bodies[i].name).slot;
    const std::string frame = bodyFrame(bodies[i]);
    if (placements_[i].floor_length > 0.0)
      scene.markers.push_back(boundedFloorMarker(placements_[i], id + 1));
    if (!placements_[i].ground_frame.empty()) scene.markers.push_back(groundMarker(placements_[i], id + 1));
    if (placements_[i].slope_length > 0.0) scene.markers.push_back(slopeMarker(placements_[i], id));
    scene.markers.push_back(bodyMarker(bodies[i], frame, id));
    if (lookOf(bodies[i]).spoke) scene.markers.push_back(spokeMarker(bodies[i], frame, id));
  }
  if (scene == scene_) return false;
  scene_ = std::move(scene);
  return true;
}

void Scene::sample(const std::vector<Body>& bodies) {
  if (marker_options_.ring() == 0) return;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    trailOf(bodies[i].name).pending.push_back(worldPosition(placements_[i], bodies[i]));
  }
}

visualization_msgs::MarkerArray Scene::changes(const ros::Time& stamp, const std::vector<Body>& bodies) {
  visualization_msgs::MarkerArray array;
  const int ring = marker_options_.ring();
  const auto deleteTrail = [&](int slot) {
    for (int k = 0; k < ring; ++k) {
      auto gone =
          marker(kNsTrail, slot * ring + k, visualization_msgs::Marker::LINE_STRIP, world_frame_, stamp);
      gone.action = visualization_msgs::Marker::DELETE;
      array.markers.push_back(gone);
    }
  };
  for (const int slot : removed_slots_) {
    deleteTrail(slot);
    for (const char* ns : {kNsLabel, kNsBoard}) {
      auto text = marker(ns, slot, visualization_msgs::Marker::TEXT_VIEW_FACING, world_frame_, stamp);
      text.action = visualization_msgs::Marker::DELETE;
      array.markers.push_back(text);
    }
  }
  removed_slots_.clear();
  for (const int slot : moved_slots_) deleteTrail(slot);  // before the new pieces, which take ids from 0
  moved_slots_.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    Trail& trail = trailOf(body.name);
    if (!trail.pending.empty()) {
      auto piece = marker(kNsTrail, trail.slot * ring + static_cast<int>(trail.pieces % ring),
                          visualization_msgs::Marker::LINE_STRIP, world_frame_, stamp);
      piece.scale.x = kTrailWidth;
      piece.color = bodyColour(body);
      piece.color.a = kTrailAlpha;
      if (trail.last) piece.points.push_back(toPoint(*trail.last));
      for (const auto& point : trail.pending) piece.points.push_back(toPoint(point));
      trail.last = trail.pending.back();
      trail.pending.clear();
      // A strip needs two points: a first piece of one point is only where the next one starts.
      if (piece.points.size() >= 2) {
        array.markers.push_back(std::move(piece));
        ++trail.pieces;
      }
    }
    const Eigen::Vector3d at = worldPosition(placements_[i], body);
    if (!inclineOf(body)) {
      // Above the rod, in its own plane: its lower line's centre kLabelAbove over the rod's reach.
      auto label = textMarker(kNsLabel, trail.slot, labelText(body, marker_options_.critical_angles), stamp,
                              world_frame_);
      const double above =
          reachOf(body) + kLabelAbove + 0.5 * (kBoardLines - 1.0) * kLineHeight * kLabelHeight;
      label.pose.position = toPoint(at + Eigen::Vector3d(0.0, 0.0, above));
      array.markers.push_back(std::move(label));
      continue;
    }
    // A name on a slope on its right, at its height: the lanes are apart enough for it (laneSpacing). What
    // it does (its mode and energy or critical angle, a racer's place and times) is on its lane's board,
    // ending before its slope's top, where no body goes.
    auto tag = textMarker(kNsLabel, trail.slot, body.name, stamp, world_frame_);
    tag.pose.position =
        toPoint(at + Eigen::Vector3d(radiusOf(body) + kTagGap + 0.5 * textWidth(tag.text), 0.0, 0.0));
    array.markers.push_back(std::move(tag));
    auto board = textMarker(kNsBoard, trail.slot, labelText(body, marker_options_.critical_angles), stamp,
                            world_frame_);
    board.pose.position = toPoint(board_ends_[i] - Eigen::Vector3d(0.5 * textWidth(board.text), 0.0, 0.0));
    array.markers.push_back(std::move(board));
  }
  return array;
}

void Scene::clearTrails() {
  for (auto& [name, trail] : trails_) {
    trail.pending.clear();
    trail.last.reset();
  }
}

visualization_msgs::MarkerArray Scene::clearMarkers(const ros::Time& stamp) const {
  visualization_msgs::MarkerArray array;
  array.markers.push_back(deleteAll(world_frame_, stamp));
  return array;
}

}  // namespace rigid_body_sim
