// Numbers for the output files (CSV tables, JSON summaries): no output file may hold a
// non-finite number, so these helpers print nan and inf as an empty CSV cell or JSON null.
#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "geometry/json_reader.hpp"

namespace iga {

/// The value with `digits` significant digits, or "" (an empty cell) if it is not finite.
inline std::string csv_number(double v, int digits = 12) {
  if (!std::isfinite(v)) return {};
  std::ostringstream s;
  s << std::setprecision(digits) << v;
  return s.str();
}

/// The value as a JSON number, or null if it is not finite.
inline Json json_number(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}

}  // namespace iga
