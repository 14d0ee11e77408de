// One body's section of the SimPanel: its keys as widgets built from its dynamic_reconfigure server's
// descriptions (a key added to a .cfg appears without code), showing the server's values; edits go to the
// server (set_parameters), so that a refused value snaps back to what runs, and the refusal is shown. Also
// the body's mode and energy, from its state topic, and a Delete button. Read-only (a replay of a recording):
// Delete and every field disabled, each with a tool tip that says why.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <QGroupBox>
#include <QLabel>

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>
#include <ros/ros.h>

#include "rigid_body_sim/rviz/body_type_rviz.h"

class QFormLayout;

namespace rigid_body_sim {

class CallQueue;

class BodySection : public QGroupBox {
  Q_OBJECT
 public:
  // `server` is the body's reconfigure namespace (e.g. /sim/rod), `state_type` its state message type;
  // `on_time` receives the simulated time of every state; `on_delete` is called by the Delete button.
  // `read_only`: why nothing can be changed (the tool tip of every disabled widget); empty: editable.
  BodySection(const std::string& name, const std::string& server, const std::string& state_type,
              CallQueue& calls, std::function<void(double)> on_time, std::function<void()> on_delete,
              const QString& read_only = {}, QWidget* parent = nullptr);

  const std::string& name() const { return name_; }
  const std::string& stateType() const { return state_type_; }
  // A line the node logged about this body (its refusal of a request): shown under the keys, and kept when
  // the server's answer to that request comes after it.
  void showNodeLine(const QString& text);
  // Whether the node is paused (as the panel knows it): a change accepted then says that the mode and
  // energy follow it at the next Step or Run (a paused node publishes no state until then).
  void setPaused(bool paused);

 private:
  struct Field {
    std::string type;  // bool, int, double, str (dynamic_reconfigure's names)
    std::function<void(const dynamic_reconfigure::Config&)> show;
  };

  void build(const dynamic_reconfigure::ConfigDescription& description);
  void addField(const dynamic_reconfigure::ParamDescription& param, double min, double max);
  QWidget* enumField(const std::string& key, const std::string& type,
                     const std::vector<std::pair<std::string, std::string>>& constants, Field& field);
  QWidget* numberField(const dynamic_reconfigure::ParamDescription& param, double min, double max,
                       Field& field);
  void addUnit(QWidget* row, const QString& object, const QString& unit, const std::string& key,
               Field& field);
  QWidget* intField(const std::string& key, double min, double max, Field& field);
  QWidget* boolField(const std::string& key, Field& field);
  QWidget* textField(const std::string& key, Field& field);
  void showCritical();
  void clearPendingNote();
  void showValues(const dynamic_reconfigure::Config& values);
  void request(dynamic_reconfigure::Config asked, const std::string& key, const QString& asked_text);
  void onState(double t, const QString& motion);
  void holdIfReadOnly(QWidget* widget);  // disabled, its tool tip the reason

  std::string name_, server_, state_type_;
  std::unique_ptr<RvizBodyType> type_;  // null for a state type the panel does not know
  CallQueue& calls_;
  std::function<void(double)> on_time_;
  QString read_only_;
  QFormLayout* form_;
  QLabel* motion_;    // mode and energy
  QLabel* critical_;  // its critical angle, for a type that has one
  QLabel* message_;   // the last refusal (or acceptance) of a request
  std::map<std::string, Field> fields_;
  std::vector<std::string> order_;  // the keys in the .cfg's order
  void showMessage(const QString& text, bool refusal);
  dynamic_reconfigure::Config values_;  // what the server shows
  bool node_line_shown_ = false;        // the node's own line came since the last request was sent
  bool paused_ = false;                 // the node is paused (setPaused)
  bool pending_note_ = false;           // the paused note is shown, until the next state
  std::vector<ros::Subscriber> subscribers_;
};

// How the panel shows a refusal: a colour apart from rviz's own warning and error colours (the screenshot
// test looks for those in the display tree) and from the text's.
inline constexpr const char* kRefusalStyle = "color: rgb(230, 90, 60);";

}  // namespace rigid_body_sim
