// helix: the rope laid as a helix of pitch H on a rigid cylinder, [KS15] Sect. 6.4 (Fig. 14):
// mu = 0.1, polar angle 180 deg, H = 0, 0.25, ..., 2; T / T0 at full slip against the 3-D Euler
// formula (83) T / T0 = exp(mu phi R / sqrt(R^2 + (H / 2 pi)^2)), R the centre line radius.
//
//   helix                                  the sweep of data/helix.json
//   helix --quick                          H = 0 and 2 (a CTest test)
//   helix --pitch 0,1,2 --mu 0.2           one sweep over the given lists
//   helix --set /geometry/rope/arc_elements=64 --out DIR --max-error 0.001
//
// Writes to --out (default out/helix): helix.csv (case,mu,phi,pitch,T_ratio,exact,rel_error),
// helix_steps.csv, model_used.json, helix.png (computed, 3-D formula (83), 2-D formula (82)),
// <case>_rod.vtu and <case>_contact.vtu for ParaView. The sweep driver: apps/rope_sweep.hpp.
#include <iostream>

#include "apps/common/resources.hpp"
#include "apps/rope_sweep.hpp"

int main(int argc, char** argv) {
  const iga::app::RopeApp app{
      "helix", "helix: rope as a helix on a rigid cylinder, T/T0 against (83) ([KS15] Sect. 6.4)",
      iga::app::resource("data/helix.json"), true, iga::app::resource("scripts/plot_helix.py")};
  try {
    return iga::app::run_rope_app(app, argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "helix: error: " << e.what() << "\n";
    return 1;
  }
}
