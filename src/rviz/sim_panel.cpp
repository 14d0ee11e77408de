#include "rigid_body_sim/rviz/sim_panel.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <QComboBox>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QScrollArea>

#include <std_srvs/Empty.h>
#include <pluginlib/class_list_macros.hpp>

#include "rigid_body_sim/Delete.h"
#include "rigid_body_sim/Spawn.h"
#include "rigid_body_sim/Step.h"
#include "rigid_body_sim/core/roller.h"
#include "rigid_body_sim/rviz/body_section.h"

namespace rigid_body_sim {

namespace {

constexpr int kDiscoverMs = 1000;
constexpr int kClockMs = 200;
constexpr double kFactorWindow = 1.0;  // wall seconds over which the real-time factor is measured
constexpr double kStoppedAfter = 0.5;  // wall seconds without a state: simulated time stands still
const std::string kDescriptions = "/parameter_descriptions";

QPushButton* button(const QString& text, const QString& name, const QString& tip, QWidget* parent) {
  auto* b = new QPushButton(text, parent);
  b->setObjectName(name);
  b->setToolTip(tip);
  return b;
}

double wallNow() { return ros::WallTime::now().toSec(); }

}  // namespace

SimPanel::SimPanel(QWidget* parent) : rviz::Panel(parent), calls_(std::make_unique<CallQueue>()) {
  auto* layout = new QVBoxLayout(this);

  auto* node_row = new QHBoxLayout();
  node_row->addWidget(new QLabel("node", this));
  node_edit_ = new QLineEdit(QString::fromStdString(node_), this);
  node_edit_->setObjectName("node");
  node_edit_->setToolTip("the namespace of sim_node (its ~pause, ~step, ~<body> ...)");
  node_row->addWidget(node_edit_, 1);
  layout->addLayout(node_row);
  connect(node_edit_, &QLineEdit::editingFinished, this,
          [this] { setNode(node_edit_->text().toStdString()); });

  auto* controls = new QHBoxLayout();
  auto* pause = button("Pause", "pause", "~pause: simulated time stops", this);
  auto* run = button("Run", "run", "~unpause: simulated time goes on", this);
  auto* step_button = button("Step", "step", "pauses, then ~step: this many physics steps", this);
  step_count_ = new QSpinBox(this);
  step_count_->setObjectName("step_count");
  step_count_->setRange(1, 1000000);
  step_count_->setValue(20);
  step_count_->setToolTip("physics steps per Step");
  auto* reset = button("Reset", "reset", "~reset: every body back to its initial conditions", this);
  for (QWidget* w : std::initializer_list<QWidget*>{pause, run, step_button, step_count_, reset})
    controls->addWidget(w);
  layout->addLayout(controls);
  connect(pause, &QPushButton::clicked, this, [this] { callEmpty("pause", "paused"); });
  connect(run, &QPushButton::clicked, this, [this] { callEmpty("unpause", "running"); });
  connect(step_button, &QPushButton::clicked, this, [this] { step(); });
  connect(reset, &QPushButton::clicked, this, [this] { callEmpty("reset", "reset"); });

  auto* spawn_row = new QHBoxLayout();
  spawn_name_ = new QLineEdit(this);
  spawn_name_->setObjectName("spawn_name");
  spawn_name_->setPlaceholderText("new body's name");
  spawn_name_->setToolTip("the name of the body Spawn adds: its TF frame and topics");
  spawn_kind_ = new QComboBox(this);
  spawn_kind_->setObjectName("spawn_kind");
  spawn_kind_->addItem("rod");
  for (const Shape shape : namedShapes()) spawn_kind_->addItem(QString::fromStdString(toString(shape)));
  spawn_kind_->setToolTip("a rod, or a roller of this shape; its other keys take their defaults");
  auto* spawn_button = button("Spawn", "spawn", "~spawn: a new body, starting now", this);
  spawn_row->addWidget(spawn_name_, 1);
  spawn_row->addWidget(spawn_kind_);
  spawn_row->addWidget(spawn_button);
  layout->addLayout(spawn_row);
  connect(spawn_button, &QPushButton::clicked, this, [this] { spawn(); });

  clock_ = new QLabel("t = ?", this);
  clock_->setObjectName("clock");
  clock_->setToolTip("simulated time, and simulated seconds per wall second over the last second");
  layout->addWidget(clock_);
  status_ = new QLabel(this);
  status_->setObjectName("status");
  status_->setWordWrap(true);
  layout->addWidget(status_);

  auto* scroll = new QScrollArea(this);
  scroll->setObjectName("sections");
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  auto* sections = new QWidget(scroll);
  sections_layout_ = new QVBoxLayout(sections);
  sections_layout_->setContentsMargins(0, 0, 0, 0);
  sections_layout_->addStretch(1);
  scroll->setWidget(sections);
  layout->addWidget(scroll, 1);

  connect(&discover_timer_, &QTimer::timeout, this, [this] { discover(); });
  connect(&clock_timer_, &QTimer::timeout, this, [this] {
    showClock();
    writeLayout();
  });
  if (const char* file = std::getenv("RBS_PANEL_LAYOUT")) layout_file_ = file;
}

SimPanel::~SimPanel() = default;

void SimPanel::onInitialize() {
  ns_ = ros::names::resolve(node_);
  log_subscriber_ = ros::NodeHandle().subscribe("/rosout", 100, &SimPanel::onLog, this);
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
}

void SimPanel::save(rviz::Config config) const {
  rviz::Panel::save(config);
  config.mapSetValue("Node", QString::fromStdString(node_));
  config.mapSetValue("Step Count", step_count_->value());
}

void SimPanel::setNode(const std::string& node) {
  if (node == node_) return;
  node_ = node;
  ns_ = ros::names::resolve(node_);
  node_edit_->setText(QString::fromStdString(node_));
  follow({});
  Q_EMIT configChanged();
}

// Bodies: the node's reconfigure servers (<ns>/<body>/parameter_descriptions), each with its state type.
void SimPanel::discover() {
  if (discovering_) return;
  discovering_ = true;
  const std::string prefix = ns_ + "/";
  using Bodies = std::map<std::string, std::string>;
  calls_->post<std::pair<bool, Bodies>>(
      this,
      [prefix] {
        ros::master::V_TopicInfo topics;
        Bodies bodies;
        if (!ros::master::getTopics(topics)) return std::make_pair(false, bodies);
        std::map<std::string, std::string> types;
        for (const auto& topic : topics) types[topic.name] = topic.datatype;
        for (const auto& [name, type] : types) {
          if (name.rfind(prefix, 0) != 0 || name.size() <= prefix.size() + kDescriptions.size() ||
              name.compare(name.size() - kDescriptions.size(), kDescriptions.size(), kDescriptions) != 0)
            continue;
          const std::string body =
              name.substr(prefix.size(), name.size() - prefix.size() - kDescriptions.size());
          if (body.find('/') != std::string::npos) continue;
          const auto state = types.find(prefix + body + "/state");
          bodies[body] = state == types.end() ? "" : state->second;
        }
        return std::make_pair(true, bodies);
      },
      [this, prefix](const std::pair<bool, Bodies>& found) {
        discovering_ = false;
        if (prefix == ns_ + "/") follow(found.second);
        if (!found.first) showStatus("no ROS master", true);
      });
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
          [this, name = name] { remove(name); });
      sections_layout_->insertWidget(index, section);
      sections_[name] = section;
    }
    ++index;
  }
}

void SimPanel::callEmpty(const std::string& service, const QString& done) {
  const std::string name = ns_ + "/" + service;
  calls_->post<bool>(
      this,
      [name] {
        std_srvs::Empty srv;
        return ros::service::call(name, srv);
      },
      [this, name, done](const bool& ok) {
        if (ok) {
          showStatus(done);
        } else {
          showStatus(QString::fromStdString("no answer from " + name), true);
        }
      });
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
        if (!ros::service::call(pause, paused) || !ros::service::call(step, srv))
          return "no answer from " + step;
        std::ostringstream text;
        text << (srv.response.success ? "paused after " + std::to_string(steps) + " steps, t = "
                                      : srv.response.message + ", t = ")
             << srv.response.t << " s";
        return text.str();
      },
      [this](const std::string& text) { showStatus(QString::fromStdString(text)); });
}

// A rod, or a roller of the chosen shape: the node gives every other key its documented default.
void SimPanel::spawn() {
  const std::string name = spawn_name_->text().trimmed().toStdString();
  const std::string kind = spawn_kind_->currentText().toStdString();
  Spawn srv;
  srv.request.name = name;
  srv.request.body = kind == "rod" ? "{type: rod}" : "{type: roller, shape: " + kind + "}";
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
        if (!ros::service::call(service, srv)) return std::make_pair(false, "no answer from " + service);
        return std::make_pair(bool(srv.response.success), srv.response.success ? done : srv.response.message);
      },
      [this](const std::pair<bool, std::string>& answer) {
        showStatus(QString::fromStdString(answer.second), !answer.first);
        discover();
      });
}

void SimPanel::onTime(double t) {
  const double now = wallNow();
  if (!times_.empty() && times_.back().first == now) return;
  if (!times_.empty() && t < times_.back().second) times_.clear();  // the node started afresh
  times_.emplace_back(now, t);
}

// t, and the simulated seconds per wall second over the last kFactorWindow; "stopped" once no state has
// come for kStoppedAfter (paused, or the node is gone).
void SimPanel::showClock() {
  const double now = wallNow();
  while (times_.size() > 1 && times_[1].first < now - kFactorWindow) times_.pop_front();
  if (times_.empty()) {
    clock_->setText("t = ?  (no state from " + QString::fromStdString(ns_) + ")");
    return;
  }
  const QString t = QString("t = %1 s   ").arg(times_.back().second, 0, 'f', 3);
  if (now - times_.back().first > kStoppedAfter) {
    clock_->setText(t + "stopped");
    return;
  }
  const double span = now - times_.front().first;
  const double factor = span > 0 ? (times_.back().second - times_.front().second) / span : 0.0;
  clock_->setText(t + QString("real-time factor %1").arg(factor, 0, 'f', 2));
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
// ("name x y width height text"; width and height 0 when scrolled out of sight), rewritten when something
// changed. The GUI test (test/pictures/rviz_panel.py) clicks and reads by it.
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
    out << w->objectName().toStdString() << ' ' << at.x() << ' ' << at.y() << ' ' << shown.width() << ' '
        << shown.height() << ' ' << text.simplified().toStdString() << '\n';
  }
  if (out.str() == layout_written_) return;
  layout_written_ = out.str();
  const std::string partial = layout_file_ + ".part";
  std::ofstream(partial) << layout_written_;
  std::rename(partial.c_str(), layout_file_.c_str());
}

}  // namespace rigid_body_sim

PLUGINLIB_EXPORT_CLASS(rigid_body_sim::SimPanel, rviz::Panel)
