#include "rigid_body_sim/ros/ros_conversions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rigid_body_sim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRodPlaneSpacing = 1.5;  // m between the planes of successive rods
constexpr double kFirstLaneY = 1.0;       // m, world y of the first roller's lane
constexpr double kMinLaneSpacing = 0.5;   // m between roller lanes
constexpr double kFloorLength = 40.0;     // m along world x

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

std_msgs::ColorRGBA bodyColor(const Body& body) {
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
  return 0.05;
}

std::string frameOf(const Body& body) {
  return body.name + (std::holds_alternative<Rod>(body.model) ? "_floor" : "_slope");
}

geometry_msgs::Pose toPose(const Eigen::Isometry3d& transform) {
  geometry_msgs::Pose pose;
  const Eigen::Quaterniond q(transform.rotation());
  pose.position.x = transform.translation().x();
  pose.position.y = transform.translation().y();
  pose.position.z = transform.translation().z();
  pose.orientation.x = q.x();
  pose.orientation.y = q.y();
  pose.orientation.z = q.z();
  pose.orientation.w = q.w();
  return pose;
}

geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& transform, const std::string& parent,
                                            const std::string& child, const ros::Time& stamp) {
  geometry_msgs::TransformStamped msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = parent;
  msg.child_frame_id = child;
  const geometry_msgs::Pose pose = toPose(transform);
  msg.transform.translation.x = pose.position.x;
  msg.transform.translation.y = pose.position.y;
  msg.transform.translation.z = pose.position.z;
  msg.transform.rotation = pose.orientation;
  return msg;
}

geometry_msgs::Point toPoint(const Eigen::Vector3d& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
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
  return std::max(kMinLaneSpacing, 3.0 * largest_radius);
}

visualization_msgs::Marker rollerShapeMarker(const Body& body, int id, const ros::Time& stamp) {
  const RollerParams& p = std::get<Roller>(body.model).params();
  const double d = 2.0 * p.radius;
  if (p.shape == Shape::Ring) {
    auto ring = marker(kNsBody, id, visualization_msgs::Marker::LINE_STRIP, body.name, stamp);
    ring.scale.x = 0.15 * p.radius;
    for (int i = 0; i <= 48; ++i) {
      const double a = 2.0 * kPi * i / 48;
      ring.points.push_back(toPoint({p.radius * std::cos(a), p.radius * std::sin(a), 0.0}));
    }
    return ring;
  }
  const bool cylinder = p.shape == Shape::Cylinder;
  auto shape = marker(kNsBody, id,
                      cylinder ? visualization_msgs::Marker::CYLINDER : visualization_msgs::Marker::SPHERE,
                      body.name, stamp);
  shape.scale.x = shape.scale.y = d;
  shape.scale.z = cylinder ? 0.8 * d : d;
  return shape;
}

visualization_msgs::Marker bodyMarker(const Body& body, int id, const ros::Time& stamp) {
  visualization_msgs::Marker m;
  if (const auto* rod = std::get_if<Rod>(&body.model)) {
    m = marker(kNsBody, id, visualization_msgs::Marker::CYLINDER, body.name, stamp);
    // A marker cylinder lies along its z; the rod lies along its frame's x.
    m.pose.orientation.y = std::sin(kPi / 4);
    m.pose.orientation.w = std::cos(kPi / 4);
    m.scale.x = m.scale.y = 0.05;
    m.scale.z = rod->params().length;
  } else {
    m = rollerShapeMarker(body, id, stamp);
  }
  m.color = bodyColor(body);
  return m;
}

// A dark bar through the centre along the body's x: it turns with the body, so rolling and slipping
// can be told apart at a glance.
visualization_msgs::Marker spokeMarker(const Body& body, int id, const ros::Time& stamp) {
  const double r = radiusOf(body);
  auto spoke = marker(kNsSpoke, id, visualization_msgs::Marker::CUBE, body.name, stamp);
  spoke.scale.x = 2.02 * r;
  spoke.scale.y = 0.25 * r;
  spoke.scale.z = 2.02 * r;
  spoke.color = rgba(0.1f, 0.1f, 0.1f);
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

ros::Time simStamp(double t) { return ros::Time(0, 1) + ros::Duration(t); }

std::vector<BodyPlacement> placeBodies(const std::vector<Body>& bodies) {
  const double lane_spacing = laneSpacing(bodies);
  int rods = 0;
  int rollers = 0;
  std::vector<BodyPlacement> placements;
  for (const auto& body : bodies) {
    if (std::holds_alternative<Rod>(body.model)) {
      placements.push_back({frameOf(body), uprightPlane({0.0, -kRodPlaneSpacing * rods++, 0.0}, 0.0), 0.0});
      continue;
    }
    const RollerParams& p = std::get<Roller>(body.model).params();
    const double top = p.incline_length * std::sin(p.incline_angle);
    const double lane_y = kFirstLaneY + lane_spacing * rollers++;
    placements.push_back(
        {frameOf(body), uprightPlane({0.0, lane_y, top}, p.incline_angle), p.incline_length});
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

RodState toRodStateMsg(double t, const Rod& rod) {
  RodState msg;
  msg.t = t;
  msg.x = rod.state().x;
  msg.y = rod.state().y;
  msg.theta = rod.state().theta;
  msg.vx = rod.state().vx;
  msg.vy = rod.state().vy;
  msg.omega = rod.state().omega;
  msg.energy = rod.energy();
  return msg;
}

RollerState toRollerStateMsg(double t, const Roller& roller) {
  RollerState msg;
  msg.t = t;
  msg.x = roller.state().x;
  msg.v = roller.state().v;
  msg.theta = roller.state().theta;
  msg.omega = roller.state().omega;
  msg.mode = toString(roller.mode());
  msg.friction = roller.frictionForce();
  msg.normal = roller.normalForce();
  msg.energy = roller.energy();
  return msg;
}

SnapshotBuilder::SnapshotBuilder(std::string world_frame, const std::vector<Body>& bodies,
                                 std::size_t trail_points)
    : world_frame_(std::move(world_frame)),
      placements_(placeBodies(bodies)),
      trail_points_(trail_points),
      trails_(bodies.size()) {}

std::vector<geometry_msgs::TransformStamped> SnapshotBuilder::staticTransforms(const ros::Time& stamp) const {
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (const auto& placement : placements_) {
    transforms.push_back(toTransform(placement.world_from_frame, world_frame_, placement.frame, stamp));
  }
  return transforms;
}

visualization_msgs::MarkerArray SnapshotBuilder::staticMarkers(const ros::Time& stamp) const {
  visualization_msgs::MarkerArray array;
  double min_y = 0.0;
  double max_y = 0.0;
  for (const auto& placement : placements_) {
    min_y = std::min(min_y, placement.world_from_frame.translation().y());
    max_y = std::max(max_y, placement.world_from_frame.translation().y());
  }
  auto floor = marker(kNsFloor, 0, visualization_msgs::Marker::CUBE, world_frame_, stamp);
  floor.pose.position.x = kFloorLength / 2 - 2.0;
  floor.pose.position.y = (min_y + max_y) / 2;
  floor.pose.position.z = -0.01;
  floor.scale.x = kFloorLength;
  floor.scale.y = max_y - min_y + 2.0;
  floor.scale.z = 0.02;
  floor.color = rgba(0.75f, 0.75f, 0.75f);
  array.markers.push_back(floor);
  const double lane_width = 0.8 * kMinLaneSpacing;
  for (std::size_t i = 0; i < placements_.size(); ++i) {
    const double length = placements_[i].slope_length;
    if (length <= 0.0) continue;
    auto slope =
        marker(kNsSlope, static_cast<int>(i), visualization_msgs::Marker::CUBE, placements_[i].frame, stamp);
    slope.pose.position.x = length / 2;
    slope.pose.position.y = -0.025;
    slope.scale.x = length;
    slope.scale.y = 0.05;
    slope.scale.z = lane_width;
    slope.color = rgba(0.55f, 0.4f, 0.25f);
    array.markers.push_back(slope);
  }
  return array;
}

Snapshot SnapshotBuilder::build(double t, const ros::Time& stamp, const std::vector<Body>& bodies) {
  Snapshot snapshot;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const Body& body = bodies[i];
    const int id = static_cast<int>(i);
    const Eigen::Isometry3d world_from_body = placements_[i].world_from_frame * frameFromBody(body);
    snapshot.tf.transforms.push_back(toTransform(world_from_body, world_frame_, body.name, stamp));

    auto& trail = trails_[i];
    trail.push_back(world_from_body.translation());
    while (trail.size() > trail_points_) trail.pop_front();
    auto trail_marker = marker(kNsTrail, id, visualization_msgs::Marker::LINE_STRIP, world_frame_, stamp);
    trail_marker.scale.x = 0.01;
    trail_marker.color = bodyColor(body);
    trail_marker.color.a = 0.6f;
    for (const auto& point : trail) trail_marker.points.push_back(toPoint(point));

    auto label = marker(kNsLabel, id, visualization_msgs::Marker::TEXT_VIEW_FACING, world_frame_, stamp);
    label.pose.position =
        toPoint(world_from_body.translation() + Eigen::Vector3d(0, 0, radiusOf(body) + 0.35));
    label.scale.z = 0.15;
    label.color = rgba(1, 1, 1);
    label.text = labelText(body);

    snapshot.markers.markers.push_back(bodyMarker(body, id, stamp));
    snapshot.markers.markers.push_back(spokeMarker(body, id, stamp));
    snapshot.markers.markers.push_back(trail_marker);
    snapshot.markers.markers.push_back(label);

    if (const auto* rod = std::get_if<Rod>(&body.model)) {
      snapshot.states.emplace_back(toRodStateMsg(t, *rod));
    } else {
      snapshot.states.emplace_back(toRollerStateMsg(t, std::get<Roller>(body.model)));
    }
    std::visit(
        [&](auto& msg) {
          msg.header.stamp = stamp;
          msg.header.frame_id = placements_[i].frame;
        },
        snapshot.states.back());
  }
  // The floor and slopes too, every time: an rviz started after the node still sees them (a few markers).
  for (const auto& m : staticMarkers(stamp).markers) snapshot.markers.markers.push_back(m);
  return snapshot;
}

visualization_msgs::MarkerArray SnapshotBuilder::restartMarkers(const ros::Time& stamp) {
  for (auto& trail : trails_) trail.clear();
  visualization_msgs::MarkerArray array;
  auto delete_all = marker("", 0, visualization_msgs::Marker::CUBE, world_frame_, stamp);
  delete_all.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(delete_all);
  for (const auto& m : staticMarkers(stamp).markers) array.markers.push_back(m);
  return array;
}

}  // namespace rigid_body_sim
