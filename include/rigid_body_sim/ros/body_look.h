// What each body type shows on the ROS side, as its own files (ros/types/<type>_ros.h and .cpp) define it
// in its RosBodyType: its state message, how it looks in rviz (BodyLook, BodyShape) and what its interactive
// markers hold and set (BodyHandles). The scene and the interactive markers lay out and draw every body from
// these alone.
#pragma once

#include <optional>
#include <vector>

#include <std_msgs/ColorRGBA.h>
#include <Eigen/Geometry>

namespace rigid_body_sim {

// Each body type's messages: a specialization in ros/types/<type>_ros.h naming its state message
// (StateMsg) and its reconfigure server's config (Reconfigure, generated from its .cfg).
template <class Type>
struct RosMessages;

std_msgs::ColorRGBA rgba(float r, float g, float b, float a = 1.0f);

struct Incline {
  double angle;   // rad
  double length;  // m
};

// Where a body is and how it sits, cheap enough for every sample.
struct BodyLook {
  std_msgs::ColorRGBA colour;
  std::optional<Incline> incline;  // a body on a slope, in a lane of its own; none: on a floor plane
  double floor_length = 0.0;       // off a slope: its bounded floor's length (0: unbounded)
  double radius = 0.0;             // half its width across its lane
  double reach = 0.0;              // how far above its centre it reaches, whatever its angle (m)
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // its centre and rotation in its fixed frame
  bool spoke = false;  // a dark bar through its centre that turns with it: rolling told from slipping
  std::optional<double> critical_tangent;  // tan of the steepest slope its static friction holds
};

// Its shape: one marker in its own frame (visualization_msgs::Marker's type, scale, orientation, points).
struct BodyShape {
  int type = 0;
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  std::vector<Eigen::Vector3d> points;  // a LINE_STRIP's
};

// Its interactive markers, in its fixed frame, at its initial conditions: a ghost of it to drag (along the
// slope's x only, or in its plane and turned about z) and a knob at the tip of its initial velocity; and
// the keys a drop sets.
struct BodyHandles {
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  double angle = 0.0;  // rad, about z
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  double size = 1.0;  // the handle's scale (m)
  BodyShape ghost;
  const char* x_key;                // the drop's x
  const char* y_key = nullptr;      // its y, where the body moves in its plane
  const char* angle_key = nullptr;  // its angle, where the body turns
  const char* vx_key;               // the knob's drop: velocity along x
  const char* vy_key = nullptr;     // and y
};

// Each body type's ROS side. Its messages are RosMessages<Type>'s; its functions are defined in its own
// src/ros/types/<type>_ros.cpp (a type without them does not link).
template <class Type>
struct RosBodyType {
  using StateMsg = typename RosMessages<Type>::StateMsg;
  using Reconfigure = typename RosMessages<Type>::Reconfigure;
  static BodyLook look(const typename Type::Model& model);
  static BodyShape shape(const typename Type::Model& model);
  static BodyHandles handles(const typename Type::Config& config);
};

}  // namespace rigid_body_sim

// Declares a body type's ROS side in its ros/types/<type>_ros.h (inside namespace rigid_body_sim): its
// messages, and the three functions its src/ros/types/<type>_ros.cpp defines.
#define RBS_ROS_BODY_TYPE(TYPE, STATE_MSG, RECONFIGURE)         \
  template <>                                                   \
  struct RosMessages<TYPE> {                                    \
    using StateMsg = STATE_MSG;                                 \
    using Reconfigure = RECONFIGURE;                            \
  };                                                            \
  template <>                                                   \
  BodyLook RosBodyType<TYPE>::look(const TYPE::Model& model);   \
  template <>                                                   \
  BodyShape RosBodyType<TYPE>::shape(const TYPE::Model& model); \
  template <>                                                   \
  BodyHandles RosBodyType<TYPE>::handles(const TYPE::Config& config)
