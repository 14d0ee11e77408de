// rviz panel rigid_body_sim/SimPanel: a thin client of sim_node. Pause / Run / Step (a count) / Reset and
// Spawn (a name and a kind) through the node's services; simulated time and the real-time factor achieved,
// from its state topics; a section per body (BodySection, with its Delete), following the bodies the node
// serves. The node's name (sim: relative to rviz's namespace, as sim.launch's ns:= puts both in one) is a
// setting saved in the .rviz file. During a replay of a recording (rosbag play of the node's topics, no node)
// the panel follows the played states read-only, Pause / Run drive the player, and the end of the
// recording is shown. A second tab, Plots (BodyPlots), charts one chosen body's states and marks its events.
#pragma once

#include <cstdint>
#include <deque>
#include <iosfwd>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QTabWidget>
#include <QTimer>
#include <QVBoxLayout>

#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <rviz/panel.h>

#include "rigid_body_sim/rviz/call_queue.h"
#include "rigid_body_sim/rviz/discovery.h"

namespace rigid_body_sim {

class BodyPlots;
class BodySection;

class SimPanel : public rviz::Panel {
  Q_OBJECT
 public:
  explicit SimPanel(QWidget* parent = nullptr);
  ~SimPanel() override;

  void onInitialize() override;
  void load(const rviz::Config& config) override;
  void save(rviz::Config config) const override;

 private:
  // The panel's rows, top to bottom (the constructor's parts).
  QHBoxLayout* nodeRow();
  QHBoxLayout* controlRow();
  QHBoxLayout* spawnRow();
  QTabWidget* makeTabs();

  void setNode(const std::string& node);
  // What the sections show: the node's bodies, a replay of a recording, or the end of that recording.
  enum class Source { Node, Replay, Ended };

  void discover();  // asks the master which bodies the node serves, or a player plays
  void onDiscovered(const Discovery& found);
  void enter(Source source, const Discovery& found);
  void enableChanges(bool enabled, const QString& why);           // Step, Reset, Spawn and their fields
  void enablePlayer(bool enabled, const QString& why);            // Pause, Run
  void follow(const std::map<std::string, std::string>& bodies);  // name -> state message type
  void callEmpty(const std::string& service, const QString& done);
  void pauseReplay(bool pause);  // the player's pause_playback
  QString replayStatus(const QString& text) const;
  void step();
  void spawn();
  void remove(const std::string& body);
  // Calls a service of the node that changes the world; its answer (or refusal) goes to the status line.
  template <class Service>
  void callChange(const std::string& service, Service srv, const std::string& done);
  void followPaused();  // subscribes to the node's ~paused
  void setPaused(bool paused);
  void onTime(double t);
  void showClock();
  QString clockState(double now) const;  // after t: the real-time factor, stopped, paused, ended
  void onLog(const rosgraph_msgs::Log::ConstPtr& line);
  void showStatus(const QString& text, bool refusal = false);
  void writeLayout();  // the widgets' places, for the GUI test (RBS_PANEL_LAYOUT)
  void writeTabs(std::ostream& out) const;

  std::string node_ = "sim";  // as set (saved in the .rviz file)
  std::string ns_;            // resolved: the prefix of the node's services and topics
  std::unique_ptr<CallQueue> calls_;
  QLineEdit* node_edit_;
  QSpinBox* step_count_;
  QLineEdit* spawn_name_;
  QComboBox* spawn_kind_;
  QPushButton* pause_;
  QPushButton* run_;
  std::vector<std::pair<QWidget*, QString>> changes_;  // what changes the world, with its tool tip
  QLabel* clock_;
  QLabel* status_;
  QVBoxLayout* sections_layout_;
  QTabWidget* tabs_;  // Bodies (the sections), Plots
  BodyPlots* plots_;
  std::map<std::string, BodySection*> sections_;
  bool discovering_ = false;
  QTimer discover_timer_, clock_timer_;
  std::deque<std::pair<double, double>> times_;  // (wall s, simulated s) of recent states
  Source source_ = Source::Node;
  std::string player_, pause_service_;  // a replay's player and its pause_playback
  double replay_paused_at_ = -1;        // wall s of the panel's Pause of a replay; < 0: not paused by it
  ros::Subscriber log_subscriber_;
  ros::Subscriber paused_subscriber_;
  bool node_paused_ = false;  // the node's ~paused
  std::string layout_file_;
  std::uint64_t layout_writes_ = 0;
};

}  // namespace rigid_body_sim
