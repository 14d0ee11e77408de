#include "rigid_body_sim/rviz/sim_panel.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <sstream>

#include <QComboBox>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QScrollBar>
#include <QTabBar>

#include <std_msgs/Bool.h>
#include <std_srvs/Empty.h>
#include <std_srvs/SetBool.h>
#include <pluginlib/class_list_macros.hpp>

#include "rigid_body_sim/Delete.h"
#include "rigid_body_sim/Spawn.h"
#include "rigid_body_sim/Step.h"
#include "rigid_body_sim/core/description.h"
#include "rigid_body_sim/rviz/body_plots.h"
#include "rigid_body_sim/rviz/body_section.h"
#include "rigid_body_sim/rviz/fixed_text.h"
#include "rigid_body_sim/rviz/focus_wheel.h"

namespace rigid_body_sim {

namespace {

constexpr int kDiscoverMs = 1000;
constexpr int kClockMs = 200;
constexpr double kFactorWindow = 1.0;  // wall seconds over which the real-time factor is measured
constexpr double kStoppedAfter = 0.5;  // wall seconds without a state: simulated time stands still
// The tool tip of what is disabled during a replay.
const QString kRecordingFixed =
    "replay of a recording: a recording cannot be changed (Pause and Run drive the player)";
const QString kPauseTip = "~pause: simulated time stops";
const QString kRunTip = "~unpause: simulated time goes on";

QPushButton* button(const QString& text, const QString& name, const QString& tip, QWidget* parent) {
  auto* b = new QPushButton(text, parent);
  b->setObjectName(name);
  b->setToolTip(tip);
  return b;
}

double wallNow() { return ros::WallTime::now().toSec(); }

// The master's published topics (with their types and publishers) and services; false if it does not answer.
bool readMaster(MasterLists& lists) {
  ros::master::V_TopicInfo topics;
  if (!ros::master::getTopics(topics)) return false;
  for (const auto& topic : topics) lists.topic_types[topic.name] = topic.datatype;
  XmlRpc::XmlRpcValue args, result, state;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, state, true)) return false;
  // [publishers, subscribers, services], each a list of [name, [node ...]]
  if (state.getType() != XmlRpc::XmlRpcValue::TypeArray || state.size() != 3) return false;
  for (int i = 0; i < state[0].size(); ++i) {
    auto& nodes = lists.publishers[static_cast<std::string&>(state[0][i][0])];
    for (int j = 0; j < state[0][i][1].size(); ++j)
      nodes.push_back(static_cast<std::string&>(state[0][i][1][j]));
  }
  for (int i = 0; i < state[2].size(); ++i) lists.services.insert(static_cast<std::string&>(state[2][i][0]));
  return true;
}

}  // namespace

SimPanel::SimPanel(QWidget* parent) : rviz::Panel(parent), calls_(std::make_unique<CallQueue>()) {
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(nodeRow());
  layout->addLayout(controlRow());
  layout->addLayout(spawnRow());
  clock_ = new QLabel("t = ?", this);
  clock_->setObjectName("clock");
  clock_->setToolTip("simulated time, and simulated seconds per wall second over the last second");
  layout->addWidget(clock_);
  status_ = new QLabel(this);
  status_->setObjectName("status");
  status_->setWordWrap(true);
  layout->addWidget(status_);
  layout->addWidget(makeTabs(), 1);

  connect(&discover_timer_, &QTimer::timeout, this, [this] { discover(); });
  connect(&clock_timer_, &QTimer::timeout, this, [this] {
    showClock();
    writeLayout();
  });
  if (const char* file = std::getenv("RBS_PANEL_LAYOUT")) layout_file_ = file;
}

QHBoxLayout* SimPanel::nodeRow() {
  auto* row = new QHBoxLayout();
  row->addWidget(new QLabel("node", this));
  node_edit_ = new QLineEdit(QString::fromStdString(node_), this);
  node_edit_->setObjectName("node");
  node_edit_->setToolTip("the namespace of sim_node (its ~pause, ~step, ~<body> ...)");
  row->addWidget(node_edit_, 1);
  connect(node_edit_, &QLineEdit::editingFinished, this,
          [this] { setNode(node_edit_->text().toStdString()); });
  return row;
}

// Pause, Run, Step with its count, Reset.
QHBoxLayout* SimPanel::controlRow() {
  auto* row = new QHBoxLayout();
  pause_ = button("Pause", "pause", kPauseTip, this);
  run_ = button("Run", "run", kRunTip, this);
  auto* step_button = button("Step", "step", "pauses, then ~step: this many physics steps", this);
  step_count_ = new FocusWheel<QSpinBox>(this);
  step_count_->setObjectName("step_count");
  step_count_->setRange(1, 1000000);
  step_count_->setValue(20);
  step_count_->setToolTip("physics steps per Step");
  auto* reset = button("Reset", "reset", "~reset: every body back to its initial conditions", this);
  for (QWidget* w : std::initializer_list<QWidget*>{pause_, run_, step_button, step_count_, reset})
    row->addWidget(w);
  connect(pause_, &QPushButton::clicked, this,
          [this] { source_ == Source::Replay ? pauseReplay(true) : callEmpty("pause", "paused"); });
  connect(run_, &QPushButton::clicked, this,
          [this] { source_ == Source::Replay ? pauseReplay(false) : callEmpty("unpause", "running"); });
  connect(step_button, &QPushButton::clicked, this, [this] { step(); });
  connect(reset, &QPushButton::clicked, this, [this] { callEmpty("reset", "reset"); });
  for (QWidget* w : std::initializer_list<QWidget*>{step_button, step_count_, reset})
    changes_.emplace_back(w, w->toolTip());
  return row;
}

// A new body's name, its kind and Spawn.
QHBoxLayout* SimPanel::spawnRow() {
  auto* row = new QHBoxLayout();
  spawn_name_ = new QLineEdit(this);
  spawn_name_->setObjectName("spawn_name");
  spawn_name_->setPlaceholderText("new body's name");
  spawn_name_->setToolTip("the name of the body Spawn adds: its TF frame and topics");
  spawn_kind_ = new FocusWheel<QComboBox>(this);
  spawn_kind_->setObjectName("spawn_kind");
  for (const SpawnChoice& choice : spawnChoices())
    spawn_kind_->addItem(QString::fromStdString(choice.label), QString::fromStdString(choice.body));
  spawn_kind_->setToolTip(
      "a body of this type (a roller: of this shape); its other keys take their defaults");
  auto* spawn_button = button("Spawn", "spawn", "~spawn: a new body, starting now", this);
  row->addWidget(spawn_name_, 1);
  row->addWidget(spawn_kind_);
  row->addWidget(spawn_button);
  connect(spawn_button, &QPushButton::clicked, this, [this] { spawn(); });
  for (QWidget* w : std::initializer_list<QWidget*>{spawn_name_, spawn_kind_, spawn_button})
    changes_.emplace_back(w, w->toolTip());
  return row;
}

// Bodies (a section per body, scrolling) and Plots.
QTabWidget* SimPanel::makeTabs() {
  auto* scroll = new QScrollArea(this);
  scroll->setObjectName("sections");
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* sections = new QWidget(scroll);
  sections_layout_ = new QVBoxLayout(sections);
  sections_layout_->setContentsMargins(0, 0, 0, 0);
  sections_layout_->addStretch(1);
  scroll->setWidget(sections);
  tabs_ = new QTabWidget(this);
  tabs_->setObjectName("tabs");
  tabs_->addTab(scroll, "Bodies");
  plots_ = new BodyPlots(*calls_, tabs_);
  tabs_->addTab(plots_, "Plots");
  return tabs_;
}

SimPanel::~SimPanel() = default;

void SimPanel::onInitialize() {
  ns_ = ros::names::resolve(node_);
  plots_->setNode(ns_);
  log_subscriber_ = ros::NodeHandle().subscribe("/rosout", 100, &SimPanel::onLog, this);
  followPaused();
  discover_timer_.start(kDiscoverMs);
  clock_timer_.start(kClockMs);
  discover();
}

void SimPanel::load(const rviz::Config& config) {
  rviz::Panel::load(config);
  QString ns;
  if (config.mapGetString("Node", &ns)) setNode(ns.toStdString());
  int steps = 0;
  if (config.mapGetInt("Step Count", &steps)) step_count_->setValue(steps);
  QString tab, body;
  for (int i = 0; config.mapGetString("Tab", &tab) && i < tabs_->count(); ++i) {
    if (tabs_->tabText(i) == tab) tabs_->setCurrentIndex(i);
  }
  if (config.mapGetString("Plot Body", &body)) plots_->prefer(body.toStdString());
}

void SimPanel::save(rviz::Config config) const {
  rviz::Panel::save(config);
  config.mapSetValue("Node", QString::fromStdString(node_));
  config.mapSetValue("Step Count", step_count_->value());
  config.mapSetValue("Tab", tabs_->tabText(tabs_->currentIndex()));
  config.mapSetValue("Plot Body", QString::fromStdString(plots_->chosen()));
}

void SimPanel::setNode(const std::string& node) {
  if (node == node_) return;
  node_ = node;
  ns_ = ros::names::resolve(node_);
  node_edit_->setText(QString::fromStdString(node_));
  follow({});
  if (log_subscriber_) {  // initialized
    plots_->setNode(ns_);
    followPaused();
  }
  Q_EMIT configChanged();
}

// Bodies: the node's reconfigure servers (<ns>/<body>/parameter_descriptions), each with its state type; or,
// with no node, the state topics a player publishes (discoverBodies).
void SimPanel::discover() {
  if (discovering_) return;
  discovering_ = true;
  const std::string node = ns_;
  calls_->post<std::pair<bool, Discovery>>(
      this,
      [node] {
        MasterLists lists;
        const bool answered = readMaster(lists);
        return std::make_pair(answered, answered ? discoverBodies(lists, node) : Discovery{});
      },
      [this, node](const std::pair<bool, Discovery>& found) {
        discovering_ = false;
        if (node == ns_) onDiscovered(found.second);
        if (!found.first) showStatus("no ROS master", true);
      });
}

// A replay is followed while its player publishes; when it stops publishing, the sections stay as the
// recording ended, until a node or another replay comes.
void SimPanel::onDiscovered(const Discovery& found) {
  Source next = found.source == BodySource::Replay ? Source::Replay : Source::Node;
  if (next == Source::Node && source_ != Source::Node && found.bodies.empty()) next = Source::Ended;
  if (next != source_ || (next == Source::Replay && found.pause_service != pause_service_))
    enter(next, found);
  if (source_ != Source::Ended) follow(found.bodies);
}

void SimPanel::enter(Source source, const Discovery& found) {
  const bool rebuild = (source == Source::Node) != (source_ == Source::Node);  // sections editable or not
  source_ = source;
  if (rebuild) follow({});
  replay_paused_at_ = -1;
  switch (source) {
    case Source::Node:
      player_.clear();
      pause_service_.clear();
      enableChanges(true, {});
      enablePlayer(true, {});
      showStatus("");
      break;
    case Source::Replay:
      player_ = found.player;
      pause_service_ = found.pause_service;
      enableChanges(false, kRecordingFixed);
      enablePlayer(!pause_service_.empty(),
                   QString::fromStdString(player_ + " offers no " + kPlayerPauseService + " service"));
      showStatus(replayStatus(""));
      break;
    case Source::Ended:
      enablePlayer(false, "the recording has ended");
      showStatus(times_.empty()
                     ? QString("end of recording")
                     : QString("end of recording at t = %1 s").arg(fixed(times_.back().second, 3)));
      break;
  }
}

void SimPanel::enableChanges(bool enabled, const QString& why) {
  for (const auto& [widget, tip] : changes_) {
    widget->setEnabled(enabled);
    widget->setToolTip(enabled ? tip : why + "\n" + tip);
  }
}

// Pause and Run: the node's services, a player's pause_playback, or disabled with the reason as tool tip.
void SimPanel::enablePlayer(bool enabled, const QString& why) {
  const QString service = QString::fromStdString(pause_service_);
  pause_->setEnabled(enabled);
  run_->setEnabled(enabled);
  if (source_ == Source::Node) {
    pause_->setToolTip(kPauseTip);
    run_->setToolTip(kRunTip);
  } else if (enabled) {
    pause_->setToolTip(service + ": the replay stops");
    run_->setToolTip(service + ": the replay goes on");
  } else {
    pause_->setToolTip(why);
    run_->setToolTip(why);
  }
}

// A section per body the node serves now, in the order of their names; sections of gone bodies go.
void SimPanel::follow(const std::map<std::string, std::string>& bodies) {
  for (auto it = sections_.begin(); it != sections_.end();) {
    const auto now = bodies.find(it->first);
    if (now == bodies.end() || now->second != it->second->stateType()) {
      delete it->second;
      it = sections_.erase(it);
    } else {
      ++it;
    }
  }
  int index = 0;
  for (const auto& [name, type] : bodies) {
    if (!sections_.count(name)) {
      auto* section = new BodySection(
          name, ns_ + "/" + name, type, *calls_, [this](double t) { onTime(t); },
          [this, name = name] { remove(name); }, source_ == Source::Node ? QString() : kRecordingFixed);
      section->setPaused(node_paused_);
      sections_layout_->insertWidget(index, section);
      sections_[name] = section;
    }
    ++index;
  }
  plots_->setBodies(bodies);
}

void SimPanel::callEmpty(const std::string& service, const QString& done) {
  const std::string name = ns_ + "/" + service;
  calls_->post<bool>(
      this,
      [name] {
        std_srvs::Empty srv;
        return CallQueue::services().call(name, srv);
      },
      [this, name, done](const bool& ok) {
        if (ok) {
          showStatus(done);
        } else {
          showStatus(QString::fromStdString("no answer from " + name), true);
        }
      });
}

// rosbag play's pause_playback: true pauses, false resumes. Its answer "already paused" (or running) is
// the state asked for, too.
void SimPanel::pauseReplay(bool pause) {
  const std::string service = pause_service_;
  calls_->post<std::pair<bool, std::string>>(
      this,
      [service, pause] {
        std_srvs::SetBool srv;
        srv.request.data = pause;
        if (!CallQueue::services().call(service, srv))
          return std::make_pair(false, "no answer from " + service);
        return std::make_pair(true, std::string(pause ? "paused" : "running"));
      },
      [this, service, pause](const std::pair<bool, std::string>& answer) {
        if (source_ != Source::Replay || service != pause_service_) return;  // that replay has gone
        if (answer.first) replay_paused_at_ = pause ? wallNow() : -1;
        showStatus(replayStatus(QString::fromStdString(answer.second)), !answer.first);
      });
}

QString SimPanel::replayStatus(const QString& text) const {
  const QString status = "replay of a recording, played by " + QString::fromStdString(player_);
  return text.isEmpty() ? status : status + ": " + text;
}

// ~step only while paused: Step pauses first.
void SimPanel::step() {
  const std::string pause = ns_ + "/pause", step = ns_ + "/step";
  const auto steps = static_cast<std::uint32_t>(step_count_->value());
  calls_->post<std::string>(
      this,
      [pause, step, steps] {
        std_srvs::Empty paused;
        Step srv;
        srv.request.steps = steps;
        if (!CallQueue::services().call(pause, paused) || !CallQueue::services().call(step, srv))
          return "no answer from " + step;
        std::ostringstream text;
        text << (srv.response.success ? "paused after " + std::to_string(steps) + " steps, t = "
                                      : srv.response.message + ", t = ")
             << srv.response.t << " s";
        return text.str();
      },
      [this](const std::string& text) { showStatus(QString::fromStdString(text)); });
}

// A body of the chosen kind: the node gives every other key its documented default.
void SimPanel::spawn() {
  const std::string name = spawn_name_->text().trimmed().toStdString();
  const std::string kind = spawn_kind_->currentText().toStdString();
  Spawn srv;
  srv.request.name = name;
  srv.request.body = spawn_kind_->currentData().toString().toStdString();
  callChange(ns_ + "/spawn", srv, "spawned '" + name + "' (" + kind + ")");
}

void SimPanel::remove(const std::string& body) {
  Delete srv;
  srv.request.name = body;
  callChange(ns_ + "/delete", srv, "deleted '" + body + "'");
}

// The sections follow at once (the bodies are looked up again) rather than at the next discovery.
template <class Service>
void SimPanel::callChange(const std::string& service, Service srv, const std::string& done) {
  calls_->post<std::pair<bool, std::string>>(
      this,
      [service, srv, done]() mutable {
        if (!CallQueue::services().call(service, srv))
          return std::make_pair(false, "no answer from " + service);
        return std::make_pair(bool(srv.response.success), srv.response.success ? done : srv.response.message);
      },
      [this](const std::pair<bool, std::string>& answer) {
        showStatus(QString::fromStdString(answer.second), !answer.first);
        discover();
      });
}

// The node's latched ~paused. When it goes on, the real-time factor is measured from then: the node takes up
// wall-clock pace from its latest t.
void SimPanel::followPaused() {
  setPaused(false);
  paused_subscriber_ = ros::NodeHandle().subscribe<std_msgs::Bool>(
      ns_ + "/paused", 1, [this](const std_msgs::Bool::ConstPtr& paused) { setPaused(paused->data); });
}

void SimPanel::setPaused(bool paused) {
  if (node_paused_ && !paused && !times_.empty()) times_ = {{wallNow(), times_.back().second}};
  node_paused_ = paused;
  for (auto& [name, section] : sections_) section->setPaused(paused);
}

void SimPanel::onTime(double t) {
  const double now = wallNow();
  if (!times_.empty() && times_.back().first == now) return;
  if (!times_.empty() && t < times_.back().second) times_.clear();  // the node started afresh
  times_.emplace_back(now, t);
  if (replay_paused_at_ >= 0 && now > replay_paused_at_ + kStoppedAfter) replay_paused_at_ = -1;  // resumed
}

// t, and the simulated seconds per wall second over the last kFactorWindow; "paused" while the node says so
// (~paused), "stopped" once no state has come for kStoppedAfter (the node is gone, or a replay stands).
void SimPanel::showClock() {
  const double now = wallNow();
  while (times_.size() > 1 && times_[1].first < now - kFactorWindow) times_.pop_front();
  if (times_.empty()) {
    const QString from = source_ == Source::Node ? QString::fromStdString(ns_) : "the replay";
    clock_->setText(source_ == Source::Ended ? "t = ?  (the recording has ended)"
                                             : "t = ?  (no state from " + from + ")");
    return;
  }
  clock_->setText(QString("t = %1 s   ").arg(fixed(times_.back().second, 3)) + clockState(now));
}

// A replay paused from the panel says so (states already on their way may still come), and so does a paused
// node; "stopped" once no state has come for kStoppedAfter; otherwise the real-time factor.
QString SimPanel::clockState(double now) const {
  if (source_ == Source::Ended) return "end of recording";
  if (source_ == Source::Replay && replay_paused_at_ >= 0) return "paused";
  if (source_ == Source::Node && node_paused_) return "paused";  // ~step's states give no factor
  if (now - times_.back().first > kStoppedAfter) return "stopped";
  const double span = now - times_.front().first;
  const double factor = span > 0 ? (times_.back().second - times_.front().second) / span : 0.0;
  return QString("real-time factor %1").arg(fixed(factor, 2));
}

// The node's WARN and ERROR lines (a refused reconfigure, drop or ~step) go to the status line, and those
// that name a body to its section too.
void SimPanel::onLog(const rosgraph_msgs::Log::ConstPtr& line) {
  if (line->name != ns_ || line->level < rosgraph_msgs::Log::WARN) return;
  for (const auto& [name, section] : sections_) {
    if (line->msg.find("body '" + name + "'") != std::string::npos)
      section->showNodeLine(QString::fromStdString(line->msg));
  }
  showStatus(QString::fromStdString(line->msg), true);  // in sight, wherever the sections are scrolled
}

void SimPanel::showStatus(const QString& text, bool refusal) {
  status_->setText(text);
  status_->setStyleSheet(refusal ? kRefusalStyle : "");
}

// With RBS_PANEL_LAYOUT set: each named widget's visible part on the screen and its text, one per line
// ("name x y width height enabled text"; width and height 0 when scrolled out of sight, enabled 1 or 0; the
// text of a scroll area, the sections, is its vertical scroll position and how far it scrolls sideways),
// rewritten at every clock tick with the count of writes. The GUI tests (test/pictures/rviz_panel.py,
// rviz_playback.py) click and read by it.
void SimPanel::writeLayout() {
  if (layout_file_.empty()) return;
  std::ostringstream out;
  for (QWidget* w : findChildren<QWidget*>()) {
    if (w->objectName().isEmpty() || w->objectName().startsWith("qt_") || !w->isVisible()) continue;
    const QRect shown = w->visibleRegion().boundingRect();  // empty when scrolled out of sight
    const QPoint at = w->mapToGlobal(shown.topLeft());
    QString text;
    if (auto* label = qobject_cast<QLabel*>(w)) text = label->text();
    if (auto* spin = qobject_cast<QAbstractSpinBox*>(w)) text = spin->text();
    if (auto* box = qobject_cast<QComboBox*>(w)) text = box->currentText();
    if (auto* line = qobject_cast<QLineEdit*>(w)) text = line->text();
    if (auto* area = qobject_cast<QAbstractScrollArea*>(w))
      text = QString("%1 %2")
                 .arg(area->verticalScrollBar()->value())
                 .arg(area->horizontalScrollBar()->maximum());
    out << w->objectName().toStdString() << ' ' << at.x() << ' ' << at.y() << ' ' << shown.width() << ' '
        << shown.height() << ' ' << (w->isEnabled() ? 1 : 0) << ' ' << text.simplified().toStdString()
        << '\n';
  }
  writeTabs(out);
  out << plots_->layoutLines();
  // Rewritten at every tick, so that a reader who waits for a later count knows the places above are
  // those of a layout made after its wait began (a click then lands where the widget is).
  out << "layout.written 0 0 0 0 1 " << ++layout_writes_ << '\n';
  const std::string partial = layout_file_ + ".part";
  std::ofstream(partial) << out.str();
  std::rename(partial.c_str(), layout_file_.c_str());
}

// Each tab's place on the screen as "tab.<its text> x y width height 1 <its text>", for a click.
void SimPanel::writeTabs(std::ostream& out) const {
  const QTabBar* bar = tabs_->tabBar();
  for (int i = 0; i < bar->count(); ++i) {
    const QRect tab = bar->tabRect(i);
    const QPoint at = bar->mapToGlobal(tab.topLeft());
    const std::string text = bar->tabText(i).toStdString();
    out << "tab." << text << ' ' << at.x() << ' ' << at.y() << ' ' << tab.width() << ' ' << tab.height()
        << " 1 " << text << '\n';
  }
}

}  // namespace rigid_body_sim

PLUGINLIB_EXPORT_CLASS(rigid_body_sim::SimPanel, rviz::Panel)
