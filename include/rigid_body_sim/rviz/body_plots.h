// The SimPanel's Plots tab: live charts (QtCharts) of ONE body, chosen in a combo box, over the last
// kPlotWindow simulated seconds, from the body's state topic. Every body: its energy, the total (the state's
// `energy`), the kinetic (the core's, from the state and the body's parameters) and the potential (their
// difference). A roller: v and -omega R on one chart (equal while it rolls), each slip-to-roll instant marked
// (the first rolling state after a slipping one), and the friction force. A rod: the height of each end,
// y +- (L/2) sin(theta). The parameters (L, R, M, c) come from the body's reconfigure server. Nothing is
// recorded or drawn while the tab is hidden (the charts start afresh when it shows again), nothing comes
// while the node is paused, and the points before a reset (the node's ~commands, kind "reset") go.
#pragma once

#include <deque>
#include <map>
#include <string>
#include <vector>

#include <QChart>
#include <QChartView>
#include <QComboBox>
#include <QLineSeries>
#include <QPointF>
#include <QScatterSeries>
#include <QTimer>
#include <QValueAxis>
#include <QWidget>

#include <dynamic_reconfigure/Config.h>
#include <ros/ros.h>

#include "rigid_body_sim/Command.h"
#include "rigid_body_sim/RodState.h"
#include "rigid_body_sim/RollerState.h"
#include "rigid_body_sim/core/rod.h"
#include "rigid_body_sim/core/roller.h"

namespace rigid_body_sim {

// Qt 5 puts QtCharts in a namespace of its own (QT_CHARTS_USE_NAMESPACE); Qt 6 does not.
#if QT_VERSION < QT_VERSION_CHECK(6, 0, 0)
using QtCharts::QChart;
using QtCharts::QChartView;
using QtCharts::QLineSeries;
using QtCharts::QScatterSeries;
using QtCharts::QValueAxis;
using QtCharts::QXYSeries;
#endif

inline constexpr double kPlotWindow = 10.0;  // simulated seconds shown

class BodyPlots : public QWidget {
  Q_OBJECT
 public:
  explicit BodyPlots(QWidget* parent = nullptr);

  void setNode(const std::string& ns);                               // the node's namespace (its ~commands)
  void setBodies(const std::map<std::string, std::string>& bodies);  // name -> state message type
  void clear();
  // The body to show once it is there (an rviz config's "Plot Body"), and the one shown.
  void prefer(const std::string& body);
  const std::string& chosen() const { return body_; }
  // For the GUI test (RBS_PANEL_LAYOUT): one line per series, "plot.<series> 0 0 0 0 1 count t value"
  // (its last point; count 0: no t and value).
  std::string layoutLines() const;

 protected:
  void showEvent(QShowEvent* event) override;

 private:
  struct Track {
    std::string key;  // plot.<key> in the layout lines
    QXYSeries* series;
    std::deque<QPointF> points;
  };
  struct Chart {
    QChartView* view;
    QValueAxis* x;
    QValueAxis* y;
    std::vector<Track> tracks;
  };

  void select(const std::string& body);
  void build(const std::string& type);  // the charts of a body of that state type; none if empty
  Chart makeChart(const QString& title, const QString& y_title);
  void addTrack(Chart& chart, const std::string& key, const QString& name, QXYSeries* series);
  void onRod(const RodState& state);
  void onRoller(const RollerState& state);
  void onCommand(const Command& command);
  void append(Chart& chart, std::size_t track, double t, double value);
  void trim(double t);
  void redraw();

  std::string ns_, body_;
  std::map<std::string, std::string> bodies_;
  QComboBox* choice_;
  QWidget* charts_box_;
  std::vector<Chart> charts_;  // energy, then a roller's speeds and friction or a rod's ends
  void setParameters(const dynamic_reconfigure::Config& config);
  void appendEnergies(Chart& chart, double t, double total, double kinetic);

  // From the body's server; not known in a replay (no server): then no ends, -omega R or kinetic energy.
  bool parameters_known_ = false;
  RodParams rod_;
  RollerParams roller_;
  std::string last_mode_;
  bool dirty_ = false;
  QTimer redraw_timer_;
  ros::Subscriber state_, parameters_, commands_;
};

}  // namespace rigid_body_sim
