#include "rigid_body_sim/rviz/body_plots.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <QHBoxLayout>
#include <QLabel>
#include <QPen>
#include <QScrollArea>
#include <QVBoxLayout>

#include <dynamic_reconfigure/Config.h>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

namespace {

constexpr int kRedrawMs = 100;
constexpr int kChartHeight = 260;  // px: each chart's, legible; the tab scrolls when they do not fit
constexpr double kTimeTick = 2;    // s between the time axis's ticks, anchored at t = 0
constexpr int kLineWidth = 3;      // px: legible on a projector
constexpr double kMarkerSize = 14;
const QColor kColours[] = {QColor(31, 119, 180), QColor(255, 127, 14), QColor(214, 39, 40)};

double parameter(const dynamic_reconfigure::Config& config, const std::string& name) {
  for (const auto& p : config.doubles) {
    if (p.name == name) return p.value;
  }
  return 0;
}

QFont bigger(QFont font, double factor) {
  font.setPointSizeF(font.pointSizeF() * factor);
  return font;
}

}  // namespace

BodyPlots::BodyPlots(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  auto* row = new QHBoxLayout();
  row->addWidget(new QLabel("body", this));
  choice_ = new QComboBox(this);
  choice_->setObjectName("plot_body");
  choice_->setToolTip("the body whose last 10 s of states the charts show");
  row->addWidget(choice_, 1);
  layout->addLayout(row);
  auto* scroll = new QScrollArea(this);  // the charts keep a legible height; the panel may be shorter
  scroll->setObjectName("plots");
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  charts_box_ = new QWidget(scroll);
  charts_box_->setLayout(new QVBoxLayout());
  charts_box_->layout()->setContentsMargins(0, 0, 0, 0);
  scroll->setWidget(charts_box_);
  layout->addWidget(scroll, 1);
  connect(choice_, &QComboBox::currentTextChanged, this,
          [this](const QString& body) { select(body.toStdString()); });
  connect(&redraw_timer_, &QTimer::timeout, this, [this] { redraw(); });
  redraw_timer_.start(kRedrawMs);
}

void BodyPlots::setNode(const std::string& ns) {
  if (ns == ns_) return;
  ns_ = ns;
  commands_ = ros::NodeHandle().subscribe<Command>(ns_ + "/commands", 100,
                                                   [this](const Command::ConstPtr& c) { onCommand(*c); });
  setBodies({});
}

// The chooser lists the bodies in name order; the chosen one stays while it exists.
void BodyPlots::setBodies(const std::map<std::string, std::string>& bodies) {
  if (bodies == bodies_) return;
  bodies_ = bodies;
  const QString chosen = QString::fromStdString(body_);
  QSignalBlocker block(choice_);
  choice_->clear();
  for (const auto& entry : bodies_) choice_->addItem(QString::fromStdString(entry.first));
  const int at = choice_->findText(chosen);
  choice_->setCurrentIndex(at >= 0 ? at : 0);
  select(choice_->currentText().toStdString());
}

void BodyPlots::prefer(const std::string& body) {
  if (bodies_.count(body)) {
    choice_->setCurrentText(QString::fromStdString(body));
  } else {
    body_ = body;  // setBodies keeps it chosen when it comes
  }
}

void BodyPlots::select(const std::string& body) {
  const auto found = bodies_.find(body);
  const std::string type = found == bodies_.end() ? std::string() : found->second;
  if (body == body_ && !charts_.empty() == !type.empty()) return;
  body_ = body;
  state_.shutdown();
  parameters_.shutdown();
  parameters_known_ = false;
  build(type);
  if (type.empty()) return;
  ros::NodeHandle nh;
  const std::string server = ns_ + "/" + body;
  parameters_ = nh.subscribe<dynamic_reconfigure::Config>(
      server + "/parameter_updates", 1,
      [this](const dynamic_reconfigure::Config::ConstPtr& c) { setParameters(*c); });
  // A queue long enough for every state between two of rviz's spins: no point, no mode change missed.
  if (type == "rigid_body_sim/RodState") {
    state_ =
        nh.subscribe<RodState>(server + "/state", 100, [this](const RodState::ConstPtr& s) { onRod(*s); });
  } else {
    state_ = nh.subscribe<RollerState>(server + "/state", 100,
                                       [this](const RollerState::ConstPtr& s) { onRoller(*s); });
  }
}

// A roller's speeds (with the slip-to-roll marker) and friction, or a rod's ends; then the energy.
void BodyPlots::build(const std::string& type) {
  for (auto& chart : charts_) delete chart.view;
  charts_.clear();
  last_mode_.clear();
  if (type.empty()) return;  // no body
  if (type == "rigid_body_sim/RollerState") {
    charts_.push_back(makeChart("speeds (equal while rolling)", "speed (m/s)"));
    addTrack(charts_.back(), "v", "v", new QLineSeries());
    addTrack(charts_.back(), "minus_omega_r", "\u2212\u03c9R", new QLineSeries());
    auto* marker = new QScatterSeries();
    marker->setMarkerSize(kMarkerSize);
    addTrack(charts_.back(), "slip_to_roll", "slip \u2192 roll", marker);
    charts_.push_back(makeChart("friction on the body, along the slope", "F (N)"));
    addTrack(charts_.back(), "friction", "friction", new QLineSeries());
  } else {
    charts_.push_back(makeChart("height of each end", "y (m)"));
    addTrack(charts_.back(), "y_end_plus", "y + (L/2) sin \u03b8", new QLineSeries());
    addTrack(charts_.back(), "y_end_minus", "y \u2212 (L/2) sin \u03b8", new QLineSeries());
  }
  charts_.push_back(makeChart(type == "rigid_body_sim/RollerState" ? "energy (potential 0 at the slope's top)"
                                                                   : "energy (potential 0 at floor level)",
                              "E (J)"));
  addTrack(charts_.back(), "energy", "total", new QLineSeries());
  addTrack(charts_.back(), "kinetic", "kinetic", new QLineSeries());
  addTrack(charts_.back(), "potential", "potential", new QLineSeries());
  for (auto& chart : charts_) charts_box_->layout()->addWidget(chart.view);
  dirty_ = true;
}

BodyPlots::Chart BodyPlots::makeChart(const QString& title, const QString& y_title) {
  auto* chart = new QChart();
  chart->setTitle(title);
  chart->setTitleFont(bigger(chart->titleFont(), 1.2));
  chart->setMargins(QMargins(2, 2, 2, 2));
  chart->legend()->setAlignment(Qt::AlignTop);
  chart->legend()->setFont(bigger(chart->legend()->font(), 1.1));
  Chart made{new QChartView(chart, charts_box_), new QValueAxis(), new QValueAxis(), {}};
  made.view->setRenderHint(QPainter::Antialiasing);
  made.view->setMinimumHeight(kChartHeight);
  for (QValueAxis* axis : {made.x, made.y}) {
    axis->setTitleFont(bigger(axis->titleFont(), 1.1));
    axis->setLabelsFont(bigger(axis->labelsFont(), 1.1));
    axis->setLabelFormat("%.3g");
  }
  made.x->setTickType(QValueAxis::TicksDynamic);  // ticks at whole multiples, moving with the window
  made.x->setTickAnchor(0);
  made.x->setTickInterval(kTimeTick);
  made.x->setLabelFormat("%.0f");
  made.x->setTitleText("t (s)");
  made.y->setTitleText(y_title);
  chart->addAxis(made.x, Qt::AlignBottom);
  chart->addAxis(made.y, Qt::AlignLeft);
  return made;
}

void BodyPlots::addTrack(Chart& chart, const std::string& key, const QString& name, QXYSeries* series) {
  series->setName(name);
  QPen pen(kColours[chart.tracks.size() % 3]);
  pen.setWidth(kLineWidth);
  if (chart.tracks.size() == 1) pen.setStyle(Qt::DashLine);  // the second line shows where they coincide
  series->setPen(pen);
  series->setColor(pen.color());
  chart.view->chart()->addSeries(series);
  series->attachAxis(chart.x);
  series->attachAxis(chart.y);
  chart.tracks.push_back({key, series, {}});
}

void BodyPlots::setParameters(const dynamic_reconfigure::Config& config) {
  rod_.mass = roller_.mass = parameter(config, "mass");
  rod_.length = parameter(config, "length");
  roller_.radius = parameter(config, "radius");
  roller_.inertia_factor = parameter(config, "inertia_factor");  // the shape's c, or a custom one
  parameters_known_ = true;
}

// The total as the state has it; the kinetic the core's; the potential what remains of the total.
void BodyPlots::appendEnergies(Chart& chart, double t, double total, double kinetic) {
  append(chart, 0, t, total);
  if (!parameters_known_) return;
  append(chart, 1, t, kinetic);
  append(chart, 2, t, total - kinetic);
}

void BodyPlots::onRod(const RodState& state) {
  if (!isVisible() || charts_.size() != 2) return;
  trim(state.t);
  if (parameters_known_) {
    append(charts_[0], 0, state.t, state.y + 0.5 * rod_.length * std::sin(state.theta));
    append(charts_[0], 1, state.t, state.y - 0.5 * rod_.length * std::sin(state.theta));
  }
  const Rod rod(rod_, RodMotion{state.x, state.y, state.theta, state.vx, state.vy, state.omega});
  appendEnergies(charts_[1], state.t, state.energy, rod.kineticEnergy());
}

// rolling means v = -omega R (RollerState.msg): v and -omega R coincide then.
void BodyPlots::onRoller(const RollerState& state) {
  if (!isVisible() || charts_.size() != 3) return;
  trim(state.t);
  append(charts_[0], 0, state.t, state.v);
  if (parameters_known_) append(charts_[0], 1, state.t, -state.omega * roller_.radius);
  if (last_mode_ == RollerState::MODE_SLIPPING && state.mode == RollerState::MODE_ROLLING)
    append(charts_[0], 2, state.t, state.v);
  last_mode_ = state.mode;
  append(charts_[1], 0, state.t, state.friction);
  const Roller roller(roller_, RollerInitial{state.x, state.v, state.theta, state.omega});
  appendEnergies(charts_[2], state.t, state.energy, roller.kineticEnergy());
}

// A reset (anyone's) puts the body back at its start: what came up to it goes (a paused node's last state
// has the reset's t). t never goes back, so the states after it stay; an old reset (the latched topic's
// last command) takes nothing.
void BodyPlots::onCommand(const Command& command) {
  if (command.kind != "reset") return;
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) {
      while (!track.points.empty() && track.points.front().x() <= command.t) track.points.pop_front();
    }
  }
  last_mode_.clear();
  dirty_ = true;
}

void BodyPlots::append(Chart& chart, std::size_t track, double t, double value) {
  chart.tracks[track].points.emplace_back(t, value);
  dirty_ = true;
}

// Only the last kPlotWindow seconds are kept.
void BodyPlots::trim(double t) {
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) {
      while (!track.points.empty() && track.points.front().x() < t - kPlotWindow) track.points.pop_front();
    }
  }
}

void BodyPlots::clear() {
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) track.points.clear();
  }
  last_mode_.clear();
  dirty_ = true;
}

// Shown again after being hidden: nothing was recorded meanwhile, so the charts start afresh.
void BodyPlots::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  clear();
}

// At most every kRedrawMs, and only in sight: the series take the points, the axes the window and range.
void BodyPlots::redraw() {
  if (!dirty_ || !isVisible()) return;
  dirty_ = false;
  double t_last = -std::numeric_limits<double>::infinity();
  for (const auto& chart : charts_) {
    for (const auto& track : chart.tracks) {
      if (!track.points.empty()) t_last = std::max(t_last, track.points.back().x());
    }
  }
  for (auto& chart : charts_) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (auto& track : chart.tracks) {
      track.series->replace(QVector<QPointF>(track.points.begin(), track.points.end()));
      for (const QPointF& p : track.points) {
        low = std::min(low, p.y());
        high = std::max(high, p.y());
      }
    }
    if (!std::isfinite(t_last) || !std::isfinite(low)) continue;
    chart.x->setRange(std::max(0.0, t_last - kPlotWindow), std::max(kPlotWindow, t_last));  // from 0 at first
    const double margin = std::max(0.05 * (high - low), 1e-3 * std::max(1.0, std::abs(high)));
    chart.y->setRange(low - margin, high + margin);
    chart.y->applyNiceNumbers();  // round ticks
  }
}

std::string BodyPlots::layoutLines() const {
  std::ostringstream out;
  for (const auto& chart : charts_) {
    for (const auto& track : chart.tracks) {
      out << "plot." << track.key << " 0 0 0 0 1 " << track.points.size();
      if (!track.points.empty())
        out << ' ' << formatNumber(track.points.back().x()) << ' ' << formatNumber(track.points.back().y());
      out << '\n';
    }
  }
  return out.str();
}

}  // namespace rigid_body_sim
