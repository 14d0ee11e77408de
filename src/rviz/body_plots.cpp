#include "rigid_body_sim/rviz/body_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include <QDir>
#include <QFileDialog>
#include <QGridLayout>
#include <QGuiApplication>
#include <QHBoxLayout>
#include <QLegendMarker>
#include <QPen>
#include <QPushButton>
#include <QScreen>
#include <QScrollArea>
#include <QVBoxLayout>

#include <dynamic_reconfigure/Config.h>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/rviz/axis_ticks.h"
#include "rigid_body_sim/rviz/fixed_text.h"

namespace rigid_body_sim {

#if QT_VERSION < QT_VERSION_CHECK(6, 0, 0)
using QtCharts::QAbstractAxis;
using QtCharts::QLegendMarker;
#endif

// Sizes in pixels, not points: a projector shows pixels, whatever DPI the machine reports.
struct BodyPlots::Style {
  int title_px;
  int axis_title_px;
  int tick_px;
  int legend_px;
  int line_px;
  double marker_px;
  QSize minimum;
};

namespace {

constexpr int kRedrawMs = 100;
constexpr double kTimeTick = 2;  // s between the time axis's ticks, anchored at t = 0
// In the panel: a chart 260 px high (the tab scrolls when they do not fit); in the projector window: at
// least 600 x 300 px each, text 18-24 px, as a room's back row reads it.
const BodyPlots::Style kDocked{14, 12, 12, 12, 3, 14, QSize(0, 260)};
const BodyPlots::Style kProjector{24, 20, 18, 18, 4, 18, QSize(600, 300)};
constexpr int kGridColumns = 2;
// A restart moves a body farther than its speed can in the time between two states; this much farther (m)
// is taken as one, above what a mode change or a bounce between two states can add.
constexpr double kJumpSlack = 0.1;
const QColor kColours[] = {QColor(31, 119, 180), QColor(255, 127, 14), QColor(214, 39, 40)};
const char* const kPngVariable = "RBS_PLOTS_PNG";

QFont pixels(QFont font, int px) {
  font.setPixelSize(px);
  return font;
}

}  // namespace

BodyPlots::BodyPlots(CallQueue& calls, QWidget* parent) : QWidget(parent), calls_(calls) {
  auto* layout = new QVBoxLayout(this);
  auto* row = new QHBoxLayout();
  row->addWidget(new QLabel("body", this));
  choice_ = new QComboBox(this);
  choice_->setObjectName("plot_body");
  choice_->setToolTip("the body whose last 10 s of states the charts show");
  row->addWidget(choice_, 1);
  auto* projector = new QPushButton("Projector view", this);
  projector->setObjectName("plots_projector");
  projector->setToolTip("every chart of the body at once, in a window of its own, large enough for a room");
  row->addWidget(projector);
  layout->addLayout(row);
  moved_ = new QLabel("the charts are in the projector window; closing it brings them back", this);
  moved_->setObjectName("plots_moved");
  moved_->setWordWrap(true);
  moved_->hide();
  layout->addWidget(moved_);
  auto* scroll = new QScrollArea(this);  // the charts keep a legible height; the panel may be shorter
  scroll->setObjectName("plots");
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  charts_box_ = new QWidget(scroll);
  charts_box_->setLayout(new QVBoxLayout());
  charts_box_->layout()->setContentsMargins(0, 0, 0, 0);
  scroll->setWidget(charts_box_);
  layout->addWidget(scroll, 1);

  window_ = new QWidget(this, Qt::Window);
  window_->setObjectName("plots_window");
  window_->installEventFilter(this);
  auto* window_layout = new QVBoxLayout(window_);
  auto* top = new QHBoxLayout();
  heading_ = new QLabel(window_);
  heading_->setObjectName("plots_heading");
  heading_->setFont(pixels(heading_->font(), kProjector.title_px));
  top->addWidget(heading_, 1);
  saved_ = new QLabel(window_);
  saved_->setObjectName("plots_saved");
  saved_->setFont(pixels(saved_->font(), kProjector.legend_px));
  top->addWidget(saved_);
  save_ = new QPushButton("Save PNG", window_);
  save_->setObjectName("plots_save");
  save_->setFont(pixels(save_->font(), kProjector.legend_px));
  save_->setToolTip("the charts as one PNG, at the window's resolution, for a slide");
  top->addWidget(save_);
  window_layout->addLayout(top);
  grid_ = new QWidget(window_);
  grid_->setObjectName("plots_grid");
  grid_->setLayout(new QGridLayout());
  grid_->layout()->setContentsMargins(0, 0, 0, 0);
  window_layout->addWidget(grid_, 1);

  const auto chosen = [this](const QString& body) { select(body.toStdString()); };
  connect(choice_, &QComboBox::currentTextChanged, this, chosen);
  connect(projector, &QPushButton::clicked, this, [this] { openWindow(); });
  connect(save_, &QPushButton::clicked, this, [this] { savePng(); });
  connect(&redraw_timer_, &QTimer::timeout, this, [this] { redraw(); });
  redraw_timer_.start(kRedrawMs);
}

void BodyPlots::setNode(const std::string& ns) {
  if (ns == ns_) return;
  ns_ = ns;
  origin_ = 0;
  gravity_ = 0;
  commands_ = ros::NodeHandle().subscribe<Command>(ns_ + "/commands", 100,
                                                   [this](const Command::ConstPtr& c) { onCommand(*c); });
  // The world's g: sim.launch loads the config's keys there, and a key it lacks takes its default.
  const std::string name = ns_ + "/gravity";
  const auto ask = [name] {
    double g = kDefaultGravity;
    ros::param::get(name, g);
    return g;
  };
  const auto got = [this, ns](const double& g) {
    if (ns == ns_ && gravity_ == 0) gravity_ = g;  // a config command's, if one came first, is newer
  };
  calls_.post<double>(this, ask, got);
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
  state_.shutdown();  // before its type goes
  parameters_.shutdown();
  type_ = rvizBodyTypeOf(type);
  build();
  if (!type_) return;
  ros::NodeHandle nh;
  const std::string server = ns_ + "/" + body;
  parameters_ = nh.subscribe<dynamic_reconfigure::Config>(
      server + "/parameter_updates", 1,
      [this](const dynamic_reconfigure::Config::ConstPtr& c) { type_->setParameters(*c); });
  const auto taken = [this](double t) { return take(t); };
  state_ = type_->plot(nh, server + "/state", taken, *this);
}

// The charts of the chosen body's type, then its energy.
void BodyPlots::build() {
  for (auto& chart : charts_) delete chart.view;
  charts_.clear();
  clear();
  heading_->setText(QString::fromStdString(body_));
  window_->setWindowTitle(QString("rigid_body_sim: %1").arg(QString::fromStdString(body_)));
  if (!type_) return;  // no body
  for (const ChartSpec& spec : type_->charts()) {
    charts_.push_back(makeChart(spec.title, spec.y_title));
    for (const TrackSpec& track : spec.tracks) addTrack(charts_.back(), track);
  }
  charts_.push_back(makeChart(QString("energy (potential 0 %1)").arg(type_->potentialZero()), "E (J)"));
  for (const char* track : {"energy", "kinetic", "potential"})
    addTrack(charts_.back(), {track, track == std::string("energy") ? "total" : track});
  place();
}

BodyPlots::Chart BodyPlots::makeChart(const QString& title, const QString& y_title) {
  auto* chart = new QChart();
  chart->setTitle(title);
  chart->setMargins(QMargins(2, 2, 2, 2));
  chart->legend()->setAlignment(Qt::AlignTop);
  Chart made{new QChartView(chart, charts_box_), new QValueAxis(), new QCategoryAxis(), {}};
  made.view->setRenderHint(QPainter::Antialiasing);
  made.x->setTickType(QValueAxis::TicksDynamic);  // ticks at whole multiples, moving with the window
  made.x->setTickAnchor(0);
  made.x->setTickInterval(kTimeTick);
  made.x->setLabelFormat("%.0f");  // whole seconds from 0 on: distinct, never "-0"
  made.x->setTitleText("t since reset (s)");
  made.y->setTitleText(y_title);
  made.y->setLabelsPosition(QCategoryAxis::AxisLabelsPositionOnValue);
  chart->addAxis(made.x, Qt::AlignBottom);
  chart->addAxis(made.y, Qt::AlignLeft);
  return made;
}

void BodyPlots::addTrack(Chart& chart, const TrackSpec& spec) {
  QXYSeries* series = spec.marks ? static_cast<QXYSeries*>(new QScatterSeries()) : new QLineSeries();
  series->setName(spec.name);
  QPen pen(kColours[chart.tracks.size() % 3]);
  if (chart.tracks.size() == 1) pen.setStyle(Qt::DashLine);  // the second line shows where they coincide
  series->setPen(pen);
  series->setColor(pen.color());
  chart.view->chart()->addSeries(series);
  series->attachAxis(chart.x);
  series->attachAxis(chart.y);
  chart.tracks.push_back({spec.key, {series}, {}, {}, nullptr});
  if (!spec.marks) return;
  auto* note = new QGraphicsSimpleTextItem(chart.view->chart());  // beside the last mark
  note->hide();
  chart.tracks.back().note_item = note;
  connect(chart.view->chart(), &QChart::plotAreaChanged, this, [this] { placeNotes(); });
}

// Fonts, pens and sizes for where the chart is: the panel's tab or the projector window.
void BodyPlots::style(Chart& chart, const Style& style) {
  QChart* c = chart.view->chart();
  c->setTitleFont(pixels(c->titleFont(), style.title_px));
  c->legend()->setFont(pixels(c->legend()->font(), style.legend_px));
  for (QAbstractAxis* axis : {static_cast<QAbstractAxis*>(chart.x), static_cast<QAbstractAxis*>(chart.y)}) {
    axis->setTitleFont(pixels(axis->titleFont(), style.axis_title_px));
    axis->setLabelsFont(pixels(axis->labelsFont(), style.tick_px));
  }
  for (auto& track : chart.tracks) {
    for (QXYSeries* series : track.series) {
      QPen pen = series->pen();
      pen.setWidth(style.line_px);
      series->setPen(pen);
      if (auto* scatter = qobject_cast<QScatterSeries*>(series)) scatter->setMarkerSize(style.marker_px);
    }
  }
  chart.view->setMinimumSize(style.minimum);
  for (auto& track : chart.tracks) {
    if (track.note_item) track.note_item->setFont(pixels(track.note_item->font(), style.tick_px));
  }
}

// In the window's grid (two columns; an odd last chart spans both) while it is open, else one under another
// in the tab.
void BodyPlots::place() {
  const bool projected = window_->isVisible();
  moved_->setVisible(projected);
  for (std::size_t i = 0; i < charts_.size(); ++i) {
    QWidget* view = charts_[i].view;
    if (QWidget* holder = view->parentWidget()) holder->layout()->removeWidget(view);
    style(charts_[i], projected ? kProjector : kDocked);
    if (projected) {
      const int row = static_cast<int>(i) / kGridColumns, column = static_cast<int>(i) % kGridColumns;
      const bool alone = i + 1 == charts_.size() && column == 0;
      static_cast<QGridLayout*>(grid_->layout())->addWidget(view, row, column, 1, alone ? kGridColumns : 1);
    } else {
      charts_box_->layout()->addWidget(view);
    }
  }
  dirty_ = true;
}

// Maximized on rviz's screen (at its size where no window manager maximizes).
void BodyPlots::openWindow() {
  const bool was_recording = recording();
  QScreen* screen = QGuiApplication::screenAt(window()->geometry().center());
  if (!screen) screen = QGuiApplication::primaryScreen();
  if (screen) window_->setGeometry(screen->availableGeometry());
  window_->showMaximized();
  window_->raise();
  window_->activateWindow();
  place();
  if (!was_recording) clear();  // nothing was recorded while neither showed
}

bool BodyPlots::eventFilter(QObject* watched, QEvent* event) {
  if (watched == window_ && event->type() == QEvent::Hide) {
    const auto back = [this] { place(); };  // once it is hidden
    QMetaObject::invokeMethod(this, back, Qt::QueuedConnection);
  }
  return QWidget::eventFilter(watched, event);
}

// The charts as the window shows them, one PNG: to the file RBS_PLOTS_PNG names (tests), else where the
// dialog says.
void BodyPlots::savePng() {
  QString path = QString::fromLocal8Bit(std::getenv(kPngVariable));
  if (path.isEmpty()) {
    const QString suggested = QDir::home().filePath(QString::fromStdString(body_) + "_plots.png");
    path = QFileDialog::getSaveFileName(window_, "Save the charts as PNG", suggested, "PNG image (*.png)");
    if (path.isEmpty()) return;
  }
  // The window as it shows, its body's name above the charts, without the buttons of the screen.
  save_->hide();
  saved_->hide();
  const QPixmap picture = window_->grab();
  save_->show();
  saved_->show();
  saved_->setText(picture.save(path, "PNG")
                      ? QString("saved %1 (%2 x %3 px)").arg(path).arg(picture.width()).arg(picture.height())
                      : QString("could not write %1").arg(path));
}

// The total as the state has it; the kinetic the core's; the potential what remains of the total.
void BodyPlots::energies(double t, double total, std::optional<double> kinetic) {
  const std::size_t chart = charts_.size() - 1;
  append(chart, 0, t, total);
  if (!kinetic) return;
  append(chart, 1, t, *kinetic);
  append(chart, 2, t, total - *kinetic);
}

bool BodyPlots::recording() const { return isVisible() || window_->isVisible(); }

bool BodyPlots::take(double t) {
  if (!recording() || charts_.empty() || t <= origin_) return false;
  trim(t);
  return true;
}

// Whether the body moved farther since its last state than its speed could take it: a restart (a lap).
bool BodyPlots::restarted(double t, double x, double v) {
  const bool jumped = have_last_ && std::abs(x - last_x_) >
                                        std::max(std::abs(v), std::abs(last_v_)) * (t - last_t_) + kJumpSlack;
  have_last_ = true;
  last_t_ = t;
  last_x_ = x;
  last_v_ = v;
  if (jumped) ++line_;
  return jumped;
}

// A reset or a new config (anyone's) puts the bodies back at their start: what came up to it goes (a paused
// node's last state has its t), and the t axis counts from it. t never goes back, so the states after it
// stay; an old one (the latched topic's last command) takes nothing but gives the axis its start.
void BodyPlots::onCommand(const Command& command) {
  if (command.kind != "reset" && command.kind != "config") return;
  origin_ = std::max(origin_, command.t);
  // A config's world has its g on a line of its own (config_writer writes every world key).
  const std::size_t at = command.yaml.find("gravity:");
  if (command.kind == "config" && at != std::string::npos && (at == 0 || command.yaml[at - 1] == '\n'))
    gravity_ = std::strtod(command.yaml.c_str() + at + 8, nullptr);
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) {
      while (!track.points.empty() && track.points.front().t <= command.t) track.points.pop_front();
    }
  }
  forget();
}

void BodyPlots::append(std::size_t chart, std::size_t track, double t, double value) {
  charts_.at(chart).tracks.at(track).points.push_back({t, value, line_});
  dirty_ = true;
}

void BodyPlots::mark(std::size_t chart, std::size_t track, double t, double value, const QString& note) {
  append(chart, track, t, value);
  charts_[chart].tracks[track].note = note;
}

// Only the last kPlotWindow seconds are kept.
void BodyPlots::trim(double t) {
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) {
      while (!track.points.empty() && track.points.front().t < t - kPlotWindow) track.points.pop_front();
      if (track.points.empty()) track.note.clear();  // its mark went out of the window
    }
  }
}

void BodyPlots::clear() {
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) track.points.clear();
  }
  forget();
}

// No line under way, no note, no phase of the body's motion.
void BodyPlots::forget() {
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) track.note.clear();
  }
  have_last_ = false;
  if (type_) type_->forget();
  dirty_ = true;
}

// Shown again after being hidden: nothing was recorded meanwhile, so the charts start afresh.
void BodyPlots::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  if (!window_->isVisible()) clear();
}

// A line series per line (the points between two restarts), all with the first one's pen and one legend
// entry; a scatter series takes every point.
void BodyPlots::drawTrack(Chart& chart, Track& track) {
  std::vector<QVector<QPointF>> lines(1);
  const bool scatter = qobject_cast<QScatterSeries*>(track.series.front()) != nullptr;
  for (std::size_t i = 0; i < track.points.size(); ++i) {
    const Point& p = track.points[i];
    if (!scatter && i > 0 && p.line != track.points[i - 1].line) lines.emplace_back();
    lines.back().append(QPointF(p.t - origin_, p.value));
  }
  while (track.series.size() < lines.size()) {
    auto* more = new QLineSeries();
    more->setPen(track.series.front()->pen());
    more->setColor(track.series.front()->color());
    chart.view->chart()->addSeries(more);
    more->attachAxis(chart.x);
    more->attachAxis(chart.y);
    for (QLegendMarker* marker : chart.view->chart()->legend()->markers(more)) marker->setVisible(false);
    track.series.push_back(more);
  }
  for (std::size_t i = 0; i < track.series.size(); ++i)
    track.series[i]->replace(i < lines.size() ? lines[i] : QVector<QPointF>());
}

// At most every kRedrawMs, and only in sight: the series take the points, the axes the window and range.
void BodyPlots::redraw() {
  if (!dirty_ || !recording()) return;
  dirty_ = false;
  double t_last = -std::numeric_limits<double>::infinity();
  for (const auto& chart : charts_) {
    for (const auto& track : chart.tracks) {
      if (!track.points.empty()) t_last = std::max(t_last, track.points.back().t - origin_);
    }
  }
  for (auto& chart : charts_) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (auto& track : chart.tracks) {
      drawTrack(chart, track);
      for (const Point& p : track.points) {
        low = std::min(low, p.value);
        high = std::max(high, p.value);
      }
    }
    if (!std::isfinite(t_last) || !std::isfinite(low)) continue;
    chart.x->setRange(std::max(0.0, t_last - kPlotWindow), std::max(kPlotWindow, t_last));  // from 0 at first
    const AxisTicks ticks = niceTicks(low, high);
    QStringList labels;
    for (const std::string& label : ticks.labels) labels << QString::fromStdString(label);
    if (labels != chart.y->categoriesLabels()) {
      for (const QString& old : chart.y->categoriesLabels()) chart.y->remove(old);
      chart.y->setStartValue(ticks.low - ticks.step);
      for (int k = 0; k < labels.size(); ++k) chart.y->append(labels[k], ticks.low + k * ticks.step);
    }
    chart.y->setRange(ticks.low, ticks.high);
  }
  placeNotes();
}

// Each note beside its last mark (to its left when the mark is in the right half of the chart).
void BodyPlots::placeNotes() {
  for (const Chart& chart : charts_) {
    for (const Track& marks : chart.tracks) {
      if (!marks.note_item) continue;
      if (marks.note.isEmpty() || marks.points.empty()) {
        marks.note_item->hide();
        continue;
      }
      QChart* drawn = chart.view->chart();
      const Point& mark = marks.points.back();
      const QPointF at = drawn->mapToPosition(QPointF(mark.t - origin_, mark.value), marks.series.front());
      marks.note_item->setText(marks.note);
      const QRectF box = marks.note_item->boundingRect();
      const bool right_half = at.x() > drawn->plotArea().center().x();
      marks.note_item->setPos(right_half ? at.x() - box.width() - 14 : at.x() + 14, at.y() + 10);
      marks.note_item->show();
    }
  }
}

std::string BodyPlots::layoutLines() const {
  std::ostringstream out;
  for (std::size_t i = 0; i < charts_.size(); ++i) {
    const Chart& chart = charts_[i];
    const QWidget* drawn_in = chart.view->viewport();  // the view's own region is all covered by it
    const QRect shown = drawn_in->visibleRegion().boundingRect();
    const QPoint at = drawn_in->mapToGlobal(shown.topLeft());
    out << "plot.chart" << i << ' ' << at.x() << ' ' << at.y() << ' ' << shown.width() << ' '
        << shown.height() << " 1 " << chart.view->chart()->titleFont().pixelSize() << ' '
        << chart.x->titleFont().pixelSize() << ' ' << chart.x->labelsFont().pixelSize() << ' '
        << chart.y->labelsFont().pixelSize() << ' ' << formatNumber(chart.x->min()) << ' '
        << formatNumber(chart.x->max()) << ' ' << chart.y->categoriesLabels().join(",").toStdString() << '\n';
    for (const auto& track : chart.tracks) {
      out << "plot." << track.key << " 0 0 0 0 1 " << track.points.size();
      if (!track.points.empty())
        out << ' ' << formatNumber(track.points.back().t) << ' ' << formatNumber(track.points.back().value);
      out << '\n';
      const auto drawn = [](const QXYSeries* s) { return s->count() > 0; };
      out << "plot." << track.key << ".lines 0 0 0 0 1 "
          << std::count_if(track.series.begin(), track.series.end(), drawn) << '\n';
      if (track.note_item)
        out << "plot." << track.key << ".note 0 0 0 0 1 " << track.note.toStdString() << '\n';
    }
  }
  return out.str();
}

}  // namespace rigid_body_sim
