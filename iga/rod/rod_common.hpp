// What the torsion-free rod (kirchhoff_rod.cpp) and the rod with torsion (twisting_rod.cpp)
// share: the checks of their curve and section, and the generalized forces of a point force.
// Internal header of iga/rod/.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "iga/rod/kirchhoff_rod.hpp"

namespace iga::detail {

/// Throws RodError, prefixed with `who`: an interior knot of multiplicity > p - 1 (not C1),
/// EA <= 0 or not finite, EI1 or EI2 < 0 or not finite.
void check_rod_curve_and_section(const NurbsCurve& reference, const RodSection& section,
                                 const std::string& who);

/// f_i = R_i(xi) F of a dead force F at parameter xi (the non-zero ones).
std::vector<std::pair<int, Vector3d>> rod_point_load(const NurbsCurve& reference, double xi,
                                                     const Vector3d& F);

}  // namespace iga::detail
