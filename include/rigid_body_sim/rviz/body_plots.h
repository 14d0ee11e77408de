// The SimPanel's Plots tab: live charts (QtCharts) of ONE body, chosen in a combo box, over the last
// kPlotWindow simulated seconds, from the body's state topic: the charts of its type (rviz/body_type_rviz.h;
// a roller's speeds, a rod's ends, a block's speed) and, for every body, its energy: the total (the state's
// `energy`), the kinetic (the core's, from the state and the body's parameters) and the potential (their
// difference). The parameters come from the body's reconfigure server.
// Events: the node's ~events (and ~get_events when the panel finds the node, for what came before), kept for
// the window. The body's type marks its own (a roller's slip-to-roll instants and finishes, each with its
// note) at their instants; a restart of the body (its lap, a race's new lap, a reset) starts a new line
// there, never a segment across it; a restart with cause reset or config (also on ~commands, for a recording
// without events) begins a run: the t axis counts from it, and what came before goes (the node's t goes on
// through a reset, a user's charts start afresh at 0). Nothing of the states is recorded or drawn while
// neither the tab nor the projector window shows (the lines start afresh when one shows again; the marks of
// the window come back from the kept events), and nothing comes while the node is paused. The projector
// window (the tab's "Projector view") holds the same charts, all at once, in a grid with fonts in pixels
// (legible from the back of a room), and saves them as one PNG ("Save PNG": a file dialog, or the file
// RBS_PLOTS_PNG names, for tests); closing it puts the charts back in the tab.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QCategoryAxis>
#include <QChart>
#include <QChartView>
#include <QComboBox>
#include <QGraphicsRectItem>
#include <QGraphicsSimpleTextItem>
#include <QLabel>
#include <QLineSeries>
#include <QPointF>
#include <QPushButton>
#include <QScatterSeries>
#include <QTimer>
#include <QValueAxis>
#include <QWidget>

#include <dynamic_reconfigure/Config.h>
#include <ros/ros.h>

#include "rigid_body_sim/Event.h"
#include "rigid_body_sim/rviz/body_type_rviz.h"
#include "rigid_body_sim/rviz/call_queue.h"

namespace rigid_body_sim {

// Qt 5 puts QtCharts in a namespace of its own (QT_CHARTS_USE_NAMESPACE); Qt 6 does not.
#if QT_VERSION < QT_VERSION_CHECK(6, 0, 0)
using QtCharts::QCategoryAxis;
using QtCharts::QChart;
using QtCharts::QChartView;
using QtCharts::QLineSeries;
using QtCharts::QScatterSeries;
using QtCharts::QValueAxis;
using QtCharts::QXYSeries;
#endif

inline constexpr double kPlotWindow = 10.0;  // simulated seconds shown

class BodyPlots : public QWidget, private PlotSink {
  Q_OBJECT
 public:
  struct Style;  // fonts, pens and sizes: the tab's or the projector window's (body_plots.cpp)

  explicit BodyPlots(CallQueue& calls, QWidget* parent = nullptr);

  void setNode(const std::string& ns);  // the node's namespace (its ~events, ~commands)
  // The node's bodies: name -> state message type. Found again after none (the node found, or back): the
  // run's events so far (~get_events).
  void setBodies(const std::map<std::string, std::string>& bodies);
  void clear();
  // The body to show once it is there (an rviz config's "Plot Body"), and the one shown.
  void prefer(const std::string& body);
  const std::string& chosen() const { return body_; }
  // The projector window: every chart of the body at once, as large as the screen allows.
  void openWindow();
  // For the GUI test (RBS_PANEL_LAYOUT): one line per series, "plot.<series> 0 0 0 0 1 count t value" (its
  // last point; count 0: no t and value) and "plot.<series>.lines 0 0 0 0 1 lines" (the lines drawn); one
  // per chart, "plot.chart<i> x y width height 1 title_px axis_title_px x_tick_px y_tick_px x_min x_max
  // y_ticks" (y_ticks comma-separated); per track of marks, "plot.<series>.note 0 0 0 0 1 text".
  std::string layoutLines() const;

 protected:
  void showEvent(QShowEvent* event) override;
  bool eventFilter(QObject* watched, QEvent* event) override;  // the projector window's closing

 private:
  struct Point {
    double t;
    double value;
    QString note = {};  // a mark's
  };
  struct Track {
    std::string key;                 // plot.<key> in the layout lines
    std::vector<QXYSeries*> series;  // a line series per line drawn, the first with the legend entry
    std::deque<Point> points;
    QGraphicsRectItem* note_ground = nullptr;  // marks': the ground of the last one's note, beside it
    QGraphicsSimpleTextItem* note_item = nullptr;
  };
  struct Chart {
    QChartView* view;
    QValueAxis* x;
    QCategoryAxis* y;  // its labels are ours: distinct, never "-0"
    std::vector<Track> tracks;
  };
  void select(const std::string& body);
  void build();  // the charts of the chosen body's type; none without one
  Chart makeChart(const QString& title, const QString& y_title);
  void addTrack(Chart& chart, const TrackSpec& spec);
  void place();  // the charts in the projector window while it is open, else in the tab
  void style(Chart& chart, const Style& style);
  void fetchEvents();  // ~get_events: the run's events so far
  void addEvents(const std::vector<Event>& events);
  void startRun(double t);  // a reset or a new config at t: the t axis counts from it
  void placeEvents();       // the chosen body's marks and restarts, from the kept events
  bool recording() const;
  bool take(double t);  // whether a state at t is drawn; drops what is older than the window
  // PlotSink: what the body's type draws of each state and event.
  void append(std::size_t chart, std::size_t track, double t, double value) override;
  void mark(std::size_t chart, std::size_t track, double t, double value, const QString& note) override;
  void energies(double t, double total, std::optional<double> kinetic) override;
  double origin() const override { return origin_; }
  void trim();  // what is older than the window goes: points and kept events
  void redraw();
  void drawTrack(Chart& chart, Track& track);
  void placeNotes();
  void savePng();

  CallQueue& calls_;
  std::string ns_, body_;
  std::map<std::string, std::string> bodies_;
  QComboBox* choice_;
  QWidget* charts_box_;
  QLabel* moved_;    // in the tab while the charts are in the projector window
  QWidget* window_;  // the projector window
  QLabel* heading_;  // its body's name
  QWidget* grid_;    // its charts
  QPushButton* save_;
  QLabel* saved_;                       // where the PNG went
  std::unique_ptr<RvizBodyType> type_;  // the chosen body's
  std::vector<Chart> charts_;           // its type's, then the energy
  std::vector<Event> events_;           // every body's of the run in the window, in time order, each once
  std::vector<double> restarts_;        // the chosen body's restarts among them: where a new line starts
  double origin_ = 0;                   // t of the last reset or config: the t axis starts there
  double newest_ = 0;                   // the latest t of a state or event: the window ends there
  std::uint64_t found_ = 0;             // how many times the node was found (a get_events answer's)
  bool dirty_ = false;
  QTimer redraw_timer_;
  ros::Subscriber state_, parameters_, event_subscriber_, command_subscriber_;
};

}  // namespace rigid_body_sim
