// Numbers as the panel and its charts show them: fixed decimals, never "-0.000" (formatFixed); a value's
// shortest form that reads back the same number; an angle in degrees.
#pragma once

#include <QString>

#include "rigid_body_sim/core/constants.h"
#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

inline QString fixed(double value, int decimals) {
  return QString::fromStdString(formatFixed(value, decimals));
}

inline QString numberText(double value) { return QString::fromStdString(formatNumber(value)); }

inline QString degreesText(double radians, int decimals) {
  return fixed(radians * 180.0 / kPi, decimals) + QChar(0x00B0);
}

}  // namespace rigid_body_sim
