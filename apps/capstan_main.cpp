// capstan: the Euler-Eytelwein belt friction example of [KS15] Sect. 6.3 (Figs. 11-12): a
// Kirchhoff rod (rope) wrapped over a rigid cylinder (exact NURBS patch, or the analytic cylinder
// with --set /contact/0/rigid=\"cylinder_analytic\"), one end under a dead load T0, the other
// pulled until the whole contact arc slides; T / T0 at that point against exp(mu phi) (82).
//
//   capstan                                    the sweeps of data/capstan.json
//   capstan --quick                            a reduced sweep (a CTest test)
//   capstan --mu 0,0.5,1 --phi-deg 180         one sweep over the given lists
//   capstan --set /materials/rope/EI=1e-3 --set /geometry/rope/arc_elements=20
//   capstan MODEL.json --out DIR --max-error 0.005
//   capstan --profile                          time shares: assembly, contact, linear solves
//
// Writes to --out (default out/capstan): capstan.csv (case,sweep,mu,phi,T_ratio,exact,rel_error,
// pull,status: one row per case, a case without full slip with its status and empty T_ratio),
// capstan_steps.csv (every converged step), model_used.json, capstan.png (plot), and for each
// case <case>_rod.vtu (centre line with axial force and curvature) and <case>_contact.vtu
// (contact points with N, T, B, slip) for ParaView. The sweep driver: apps/rope_sweep.hpp.
#include <iostream>

#include "apps/common/resources.hpp"
#include "apps/rope_sweep.hpp"

int main(int argc, char** argv) {
  const iga::app::RopeApp app{
      "capstan", "capstan: rope on a rigid cylinder, T/T0 against exp(mu phi) ([KS15] Sect. 6.3)",
      iga::app::resource("data/capstan.json"), false,
      iga::app::resource("scripts/plot_capstan.py")};
  try {
    return iga::app::run_rope_app(app, argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "capstan: error: " << e.what() << "\n";
    return 1;
  }
}
