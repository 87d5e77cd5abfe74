// A program of a downstream project: loads a model through the installed library, runs it and
// prints the tip displacement of the rolled-up rod (an end moment M on a clamped rod of length
// L bends it into a circle of radius EI / M; rollup.json closes the circle: the tip returns to
// the clamp). Usage: downstream <model.json>
#include <iostream>

#include "iga/model/analysis.hpp"
#include "iga/rod/kirchhoff_rod.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: downstream <model.json>\n";
    return 2;
  }
  iga::Analysis a = iga::Analysis::load(argv[1]);
  std::cout << a.describe() << "\n";
  const iga::AnalysisResult r = a.run();
  if (!r.solver.converged()) {
    std::cerr << "not converged: " << r.solver.message << "\n";
    return 1;
  }
  const iga::RodProblem& rod = a.body_as<iga::RodProblem>();
  const std::vector<iga::Vector3d> x = rod.current_points(r.u, r.solver.t);
  const iga::Interval D = rod.rod().reference().domain();
  const iga::Vector3d tip = rod.rod().point(D.hi, x), root = rod.rod().point(D.lo, x);
  std::cout << "tip to clamp distance " << (tip - root).norm() << "\n";
  return 0;
}
