// The shell as a Body: its description and sampled output fields.
#include <cmath>
#include <exception>
#include <string>

#include "iga/shell/shell_problem.hpp"

namespace iga {

std::string ShellProblem::describe() const {
  const NurbsSurface& S = shell_.reference();
  return "shell of " + std::to_string(shell_.num_patch_elements()) + " elements (degree " +
         std::to_string(S.degree_u()) + " x " + std::to_string(S.degree_v()) + ", " +
         std::to_string(num_control_points()) + " control points" +
         (shell_.material().law == ShellLaw::kNeoHookean
              ? ", neo-Hookean, " + std::to_string(shell_.material().thickness_points) +
                    " points through the thickness)"
              : ")");
}

SampledMesh ShellProblem::sample_model(const VectorXd& u, double t, int samples) const {
  const std::vector<Vector3d> x = current_points(u, t);
  const NurbsSurface& S = shell_.reference();
  SampledMesh m =
      element_grid(S.knots_u().breaks(), S.knots_v().breaks(), samples, shell_.options().block);
  std::vector<Vector3d> disp, normal, nloc, mloc;
  std::vector<double> von_mises, singular;
  for (const auto& [pu, pv] : m.params) {
    const Vector3d p = shell_.point(pu, pv, x);
    m.points.push_back(p);
    disp.push_back(p - S.point(pu, pv));
    Vector3d nrm = Vector3d::Zero(), nl = Vector3d::Zero(), ml = Vector3d::Zero();
    double vm = 0.0;
    bool ok = true;
    try {
      nrm = shell_.normal(pu, pv, x);
      const ShellStresses st = shell_.stresses(pu, pv, x);
      nl = st.membrane_force_local;
      ml = st.moment_local;
      vm = st.von_mises;
      ok = nrm.allFinite() && nrm.norm() > 0.5 && nl.allFinite() && ml.allFinite() &&
           std::isfinite(vm);
    } catch (const std::exception&) {
      ok = false;
    }
    normal.push_back(ok ? nrm : Vector3d::Zero());
    nloc.push_back(ok ? nl : Vector3d::Zero());
    mloc.push_back(ok ? ml : Vector3d::Zero());
    von_mises.push_back(ok ? vm : 0.0);
    singular.push_back(ok ? 0.0 : 1.0);
  }
  m.fields.scalars = {{"von_mises", von_mises}, {"singular", singular}};
  m.fields.vectors = {{"displacement", disp},
                      {"normal", normal},
                      {"membrane_force_N11_N22_N12", nloc},
                      {"moment_M11_M22_M12", mloc}};
  return m;
}

}  // namespace iga
