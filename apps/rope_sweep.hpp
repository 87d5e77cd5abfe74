// The driver of the rope apps `capstan` ([KS15] Sect. 6.3) and `helix` (Sect. 6.4): sweeps of a
// rope-over-cylinder model (data/capstan.json, data/helix.json, loaded by the generic loader of
// iga/model/analysis.hpp) over the friction coefficient mu, the wrap angle phi and the helix pitch
// H, each case run until the whole contact arc slides, T / T0 compared with (83)
//   T / T0 = exp(mu phi rho / sqrt(rho^2 + (H / 2 pi)^2)),  rho the centre line radius,
// which is the Euler-Eytelwein formula (82) exp(mu phi) for H = 0.
//
// The model's "app" section names, by JSON pointers into the model, where T0, mu, phi (degrees),
// H and rho are, and which control point's reaction is the pulled end's tension; "sweeps" and
// "quick" give the cases. Optional "pull" (a pointer to the pulled end's displacement) and
// "max_pull": a case that reaches t_end without full slip is run again with twice the pull,
// up to max_pull. T0 and rho must be > 0 (checked before any case runs, as is every case's
// model). The CSV has one row per case (case name, sweep, ..., pull, status), failed cases
// included with an empty T_ratio. Command line:
//   APP [MODEL.json] [--mu LIST] [--phi-deg LIST] [--pitch LIST] [--set /ptr=value]...
//       [--out DIR] [--quick] [--max-error X] [--profile] [--verbose]
// Exit status: 0 ok, 1 bad input, 2 a bad command line or a case that did not reach full slip,
// 3 --max-error exceeded.
#pragma once

#include <string>

namespace iga::app {

struct RopeApp {
  std::string name;           ///< "capstan" or "helix": program name, CSV and plot names
  std::string title;          ///< one-line description for --help
  std::string default_model;  ///< data/<name>.json
  bool pitch_column = false;  ///< the CSV has the column "pitch" (helix)
  std::string plot_script;    ///< scripts/plot_<name>.py
};

int run_rope_app(const RopeApp& app, int argc, char** argv);

}  // namespace iga::app
