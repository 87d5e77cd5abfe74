// The cross-product matrix of a vector, used by the rod and shell tangents.
#pragma once

#include "geometry/derivatives.hpp"

namespace iga {

/// [v]x with [v]x w = v x w.
inline Matrix3d skew(const Vector3d& v) {
  Matrix3d S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

}  // namespace iga
