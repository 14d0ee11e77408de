#include "rigid_body_sim/ros/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/ros/messages.h"

namespace rigid_body_sim {

namespace {

// --- placement (m) -------------------------------------------------------------------------------
constexpr double kRodPlaneSpacing = 1.5;  // between the planes of successive rods
constexpr double kFirstLaneY = 1.0;       // world y of the first roller's lane
constexpr double kMinLaneSpacing = 0.5;   // between roller lanes
constexpr double kLaneRadii = 3.0;        // a lane is at least this many of the largest radius wide

// --- the look (m, and RGBA in [0, 1]) ------------------------------------------------------------
constexpr double kFloorLength = 40.0;  // along world x
constexpr double kFloorBehind = 2.0;   // of floor behind x = 0
constexpr double kFloorMargin = 1.0;   // of floor beyond the outermost lane on either side
constexpr double kFloorThickness = 0.02;
constexpr double kBoundedFloorWidth = 0.8;    // across a rod's plane
constexpr double kBoundedFloorRaise = 0.005;  // its top above the floor's, so that both show
constexpr double kSlopeThickness = 0.05;
constexpr double kSlopeWidth = 0.8 * kMinLaneSpacing;
constexpr double kRodThickness = 0.05;   // also a rod's "radius" for its label
constexpr double kCylinderLength = 0.8;  // of a cylinder's diameter
constexpr double kRingWidth = 0.15;      // of a ring's radius
constexpr int kRingSegments = 48;
constexpr double kSpokeLength = 2.02;  // of the radius: just out of the body
constexpr double kSpokeWidth = 0.25;   // of the radius
constexpr double kTrailWidth = 0.01;
constexpr float kTrailAlpha = 0.6f;
constexpr double kLabelAbove = 0.35;  // between the body's top and its label
constexpr double kLabelHeight = 0.15;

// Marker namespaces: fixed, so that a user can toggle them in rviz.
const char* const kNsFloor = "floor";
const char* const kNsSlope = "slope";
const char* const kNsBody = "body";
const char* const kNsSpoke = "spoke";
const char* const kNsTrail = "trail";
const char* const kNsLabel = "label";

std_msgs::ColorRGBA rgba(float r, float g, float b, float a = 1.0f) {
  std_msgs::ColorRGBA color;
  color.r = r;
  color.g = g;
  color.b = b;
  color.a = a;
  return color;
}

const std_msgs::ColorRGBA kFloorColour = rgba(0.75f, 0.75f, 0.75f);
const std_msgs::ColorRGBA kBoundedFloorColour = rgba(0.5f, 0.5f, 0.5f);
const std_msgs::ColorRGBA kSlopeColour = rgba(0.55f, 0.4f, 0.25f);
const std_msgs::ColorRGBA kSpokeColour = rgba(0.1f, 0.1f, 0.1f);
const std_msgs::ColorRGBA kLabelColour = rgba(1, 1, 1);

std_msgs::ColorRGBA bodyColour(const Body& body) {
  if (std::holds_alternative<Rod>(body.model)) return rgba(0.1f, 0.3f, 0.9f);
  switch (std::get<Roller>(body.model).params().shape) {
    case Shape::Sphere: return rgba(0.9f, 0.1f, 0.1f);
    case Shape::Cylinder: return rgba(0.1f, 0.8f, 0.1f);
    case Shape::Ring: return rgba(1.0f, 0.6f, 0.0f);
    case Shape::SphericalShell: return rgba(0.7f, 0.1f, 0.9f);
    case Shape::Custom: return rgba(0.6f, 0.6f, 0.6f);
  }
  return rgba(1, 1, 1);
}

double radiusOf(const Body& body) {
  if (const auto* roller = std::get_if<Roller>(&body.model)) return roller->params().radius;
  return kRodThickness;
}

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

double laneSpacing(const std::vector<Body>& bodies) {
  double largest_radius = 0.0;
  for (const auto& body : bodies) {
    if (std::holds_alternative<Roller>(body.model)) largest_radius = std::max(largest_radius, radiusOf(body));
  }
  return std::max(kMinLaneSpacing, kLaneRadii * largest_radius);
}

visualization_msgs::Marker rollerShapeMarker(const Body& body, const std::string& frame, int id,
                                             const ros::Time& stamp) {
  const RollerParams& p = std::get<Roller>(body.model).params();
  const double d = 2.0 * p.radius;
  if (p.shape == Shape::Ring) {
    auto ring = marker(kNsBody, id, visualization_msgs::Marker::LINE_STRIP, frame, stamp);
    ring.scale.x = kRingWidth * p.radius;
    for (int i = 0; i <= kRingSegments; ++i) {
      const double a = 2.0 * kPi * i / kRingSegments;
      ring.points.push_back(toPoint({p.radius * std::cos(a), p.radius * std::sin(a), 0.0}));
    }
    return ring;
  }
  const bool cylinder = p.shape == Shape::Cylinder;
  auto shape = marker(kNsBody, id,
                      cylinder ? visualization_msgs::Marker::CYLINDER : visualization_msgs::Marker::SPHERE,
                      frame, stamp);
  shape.scale.x = shape.scale.y = d;
  shape.scale.z = cylinder ? kCylinderLength * d : d;
  return shape;
}

visualization_msgs::Marker bodyMarker(const Body& body, const std::string& frame, int id,
                                      const ros::Time& stamp) {
  visualization_msgs::Marker m;
  if (const auto* rod = std::get_if<Rod>(&body.model)) {
    m = marker(kNsBody, id, visualization_msgs::Marker::CYLINDER, frame, stamp);
    // A marker cylinder lies along its z; the rod lies along its frame's x.
    m.pose.orientation.y = std::sin(kPi / 4);
    m.pose.orientation.w = std::cos(kPi / 4);
    m.scale.x = m.scale.y = kRodThickness;
    m.scale.z = rod->params().length;
  } else {
    m = rollerShapeMarker(body, frame, id, stamp);
  }
  m.color = bodyColour(body);
  return m;
}

// A dark bar through the centre along the body's x: it turns with the body, so rolling and slipping
// can be told apart at a glance.
visualization_msgs::Marker spokeMarker(const Body& body, const std::string& frame, int id,
                                       const ros::Time& stamp) {
  const double r = radiusOf(body);
  auto spoke = marker(kNsSpoke, id, visualization_msgs::Marker::CUBE, frame, stamp);
  spoke.scale.x = kSpokeLength * r;
  spoke.scale.y = kSpokeWidth * r;
  spoke.scale.z = kSpokeLength * r;
  spoke.color = kSpokeColour;
  if (std::holds_alternative<Rod>(body.model)) spoke.action = visualization_msgs::Marker::DELETE;
  return spoke;
}

std::string labelText(const Body& body) {
  char energy[48];
  std::snprintf(energy, sizeof energy, "E = %.3f J", energyOf(body));
  if (const auto* roller = std::get_if<Roller>(&body.model)) {
    return body.name + ": " + toString(roller->mode()) + ", " + energy;
  }
  return body.name + ": " + energy;
}

}  // namespace

std::vector<BodyPlacement> placeBodies(const std::vector<Body>& bodies, const std::string& frame_prefix) {
  const double lane_spacing = laneSpacing(bodies);
  int rods = 0;
  int rollers = 0;
  std::vector<BodyPlacement> placements;
  for (const auto& body : bodies) {
    if (const auto* rod = std::get_if<Rod>(&body.model)) {
      placements.push_back({frame_prefix + fixedFrameOf(body),
                            uprightPlane({0.0, -kRodPlaneSpacing * rods++, 0.0}, 0.0), 0.0,
                            rod->params().floor_length});
      continue;
    }
    const RollerParams& p = std::get<Roller>(body.model).params();
    const double top = p.incline_length * std::sin(p.incline_angle);
    const double lane_y = kFirstLaneY + lane_spacing * rollers++;
    placements.push_back({frame_prefix + fixedFrameOf(body),
                          uprightPlane({0.0, lane_y, top}, p.incline_angle), p.incline_length});
  }
  return placements;
}

Eigen::Isometry3d frameFromBody(const Body& body) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (const auto* rod = std::get_if<Rod>(&body.model)) {
    pose.translate(Eigen::Vector3d(rod->state().x, rod->state().y, 0.0));
    pose.rotate(Eigen::AngleAxisd(rod->state().theta, Eigen::Vector3d::UnitZ()));
    return pose;
  }
  const auto& roller = std::get<Roller>(body.model);
  pose.translate(Eigen::Vector3d(roller.state().x, roller.params().radius, 0.0));
  pose.rotate(Eigen::AngleAxisd(roller.state().theta, Eigen::Vector3d::UnitZ()));
  return pose;
}

Scene::Scene(std::string world_frame, std::string frame_prefix, const std::vector<Body>& bodies,
             std::size_t trail_points)
    : world_frame_(std::move(world_frame)),
      frame_prefix_(std::move(frame_prefix)),
      placements_(placeBodies(bodies, frame_prefix_)),
      trail_points_(trail_points),
      trails_(bodies.size()) {}

visualization_msgs::MarkerArray Scene::fixedMarkers(const ros::Time& stamp) const {
  visualization_msgs::MarkerArray array;
  double min_y = 0.0;
  double max_y = 0.0;
  for (const auto& placement : placements_) {
    min_y = std::min(min_y, placement.world_from_frame.translation().y());
    max_y = std::max(max_y, placement.world_from_frame.translation().y());
  }
  auto floor = marker(kNsFloor, 0, visualization_msgs::Marker::CUBE, world_frame_, stamp);
  floor.pose.position.x = kFloorLength / 2 - kFloorBehind;
  floor.pose.position.y = (min_y + max_y) / 2;
  floor.pose.position.z = -kFloorThickness / 2;
  floor.scale.x = kFloorLength;
  floor.scale.y = max_y - min_y + 2 * kFloorMargin;
  floor.scale.z = kFloorThickness;
  floor.color = kFloorColour;
  array.markers.push_back(floor);
  for (std::size_t i = 0; i < placements_.size(); ++i) {
    // A rod's bounded floor: a darker strip over x in [0, floor_length] of its floor frame.
    const double floor_length = placements_[i].floor_length;
    if (floor_length > 0.0) {
      auto strip = marker(kNsFloor, static_cast<int>(i) + 1, visualization_msgs::Marker::CUBE,
                          placements_[i].frame, stamp);
      strip.pose.position.x = floor_length / 2;
      strip.pose.position.y = kBoundedFloorRaise - kFloorThickness / 2;
      strip.scale.x = floor_length;
      strip.scale.y = kFloorThickness;
      strip.scale.z = kBoundedFloorWidth;
      strip.color = kBoundedFloorColour;
      array.markers.push_back(strip);
    }
    const double length = placements_[i].slope_length;
    if (length <= 0.0) continue;
    auto slope =
        marker(kNsSlope, static_cast<int>(i), visualization_msgs::Marker::CUBE, placements_[i].frame, stamp);
    slope.pose.position.x = length / 2;
    slope.pose.position.y = -kSlopeThickness / 2;
    slope.scale.x = length;
    slope.scale.y = kSlopeThickness;
    slope.scale.z = kSlopeWidth;
    slope.color = kSlopeColour;
    array.markers.push_back(slope);
  }
  return array;
}

void Scene::addBodyMarkers(std::size_t index, const Body& body, const Eigen::Isometry3d& world_from_body,
                           const ros::Time& stamp, visualization_msgs::MarkerArray& markers) {
  const int id = static_cast<int>(index);
  auto& trail = trails_[index];
  trail.push_back(world_from_body.translation());
  while (trail.size() > trail_points_) trail.pop_front();
  auto trail_marker = marker(kNsTrail, id, visualization_msgs::Marker::LINE_STRIP, world_frame_, stamp);
  trail_marker.scale.x = kTrailWidth;
  trail_marker.color = bodyColour(body);
  trail_marker.color.a = kTrailAlpha;
  for (const auto& point : trail) trail_marker.points.push_back(toPoint(point));

  auto label = marker(kNsLabel, id, visualization_msgs::Marker::TEXT_VIEW_FACING, world_frame_, stamp);
  label.pose.position =
      toPoint(world_from_body.translation() + Eigen::Vector3d(0, 0, radiusOf(body) + kLabelAbove));
  label.scale.z = kLabelHeight;
  label.color = kLabelColour;
  label.text = labelText(body);

  markers.markers.push_back(bodyMarker(body, bodyFrame(body), id, stamp));
  markers.markers.push_back(spokeMarker(body, bodyFrame(body), id, stamp));
  markers.markers.push_back(trail_marker);
  markers.markers.push_back(label);
}

visualization_msgs::MarkerArray Scene::restartMarkers(const ros::Time& stamp) {
  for (auto& trail : trails_) trail.clear();
  visualization_msgs::MarkerArray array;
  auto delete_all = marker("", 0, visualization_msgs::Marker::CUBE, world_frame_, stamp);
  delete_all.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(delete_all);
  for (const auto& m : fixedMarkers(stamp).markers) array.markers.push_back(m);
  return array;
}

}  // namespace rigid_body_sim
