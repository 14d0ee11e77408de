// A field that takes the mouse wheel only while it has the keyboard focus (clicked or tabbed into). Over a
// field without focus the wheel event is left unaccepted, so Qt hands it on to the field's parents: the
// panel's scroll area scrolls and the value stays. A wheel that lands on a field does not give it focus
// (Qt::StrongFocus, where spin boxes and combo boxes default to Qt::WheelFocus).
#pragma once

#include <utility>

#include <QWheelEvent>

namespace rigid_body_sim {

template <class Base>
class FocusWheel : public Base {
 public:
  template <class... Args>
  explicit FocusWheel(Args&&... args) : Base(std::forward<Args>(args)...) {
    this->setFocusPolicy(Qt::StrongFocus);
  }

 protected:
  void wheelEvent(QWheelEvent* event) override {
    if (this->hasFocus()) {
      Base::wheelEvent(event);
    } else {
      event->ignore();
    }
  }
};

}  // namespace rigid_body_sim
