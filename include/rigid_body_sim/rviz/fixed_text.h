// Numbers as the panel and its charts show them: fixed decimals, never "-0.000" (formatFixed).
#pragma once

#include <QString>

#include "rigid_body_sim/core/parameters.h"

namespace rigid_body_sim {

inline QString fixed(double value, int decimals) {
  return QString::fromStdString(formatFixed(value, decimals));
}

}  // namespace rigid_body_sim
