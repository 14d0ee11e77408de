#include "rigid_body_sim/rviz/body_section.h"

#include <cmath>
#include <limits>
#include <regex>
#include <utility>

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFontMetrics>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLineEdit>
#include <QPushButton>
#include <QSlider>
#include <QSpinBox>

#include <dynamic_reconfigure/Reconfigure.h>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/parameters.h"
#include "rigid_body_sim/rviz/call_queue.h"
#include "rigid_body_sim/rviz/fixed_text.h"
#include "rigid_body_sim/rviz/focus_wheel.h"

namespace rigid_body_sim {

namespace {

constexpr int kSliderTicks = 1000;
constexpr int kNumberChars = 8;  // a number box is at least this many digits wide
const char* const kNoteStyle = "color: palette(mid);";

// A spin box for any double: shows the shortest text that reads back the same number, takes any number
// typed (1e-3 included), and reports a value only when the edit is done (Enter, focus out, arrows, the wheel
// once it has focus).
class NumberBox : public FocusWheel<QDoubleSpinBox> {
 public:
  explicit NumberBox(QWidget* parent) : FocusWheel<QDoubleSpinBox>(parent) {
    setDecimals(std::numeric_limits<double>::max_exponent10);  // no rounding of what is typed
    setKeyboardTracking(false);
    setAccelerated(true);
  }
  QString textFromValue(double value) const override { return numberText(value); }
  double valueFromText(const QString& text) const override { return text.trimmed().toDouble(); }
  QValidator::State validate(QString& text, int&) const override {
    bool ok = false;
    text.trimmed().toDouble(&ok);
    return ok ? QValidator::Acceptable : QValidator::Intermediate;
  }
};

// The constants of an enum from a description's edit_method (a Python dict literal): (name, value text).
std::vector<std::pair<std::string, std::string>> enumConstants(const std::string& edit_method) {
  std::vector<std::pair<std::string, std::string>> constants;
  static const std::regex constant(R"('name':\s*'([^']*)'.*?'value':\s*('[^']*'|[^,}]+))");
  for (std::sregex_iterator it(edit_method.begin(), edit_method.end(), constant), end; it != end; ++it) {
    std::string value = (*it)[2];
    if (value.size() >= 2 && value.front() == '\'') value = value.substr(1, value.size() - 2);
    constants.emplace_back((*it)[1], value);
  }
  return constants;
}

// A change accepted while the node is paused: no state comes to show it until the next Step or Run.
QString pausedNote(const std::string& key, const QString& value) {
  return QString("paused: %1 = %2 is set; the mode and energy above follow it at the next Step or Run")
      .arg(QString::fromStdString(key), value);
}

QString valueText(const dynamic_reconfigure::Config& config, const std::string& key) {
  if (const auto* p = parameterNamed(config.doubles, key)) return numberText(p->value);
  if (const auto* p = parameterNamed(config.ints, key)) return QString::number(p->value);
  if (const auto* p = parameterNamed(config.bools, key)) return p->value ? "true" : "false";
  if (const auto* p = parameterNamed(config.strs, key)) return QString::fromStdString(p->value);
  return "?";
}

}  // namespace

BodySection::BodySection(const std::string& name, const std::string& server, const std::string& state_type,
                         CallQueue& calls, std::function<void(double)> on_time,
                         std::function<void()> on_delete, const QString& read_only, QWidget* parent)
    : QGroupBox(QString::fromStdString(name), parent),
      name_(name),
      server_(server),
      state_type_(state_type),
      type_(rvizBodyTypeOf(state_type)),
      calls_(calls),
      on_time_(std::move(on_time)),
      read_only_(read_only) {
  setObjectName(QString::fromStdString(name));
  auto* layout = new QVBoxLayout(this);
  auto* top = new QHBoxLayout();
  motion_ = new QLabel("waiting for its state", this);
  motion_->setObjectName(QString::fromStdString(name + ".motion"));
  motion_->setWordWrap(true);
  top->addWidget(motion_, 1);
  auto* remove = new QPushButton("Delete", this);
  remove->setObjectName(QString::fromStdString(name + ".delete"));
  remove->setToolTip("~delete: the body leaves the world");
  connect(remove, &QPushButton::clicked, this, std::move(on_delete));
  holdIfReadOnly(remove);
  top->addWidget(remove);
  layout->addLayout(top);
  critical_ = new QLabel(this);
  critical_->setObjectName(QString::fromStdString(name + ".critical"));
  critical_->setWordWrap(true);
  critical_->hide();
  layout->addWidget(critical_);
  form_ = new QFormLayout();
  form_->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
  layout->addLayout(form_);
  message_ = new QLabel(this);
  message_->setObjectName(QString::fromStdString(name + ".message"));
  message_->setWordWrap(true);
  message_->hide();
  layout->addWidget(message_);

  ros::NodeHandle nh;
  subscribers_.push_back(nh.subscribe<dynamic_reconfigure::ConfigDescription>(
      server_ + "/parameter_descriptions", 1,
      [this](const dynamic_reconfigure::ConfigDescription::ConstPtr& d) { build(*d); }));
  subscribers_.push_back(nh.subscribe<dynamic_reconfigure::Config>(
      server_ + "/parameter_updates", 1, [this](const dynamic_reconfigure::Config::ConstPtr& c) {
        values_ = *c;
        showValues(values_);
      }));
  if (type_) {
    subscribers_.push_back(type_->describe(nh, server_ + "/state",
                                           [this](double t, const QString& motion) { onState(t, motion); }));
  }
}

void BodySection::showNodeLine(const QString& text) {
  node_line_shown_ = true;
  showMessage(text, true);
}

void BodySection::showMessage(const QString& text, bool refusal) {
  message_->setText(text);
  message_->setStyleSheet(refusal ? kRefusalStyle : kNoteStyle);
  message_->setVisible(!text.isEmpty());
}

// The widgets, once per description (the server sends it when it starts, latched).
void BodySection::build(const dynamic_reconfigure::ConfigDescription& description) {
  while (form_->rowCount() > 0) form_->removeRow(0);
  fields_.clear();
  order_.clear();
  for (const auto& group : description.groups) {
    for (const auto& param : group.parameters) {
      const auto* min = parameterNamed(description.min.doubles, param.name);
      const auto* max = parameterNamed(description.max.doubles, param.name);
      const double inf = std::numeric_limits<double>::infinity();
      addField(param, min ? min->value : -inf, max ? max->value : inf);
    }
  }
  showValues(values_);
}

// One key: an enum as a combo box, a number as a spin box with its unit (and a slider when its .cfg gives it
// a finite range), a bool as a check box, other text as a line. Its tool tip is the .cfg's description.
void BodySection::addField(const dynamic_reconfigure::ParamDescription& param, double min, double max) {
  const std::string& key = param.name;
  Field field{param.type, {}};
  QWidget* widget = nullptr;
  const auto constants = enumConstants(param.edit_method);
  if (!constants.empty()) {
    widget = enumField(key, param.type, constants, field);
  } else if (param.type == "double") {
    widget = numberField(param, min, max, field);
  } else if (param.type == "int") {
    widget = intField(key, min, max, field);
  } else if (param.type == "bool") {
    widget = boolField(key, field);
  } else {
    widget = textField(key, field);
  }
  if (widget->objectName().isEmpty()) widget->setObjectName(QString::fromStdString(name_ + "." + key));
  widget->setToolTip(QString::fromStdString(param.description));
  holdIfReadOnly(widget);
  for (auto* child : widget->findChildren<QWidget*>()) holdIfReadOnly(child);  // a number's box and slider
  auto* label = new QLabel(QString::fromStdString(key), this);
  label->setToolTip(QString::fromStdString(param.description));
  form_->addRow(label, widget);
  fields_[key] = std::move(field);
  order_.push_back(key);
}

QWidget* BodySection::enumField(const std::string& key, const std::string& type,
                                const std::vector<std::pair<std::string, std::string>>& constants,
                                Field& field) {
  auto* box = new FocusWheel<QComboBox>(this);
  for (const auto& [label, value] : constants)
    box->addItem(QString::fromStdString(label), QString::fromStdString(value));
  field.show = [box, key](const dynamic_reconfigure::Config& c) {
    const int index = box->findData(valueText(c, key));
    QSignalBlocker block(box);
    box->setCurrentIndex(index);
  };
  connect(box, QOverload<int>::of(&QComboBox::activated), this, [this, box, key, type](int index) {
    const std::string value = box->itemData(index).toString().toStdString();
    dynamic_reconfigure::Config asked;
    if (type == "str") {
      asked.strs.resize(1);
      asked.strs[0].name = key;
      asked.strs[0].value = value;
    } else if (type == "int") {
      asked.ints.resize(1);
      asked.ints[0].name = key;
      asked.ints[0].value = std::stoi(value);
    } else {
      asked.doubles.resize(1);
      asked.doubles[0].name = key;
      asked.doubles[0].value = std::stod(value);
    }
    request(asked, key, QString::fromStdString(value));
  });
  return box;
}

// A row named <body>.<key>.row: the spin box (named <body>.<key>), a slider for a finite range, the unit
// (<body>.<key>.unit) and, for an angle, the value in degrees (<body>.<key>.degrees).
QWidget* BodySection::numberField(const dynamic_reconfigure::ParamDescription& param, double min, double max,
                                  Field& field) {
  const std::string key = param.name;
  const QString object = QString::fromStdString(name_ + "." + key);
  auto* row = new QWidget(this);
  row->setObjectName(object + ".row");
  auto* row_layout = new QHBoxLayout(row);
  row_layout->setContentsMargins(0, 0, 0, 0);
  auto* box = new NumberBox(row);
  box->setObjectName(object);
  // Narrower than its range's text (-1.7976931348623157e+308) would make it: the row, its unit included,
  // fits the panel; a longer number scrolls inside the box.
  box->setMinimumWidth(box->fontMetrics().horizontalAdvance(QString(kNumberChars, '0')));
  const bool bounded = std::isfinite(min) && std::isfinite(max) && max > min;
  box->setRange(bounded ? min : std::numeric_limits<double>::lowest(),
                bounded ? max : std::numeric_limits<double>::max());
  row_layout->addWidget(box, 1);
  QSlider* slider = nullptr;
  if (bounded) {
    slider = new FocusWheel<QSlider>(Qt::Horizontal, row);
    slider->setRange(0, kSliderTicks);
    slider->setTracking(false);
    row_layout->addWidget(slider, 1);
    connect(slider, &QSlider::valueChanged, box, [box, min, max](int tick) {
      box->setValue(min + (max - min) * tick / kSliderTicks);  // the box sends it
    });
  }
  field.show = [box, slider, key, min, max](const dynamic_reconfigure::Config& c) {
    const auto* p = parameterNamed(c.doubles, key);
    if (!p) return;
    QSignalBlocker block(box);
    box->setValue(p->value);
    box->setSingleStep(p->value != 0 ? std::pow(10.0, std::floor(std::log10(std::abs(p->value)))) / 10 : 0.1);
    if (slider) {
      QSignalBlocker block_slider(slider);
      slider->setValue(static_cast<int>(std::lround((p->value - min) / (max - min) * kSliderTicks)));
    }
  };
  addUnit(row, object, type_ ? type_->unit(key) : QString(), key, field);
  connect(box, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, [this, key](double value) {
    dynamic_reconfigure::Config asked;
    asked.doubles.resize(1);
    asked.doubles[0].name = key;
    asked.doubles[0].value = value;
    request(asked, key, numberText(value));
  });
  return row;
}

// The unit after a number's box, and for an angle (rad) the value in degrees, kept with the value shown.
void BodySection::addUnit(QWidget* row, const QString& object, const QString& unit, const std::string& key,
                          Field& field) {
  if (unit.isEmpty()) return;  // a pure number
  auto* unit_label = new QLabel(unit, row);
  unit_label->setObjectName(object + ".unit");
  row->layout()->addWidget(unit_label);
  if (unit != "rad") return;
  auto* degrees = new QLabel(row);
  degrees->setObjectName(object + ".degrees");
  degrees->setToolTip("the same angle in degrees");
  row->layout()->addWidget(degrees);
  field.show = [show = std::move(field.show), degrees, key](const dynamic_reconfigure::Config& c) {
    show(c);
    if (const auto* p = parameterNamed(c.doubles, key)) degrees->setText(degreesText(p->value, 2));
  };
}

QWidget* BodySection::intField(const std::string& key, double min, double max, Field& field) {
  auto* box = new FocusWheel<QSpinBox>(this);
  box->setKeyboardTracking(false);
  box->setRange(std::isfinite(min) ? static_cast<int>(min) : std::numeric_limits<int>::min(),
                std::isfinite(max) ? static_cast<int>(max) : std::numeric_limits<int>::max());
  field.show = [box, key](const dynamic_reconfigure::Config& c) {
    if (const auto* p = parameterNamed(c.ints, key)) {
      QSignalBlocker block(box);
      box->setValue(p->value);
    }
  };
  connect(box, QOverload<int>::of(&QSpinBox::valueChanged), this, [this, key](int value) {
    dynamic_reconfigure::Config asked;
    asked.ints.resize(1);
    asked.ints[0].name = key;
    asked.ints[0].value = value;
    request(asked, key, QString::number(value));
  });
  return box;
}

QWidget* BodySection::boolField(const std::string& key, Field& field) {
  auto* box = new QCheckBox(this);
  field.show = [box, key](const dynamic_reconfigure::Config& c) {
    if (const auto* p = parameterNamed(c.bools, key)) {
      QSignalBlocker block(box);
      box->setChecked(p->value);
    }
  };
  connect(box, &QCheckBox::toggled, this, [this, key](bool value) {
    dynamic_reconfigure::Config asked;
    asked.bools.resize(1);
    asked.bools[0].name = key;
    asked.bools[0].value = value;
    request(asked, key, value ? "true" : "false");
  });
  return box;
}

QWidget* BodySection::textField(const std::string& key, Field& field) {
  auto* line = new QLineEdit(this);
  field.show = [line, key](const dynamic_reconfigure::Config& c) {
    if (const auto* p = parameterNamed(c.strs, key)) line->setText(QString::fromStdString(p->value));
  };
  connect(line, &QLineEdit::editingFinished, this, [this, line, key] {
    dynamic_reconfigure::Config asked;
    asked.strs.resize(1);
    asked.strs[0].name = key;
    asked.strs[0].value = line->text().toStdString();
    request(asked, key, line->text());
  });
  return line;
}

void BodySection::holdIfReadOnly(QWidget* widget) {
  if (read_only_.isEmpty()) return;
  widget->setEnabled(false);
  widget->setToolTip(widget->toolTip().isEmpty() ? read_only_ : read_only_ + "\n" + widget->toolTip());
}

void BodySection::showValues(const dynamic_reconfigure::Config& values) {
  for (auto& [key, field] : fields_) field.show(values);
  if (type_) type_->setParameters(values);
  showCritical();
}

void BodySection::setPaused(bool paused) { paused_ = paused; }

// Its type's critical angle from the values shown, and whether its slope is above it.
void BodySection::showCritical() {
  const auto verdict = type_ ? type_->critical() : std::nullopt;
  critical_->setVisible(verdict.has_value());
  if (!verdict) return;
  critical_->setText(verdict->text);
  critical_->setToolTip(verdict->why);
}

// Sends one key to the server. Its answer is what runs: shown at once, so that a refused value snaps back;
// a refusal is named here unless the node's own line about it came first (SimPanel routes it to showNodeLine;
// the node logs it before it answers, and /rosout may deliver it before the answer or after).
void BodySection::request(dynamic_reconfigure::Config asked, const std::string& key,
                          const QString& asked_text) {
  const std::string service = server_ + "/set_parameters";
  node_line_shown_ = false;
  struct Answer {
    bool called = false;
    dynamic_reconfigure::Config shown;
  };
  calls_.post<Answer>(
      this,
      [service, asked] {
        dynamic_reconfigure::Reconfigure srv;
        srv.request.config = asked;
        Answer answer;
        answer.called = CallQueue::services().call(service, srv);
        answer.shown = srv.response.config;
        return answer;
      },
      [this, key, asked_text](const Answer& answer) {
        if (!answer.called) {
          showMessage(QString::fromStdString("no answer from " + server_ + "/set_parameters"), true);
          showValues(values_);
          return;
        }
        values_ = answer.shown;
        showValues(values_);
        const QString now = valueText(values_, key);
        if (now == asked_text) {
          pending_note_ = paused_;
          showMessage(paused_ ? pausedNote(key, now) : QString(), false);
        } else if (!node_line_shown_) {
          showMessage(QString("refused %1 = %2: snapped back to %3")
                          .arg(QString::fromStdString(key), asked_text, now),
                      true);
        }
      });
}

// A state after a change made while paused: the mode and energy now show it.
void BodySection::clearPendingNote() {
  if (!pending_note_) return;
  pending_note_ = false;
  showMessage("", false);
}

// Its mode (as its type tells it) and energy, from its newest state.
void BodySection::onState(double t, const QString& motion) {
  motion_->setText(motion);
  clearPendingNote();
  on_time_(t);
}

}  // namespace rigid_body_sim
