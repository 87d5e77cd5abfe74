// Numbers in messages: `significant` significant digits, as printf's %g (and an ostream's
// default format with that precision): 0.1, 1e+20, 3.14159.
#pragma once

#include <cstdio>
#include <string>

namespace iga {

inline std::string num_text(double x, int significant) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", significant, x);
  return buf;
}

}  // namespace iga
