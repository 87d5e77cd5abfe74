// The rod as a Body: its description, displacements and sampled output fields.
#include <cmath>
#include <exception>
#include <string>

#include "iga/rod/kirchhoff_rod.hpp"

namespace iga {

std::string RodProblem::describe() const {
  return "rod of " + std::to_string(rod_.num_elements()) + " elements (degree " +
         std::to_string(rod_.degree()) + ", " + std::to_string(num_control_points()) +
         " control points)";
}

Vector3d RodProblem::displacement(double pu, double pv, const VectorXd& u, double t) const {
  (void)pv;
  const std::vector<Vector3d> x = current_points(u, t);
  return rod_.point(pu, x) - rod_.reference().point(pu);
}

SampledMesh RodProblem::sample_model(const VectorXd& u, double t, int samples) const {
  const std::vector<Vector3d> x = current_points(u, t);
  SampledMesh m;
  m.shape = SampledMesh::Shape::kPolyline;
  std::vector<double> force, curvature, singular;
  for (int e = 0; e < rod_.num_elements(); ++e) {
    const Interval I = rod_.element_range(e);
    for (int k = (e == 0 ? 0 : 1); k <= samples; ++k) {
      const double xi = I.lo + (I.hi - I.lo) * k / samples;
      m.points.push_back(rod_.point(xi, x));
      m.params.push_back({xi, 0.0});
      m.elements.push_back(e);
      double n = 0.0, kappa = 0.0;
      bool ok = true;
      try {
        const RodStrains st = rod_.strains(xi, x);
        n = st.axial_force;
        kappa = st.curvature;
        ok = std::isfinite(n) && std::isfinite(kappa);
      } catch (const std::exception&) {
        ok = false;
      }
      force.push_back(ok ? n : 0.0);
      curvature.push_back(ok ? kappa : 0.0);
      singular.push_back(ok ? 0.0 : 1.0);
    }
  }
  m.fields.scalars = {{"axial_force", force}, {"curvature", curvature}, {"singular", singular}};
  return m;
}

}  // namespace iga
