#include "rigid_body_sim/rviz/body_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include <QDir>
#include <QFileDialog>
#include <QGraphicsRectItem>
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

#include "rigid_body_sim/Command.h"
#include "rigid_body_sim/GetEvents.h"
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
constexpr std::uint32_t kEventQueue = 10000;  // events between two of rviz's spins: none dropped
constexpr double kNoteAside = 14;             // px from a mark's centre to its note's side
constexpr double kNoteBelow = 10;             // px from a mark's centre to its note's top (or bottom)
constexpr double kNoteGap = 4;                // px between two notes
constexpr double kNotePad = 2;                // px of a note's ground around its text
constexpr double kNoteZ = 100;                // above every series and the legend
constexpr int kNoteDarker = 130;              // a note's text: its marks' colour, this much darker (%)
const QColor kNoteGround(255, 255, 255, 215);
// A chart's lines in turn, and its tracks of marks in turn: a red disc, then a green square.
const QColor kColours[] = {QColor(31, 119, 180), QColor(255, 127, 14), QColor(214, 39, 40)};
const QColor kMarkColours[] = {QColor(214, 39, 40), QColor(44, 160, 44)};
const QScatterSeries::MarkerShape kMarkShapes[] = {QScatterSeries::MarkerShapeCircle,
                                                   QScatterSeries::MarkerShapeRectangle};
const char* const kPngVariable = "RBS_PLOTS_PNG";

QFont pixels(QFont font, int px) {
  font.setPixelSize(px);
  return font;
}

// A restart with cause reset or config begins a run: the node's ~get_events forgets what came before it.
bool startsRun(const Event& event) {
  const auto cause = eventText(event.values, "cause");
  return eventRole(event) == EventRole::Restart && cause && (*cause == "reset" || *cause == "config");
}

bool sameEvent(const Event& a, const Event& b) {
  return a.t == b.t && a.body == b.body && a.type == b.type && a.kind == b.kind && a.values == b.values;
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
  ++found_;  // an answer of the node before is not this one's
  event_subscriber_ = ros::NodeHandle().subscribe<Event>(
      ns_ + "/events", kEventQueue, [this](const Event::ConstPtr& e) { addEvents({*e}); });
  // A reset or a new config is on ~commands too, at its restarts' instant: a recording made before the node
  // had events says it there alone. (A replay's player waits for a subscriber of each topic it plays.)
  command_subscriber_ =
      ros::NodeHandle().subscribe<Command>(ns_ + "/commands", 100, [this](const Command::ConstPtr& command) {
        if ((command->kind != "reset" && command->kind != "config") || command->t <= origin_) return;
        startRun(command->t);
        placeEvents();
      });
  setBodies({});
}

// What the node kept of its run (since its start, or its last reset): what came before the panel found it.
// The topic brings what comes after; an event both bring is kept once.
void BodyPlots::fetchEvents() {
  const std::string name = ns_ + "/get_events";
  const std::uint64_t found = ++found_;
  using Answer = std::optional<std::vector<Event>>;
  const auto ask = [name]() -> Answer {
    GetEvents srv;
    if (!CallQueue::services().call(name, srv)) return std::nullopt;  // a replay: no node
    return srv.response.events;
  };
  const auto got = [this, found](const Answer& events) {
    if (found == found_ && events) addEvents(*events);  // the node not lost or found again since
  };
  calls_.post<Answer>(this, ask, got);
}

// The chooser lists the bodies in name order; the chosen one stays while it exists.
void BodyPlots::setBodies(const std::map<std::string, std::string>& bodies) {
  if (bodies == bodies_) return;
  const bool found = bodies_.empty() && !bodies.empty();  // the node found (a new one, or back)
  bodies_ = bodies;
  if (found) {
    events_.clear();
    origin_ = newest_ = 0;
    fetchEvents();
  }
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
  placeEvents();
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
  const auto marks = static_cast<std::size_t>(
      std::count_if(chart.tracks.begin(), chart.tracks.end(), [](const Track& t) { return t.note_item; }));
  const std::size_t lines = chart.tracks.size() - marks;
  QXYSeries* series;
  QPen pen;
  if (spec.marks) {
    auto* scatter = new QScatterSeries();
    scatter->setMarkerShape(kMarkShapes[marks % 2]);
    series = scatter;
    pen = QPen(kMarkColours[marks % 2]);
  } else {
    series = new QLineSeries();
    pen = QPen(kColours[lines % 3]);
    if (lines == 1) pen.setStyle(Qt::DashLine);  // the second line shows where they coincide
  }
  series->setName(spec.name);
  series->setPen(pen);
  series->setColor(pen.color());
  chart.view->chart()->addSeries(series);
  series->attachAxis(chart.x);
  series->attachAxis(chart.y);
  chart.tracks.push_back({spec.key, {series}, {}, nullptr});
  if (!spec.marks) return;
  // Its note beside its last mark, in its colour on a light ground over the lines, above the series.
  auto* ground = new QGraphicsRectItem(chart.view->chart());
  ground->setBrush(kNoteGround);
  ground->setPen(Qt::NoPen);
  ground->setZValue(kNoteZ);
  ground->hide();
  auto* note = new QGraphicsSimpleTextItem(ground);
  note->setBrush(pen.color().darker(kNoteDarker));
  note->setPos(kNotePad, kNotePad);
  chart.tracks.back().note_ground = ground;
  chart.tracks.back().note_item = note;
  if (marks == 0) connect(chart.view->chart(), &QChart::plotAreaChanged, this, [this] { placeNotes(); });
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
  if (t <= origin_) return false;  // from before the run's start (a reset's)
  newest_ = std::max(newest_, t);
  trim();
  return recording() && !charts_.empty();
}

// Each event once, in time order. One of the chosen body marks or restarts it; a restart with cause reset or
// config (every body's, at one instant) begins a run.
void BodyPlots::addEvents(const std::vector<Event>& events) {
  bool placed = false;
  for (const Event& event : events) {
    if (event.t < origin_) continue;  // of the run before (a late arrival)
    const auto after = std::upper_bound(events_.begin(), events_.end(), event.t,
                                        [](double t, const Event& e) { return t < e.t; });
    bool seen = false;
    for (auto at = after; at != events_.begin() && std::prev(at)->t == event.t; --at)
      seen = seen || sameEvent(*std::prev(at), event);
    if (seen) continue;
    events_.insert(after, event);
    newest_ = std::max(newest_, event.t);
    placed = placed || event.body == body_;
    if (startsRun(event) && event.t > origin_) {
      startRun(event.t);
      placed = true;
    }
  }
  trim();
  if (placed) placeEvents();
}

// Its points go (a paused node's last state has the reset's t), and so do the events before it. t never goes
// back, so the states after it stay; a late one from before takes nothing (take).
void BodyPlots::startRun(double t) {
  origin_ = t;
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) {
      while (!track.points.empty() && track.points.front().t <= t) track.points.pop_front();
    }
  }
  const auto first =
      std::lower_bound(events_.begin(), events_.end(), t, [](const Event& e, double at) { return e.t < at; });
  events_.erase(events_.begin(), first);
  dirty_ = true;
}

// The chosen body's type marks what it draws of its events; its restarts are where a new line starts.
void BodyPlots::placeEvents() {
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) {
      if (track.note_item) track.points.clear();
    }
  }
  restarts_.clear();
  dirty_ = true;
  if (!type_ || charts_.empty()) return;  // no body, or its charts not built yet
  for (const Event& event : events_) {
    if (event.body != body_) continue;
    if (eventRole(event) == EventRole::Restart) restarts_.push_back(event.t);
    type_->plotEvent(event, *this);
  }
}

void BodyPlots::append(std::size_t chart, std::size_t track, double t, double value) {
  charts_.at(chart).tracks.at(track).points.push_back({t, value});
  dirty_ = true;
}

void BodyPlots::mark(std::size_t chart, std::size_t track, double t, double value, const QString& note) {
  charts_.at(chart).tracks.at(track).points.push_back({t, value, note});
  dirty_ = true;
}

// Only the last kPlotWindow seconds are kept, of the points and of the events.
void BodyPlots::trim() {
  const double cutoff = newest_ - kPlotWindow;
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) {
      while (!track.points.empty() && track.points.front().t < cutoff) track.points.pop_front();
    }
  }
  const auto first = std::lower_bound(events_.begin(), events_.end(), cutoff,
                                      [](const Event& e, double at) { return e.t < at; });
  events_.erase(events_.begin(), first);
  while (!restarts_.empty() && restarts_.front() < cutoff) restarts_.erase(restarts_.begin());
}

// The lines start afresh; the marks of the window come back from the kept events.
void BodyPlots::clear() {
  for (auto& chart : charts_) {
    for (auto& track : chart.tracks) track.points.clear();
  }
  placeEvents();
}

// Shown again after being hidden: nothing was recorded meanwhile, so the lines start afresh.
void BodyPlots::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  if (!window_->isVisible()) clear();
}

// A line series per line (the points between two of the body's restarts: a state at a restart's instant is
// the new line's), all with the first one's pen and one legend entry; a scatter series takes every point.
void BodyPlots::drawTrack(Chart& chart, Track& track) {
  std::vector<QVector<QPointF>> lines(1);
  const bool scatter = qobject_cast<QScatterSeries*>(track.series.front()) != nullptr;
  for (std::size_t i = 0; i < track.points.size(); ++i) {
    const Point& p = track.points[i];
    if (!scatter && i > 0) {
      const auto restart = std::upper_bound(restarts_.begin(), restarts_.end(), track.points[i - 1].t);
      if (restart != restarts_.end() && *restart <= p.t) lines.emplace_back();
    }
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

// Each note beside its track's last mark: to its right, or to its left when the mark is in the right half of
// the chart; under it, or over it when the mark is in the lower half; moved on that way clear of the notes
// placed before it on its chart, and sideways into the plot area where it fits.
void BodyPlots::placeNotes() {
  for (const Chart& chart : charts_) {
    QChart* drawn = chart.view->chart();
    const QRectF area = drawn->plotArea();
    std::vector<QRectF> placed;
    for (const Track& marks : chart.tracks) {
      if (!marks.note_item) continue;
      if (marks.points.empty() || marks.points.back().note.isEmpty()) {
        marks.note_ground->hide();
        continue;
      }
      const Point& mark = marks.points.back();
      const QPointF at = drawn->mapToPosition(QPointF(mark.t - origin_, mark.value), marks.series.front());
      marks.note_item->setText(mark.note);
      QRectF box = marks.note_item->boundingRect().adjusted(0, 0, 2 * kNotePad, 2 * kNotePad);
      const bool left = at.x() > area.center().x(), up = at.y() > area.center().y();
      box.moveLeft(left ? at.x() - box.width() - kNoteAside : at.x() + kNoteAside);
      if (box.width() <= area.width())
        box.moveLeft(std::clamp(box.left(), area.left(), area.right() - box.width()));
      box.moveTop(up ? at.y() - kNoteBelow - box.height() : at.y() + kNoteBelow);
      for (bool moved = true; moved;) {
        moved = false;
        for (const QRectF& other : placed) {
          if (!box.intersects(other)) continue;
          box.moveTop(up ? other.top() - kNoteGap - box.height() : other.bottom() + kNoteGap);
          moved = true;
        }
      }
      placed.push_back(box);
      marks.note_ground->setRect(0, 0, box.width(), box.height());
      marks.note_ground->setPos(box.topLeft());
      marks.note_ground->show();
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
      if (track.note_item) {
        out << "plot." << track.key << ".note 0 0 0 0 1 "
            << (track.points.empty() ? std::string() : track.points.back().note.toStdString()) << '\n';
      }
    }
  }
  return out.str();
}

}  // namespace rigid_body_sim
