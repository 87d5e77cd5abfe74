// ParaView output of an analysis: the rod's centre line and the shell's surface with their
// fields, the contact points, and the contact fields on the rigid tool's pieces.
#include "iga/model/analysis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <tuple>

#include "geometry/constructions.hpp"
#include "iga/model/model.hpp"
#include "iga/model/sections.hpp"
#include "iga/output/output_format.hpp"
#include "iga/output/vtk_writer.hpp"

namespace iga {

namespace fs = std::filesystem;
using model_detail::fmt;

namespace {

/// The rod's centre line sampled per element, with axial force and curvature. A sample where
/// the strains cannot be evaluated (a zero tangent, e.g. at an end whose first two control
/// points coincide) gets zero force and curvature and the flag singular = 1.
/// Contact fields on the rod, per element: the line pressure -N (force per reference length),
/// the pulling and dragging tractions T (69), B (70), each the mean of the element's contact
/// points weighted as in the contact integral (what the penalty resolves: point by point the
/// values oscillate about it within an element), and the state 0 apart, 1 stick, 2 slip (2 if
/// any point of the element slides, 1 if one sticks).
struct RodContactFields {
  double pressure = 0.0, T = 0.0, B = 0.0, state = 0.0;
};

RodContactFields rod_contact_fields(const CurveContact& contact, const Interval& I) {
  RodContactFields f;
  double w = 0.0;
  for (const CurveContactPoint& cp : contact.points()) {
    if (cp.eta < I.lo || cp.eta > I.hi) continue;
    w += cp.weight;
    if (!cp.law.active) continue;
    f.pressure += cp.weight * -cp.N;
    f.T += cp.weight * cp.T;
    f.B += cp.weight * cp.B;
    f.state = std::max(f.state, cp.law.slip ? 2.0 : 1.0);
  }
  if (w > 0.0) {
    f.pressure /= w;
    f.T /= w;
    f.B /= w;
  }
  return f;
}

void write_rod_vtk(const std::string& path, const KirchhoffRod& rod, const std::vector<Vector3d>& x,
                   int samples, const std::string& title, const CurveContact* contact) {
  std::vector<Vector3d> line;
  std::vector<double> force, curvature, singular;
  std::vector<double> pressure, traction_T, traction_B, state;
  for (int e = 0; e < rod.num_elements(); ++e) {
    const Interval I = rod.element_range(e);
    const RodContactFields cf = contact ? rod_contact_fields(*contact, I) : RodContactFields{};
    for (int k = (e == 0 ? 0 : 1); k <= samples; ++k) {
      const double xi = I.lo + (I.hi - I.lo) * k / samples;
      line.push_back(rod.point(xi, x));
      double n = 0.0, kappa = 0.0;
      bool ok = true;
      try {
        const RodStrains st = rod.strains(xi, x);
        n = st.axial_force;
        kappa = st.curvature;
        ok = std::isfinite(n) && std::isfinite(kappa);
      } catch (const std::exception&) {
        ok = false;
      }
      force.push_back(ok ? n : 0.0);
      curvature.push_back(ok ? kappa : 0.0);
      singular.push_back(ok ? 0.0 : 1.0);
      pressure.push_back(cf.pressure);
      traction_T.push_back(cf.T);
      traction_B.push_back(cf.B);
      state.push_back(cf.state);
    }
  }
  VtkPointData d;
  d.scalars = {{"axial_force", force}, {"curvature", curvature}, {"singular", singular}};
  if (contact) {
    d.scalars.push_back({"contact_pressure", pressure});
    d.scalars.push_back({"contact_traction_T", traction_T});
    d.scalars.push_back({"contact_traction_B", traction_B});
    d.scalars.push_back({"contact_state", state});
  }
  write_vtk_polydata(path, line, true, d, title);
}

/// Parameters of a grid over the element spans: `samples` intervals per span.
std::vector<double> span_samples(const std::vector<double>& breaks, int samples) {
  std::vector<double> s;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k)
    for (int i = (k == 0 ? 0 : 1); i <= samples; ++i)
      s.push_back(breaks[k] + (breaks[k + 1] - breaks[k]) * i / samples);
  return s;
}

/// Contact fields over the shell (issue 12 item 6): the pressure -N, the tangential traction on
/// the shell T_vector, the gap xi3 and the state (0 apart, 1 stick, 2 slip) of the element's
/// n x n contact (Gauss) points, evaluated anywhere in the element. N of the contact law (34) and
/// T_vector are forces per reference area: the contact integral weights them with cp.weight, the
/// Gauss weight times the reference area element. The interpolation:
///  - where all points of the element are in contact and in one state (pressure and traction
///    are smooth there): tensor-product Lagrange interpolation through the points' parameters,
///    f(u, v) = sum_ij f_ij l_i(u) l_j(v), l_i(u) = prod_{k != i} (u - u_k) / (u_i - u_k). It
///    reproduces a field of degree n - 1 in each parameter, e.g. the penalty pressure on a flat
///    tool, eps_N times the gap of a polynomial shell, up to the rational part of the normal;
///  - where the edge of the contact zone or of a stick zone runs through the element (a kink
///    between the points: a polynomial through them would overshoot): piecewise bilinear between
///    the neighbouring points, held constant from the outer points to the element's edges.
/// The pressure is clamped at >= 0; the state is the nearest point's. The gap is interpolated
/// among the points that have a foot within the search distance (the others have no gap); where
/// none has, it is unknown: 0 and gap_known = false.
class ShellContactField {
 public:
  ShellContactField(const SurfaceContact& contact, const NurbsSurface& S)
      : contact_(contact), bu_(S.knots_u().breaks()), bv_(S.knots_v().breaks()) {
    const std::size_t nu = bu_.size() - 1, nv = bv_.size() - 1;
    elements_.resize(nu * nv);
    for (const SurfaceContactPoint& cp : contact.points()) {
      const auto e = static_cast<std::size_t>(cp.element);
      if (e < elements_.size()) elements_[e].points.push_back(&cp);
    }
    for (Element& el : elements_) {
      for (const SurfaceContactPoint* p : el.points) {
        el.u.push_back(p->uv[0]);
        el.v.push_back(p->uv[1]);
      }
      for (std::vector<double>* a : {&el.u, &el.v}) {
        std::sort(a->begin(), a->end());
        a->erase(std::unique(a->begin(), a->end()), a->end());
      }
      el.grid.assign(el.u.size() * el.v.size(), nullptr);
      for (const SurfaceContactPoint* p : el.points) {
        const auto i = std::lower_bound(el.u.begin(), el.u.end(), p->uv[0]) - el.u.begin();
        const auto j = std::lower_bound(el.v.begin(), el.v.end(), p->uv[1]) - el.v.begin();
        el.grid[static_cast<std::size_t>(j) * el.u.size() + static_cast<std::size_t>(i)] = p;
      }
      // Smooth: a complete tensor grid of points, all in contact, all in the same state.
      el.smooth = !el.points.empty() && el.points.size() == el.grid.size() &&
                  std::none_of(el.grid.begin(), el.grid.end(),
                               [](const SurfaceContactPoint* p) { return p == nullptr; });
      for (const SurfaceContactPoint* p : el.points)
        el.smooth = el.smooth && p->active && state(*p) == state(*el.points.front());
    }
  }

  struct Value {
    double pressure = 0.0, gap = 0.0, state = 0.0;
    Vector3d traction = Vector3d::Zero();
    bool gap_known = false;
  };

  Value at(double u, double v) const {
    const std::size_t iu = span_of(bu_, u), iv = span_of(bv_, v);
    const Element& el = elements_[iv * (bu_.size() - 1) + iu];
    if (el.u.empty() || el.v.empty()) return {};
    Value out = el.smooth ? lagrange(el, u, v) : bilinear(el, u, v);
    out.pressure = std::max(0.0, out.pressure);
    return out;
  }

 private:
  struct Element {
    std::vector<const SurfaceContactPoint*> points;
    std::vector<double> u, v;                      ///< sorted abscissae of the points
    std::vector<const SurfaceContactPoint*> grid;  ///< [j * u.size() + i]
    bool smooth = false;  ///< all points in contact, in one state: Lagrange interpolation
    const SurfaceContactPoint* point(std::size_t i, std::size_t j) const {
      return grid[j * u.size() + i];
    }
  };

  double state(const SurfaceContactPoint& p) const {
    return !p.active ? 0.0 : contact_.sticks(p) ? 1.0 : 2.0;
  }

  /// The Lagrange basis through the abscissae a at x: l_i(x) = prod_{k != i} (x - a_k) / (a_i -
  /// a_k).
  static std::vector<double> lagrange_basis(const std::vector<double>& a, double x) {
    std::vector<double> l(a.size(), 1.0);
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t k = 0; k < a.size(); ++k)
        if (k != i) l[i] *= (x - a[k]) / (a[i] - a[k]);
    return l;
  }

  /// A smooth element: f(u, v) = sum_ij f_ij l_i(u) l_j(v) (every point active, with a foot).
  Value lagrange(const Element& el, double u, double v) const {
    const std::vector<double> lu = lagrange_basis(el.u, u), lv = lagrange_basis(el.v, v);
    Value out;
    for (std::size_t j = 0; j < el.v.size(); ++j)
      for (std::size_t i = 0; i < el.u.size(); ++i) {
        const SurfaceContactPoint& p = *el.point(i, j);
        const double w = lu[i] * lv[j];
        out.pressure += w * -p.N;
        out.traction += w * p.T_vector;
        out.gap += w * p.gap;
      }
    out.state = state(*el.points.front());
    out.gap_known = true;
    return out;
  }

  /// An element with a contact or stick edge: bilinear between the 4 neighbouring points, the
  /// outer points' values held to the element's edges.
  Value bilinear(const Element& el, double u, double v) const {
    const auto [i0, i1, s] = bracket(el.u, u);
    const auto [j0, j1, r] = bracket(el.v, v);
    const double w[4] = {(1 - s) * (1 - r), s * (1 - r), (1 - s) * r, s * r};
    const SurfaceContactPoint* corner[4] = {el.point(i0, j0), el.point(i1, j0), el.point(i0, j1),
                                            el.point(i1, j1)};
    Value out;
    int nearest = 0;
    double wgap = 0.0;  // the weight of the corners with a gap
    for (int k = 0; k < 4; ++k) {
      if (w[k] > w[nearest]) nearest = k;
      const SurfaceContactPoint* p = corner[k];
      if (p == nullptr) return Value{};  // an incomplete element (not expected): no field
      if (found(p->foot.status)) {
        wgap += w[k];
        out.gap += w[k] * p->gap;
      }
      if (!p->active) continue;
      out.pressure += w[k] * -p->N;
      out.traction += w[k] * p->T_vector;
    }
    out.gap_known = wgap > 0.0;
    out.gap = out.gap_known ? out.gap / wgap : 0.0;
    out.state = state(*corner[nearest]);
    return out;
  }

  static std::size_t span_of(const std::vector<double>& b, double x) {
    const auto k = std::upper_bound(b.begin(), b.end(), x) - b.begin() - 1;
    return static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(k, 0, std::ssize(b) - 2));
  }
  /// The neighbours of x among the sorted abscissae a and the weight of the upper one.
  static std::tuple<std::size_t, std::size_t, double> bracket(const std::vector<double>& a,
                                                              double x) {
    if (x <= a.front()) return {0, 0, 0.0};
    if (x >= a.back()) return {a.size() - 1, a.size() - 1, 0.0};
    const auto k = static_cast<std::size_t>(std::upper_bound(a.begin(), a.end(), x) - a.begin());
    return {k - 1, k, (x - a[k - 1]) / (a[k] - a[k - 1])};
  }
  const SurfaceContact& contact_;
  std::vector<double> bu_, bv_;
  std::vector<Element> elements_;
};

/// The shell's surface sampled per element, with displacement, normal and stress resultants. A
/// sample where the normal or the stresses cannot be evaluated (a degenerate point: a collapsed
/// edge, a pole) gets a zero normal and zero stresses and the flag singular = 1. With contact:
/// contact_pressure, contact_traction, contact_gap, contact_state (ShellContactField) and the
/// flag contact_undefined = 1 where the gap is unknown (no point near has a foot) or a value is
/// not finite; such values are written as 0.
void write_shell_vtk(const std::string& path, const KirchhoffLoveShell& shell,
                     const std::vector<Vector3d>& x, int samples, const std::string& title,
                     const SurfaceContact* contact) {
  const NurbsSurface& S = shell.reference();
  const std::vector<double> us = span_samples(S.knots_u().breaks(), samples);
  const std::vector<double> vs = span_samples(S.knots_v().breaks(), samples);
  std::vector<Vector3d> pts, disp, normal, nloc, mloc;
  std::vector<double> von_mises, singular;
  std::optional<ShellContactField> field;
  if (contact) field.emplace(*contact, S);
  std::vector<double> c_pressure, c_gap, c_state, c_undefined;
  std::vector<Vector3d> c_traction;
  for (double v : vs)
    for (double u : us) {
      if (field) {
        const ShellContactField::Value cv = field->at(u, v);
        const bool finite =
            std::isfinite(cv.pressure) && std::isfinite(cv.gap) && cv.traction.allFinite();
        c_pressure.push_back(finite ? cv.pressure : 0.0);
        c_gap.push_back(finite ? cv.gap : 0.0);
        c_traction.push_back(finite ? cv.traction : Vector3d::Zero());
        c_state.push_back(cv.state);
        c_undefined.push_back(finite && cv.gap_known ? 0.0 : 1.0);
      }
      const Vector3d p = shell.point(u, v, x);
      pts.push_back(p);
      disp.push_back(p - S.point(u, v));
      Vector3d nrm = Vector3d::Zero(), nl = Vector3d::Zero(), ml = Vector3d::Zero();
      double vm = 0.0;
      bool ok = true;
      try {
        nrm = shell.normal(u, v, x);
        const ShellStresses st = shell.stresses(u, v, x);
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
  VtkPointData d;
  d.scalars = {{"von_mises", von_mises}, {"singular", singular}};
  d.vectors = {{"displacement", disp},
               {"normal", normal},
               {"membrane_force_N11_N22_N12", nloc},
               {"moment_M11_M22_M12", mloc}};
  if (field) {
    d.scalars.push_back({"contact_pressure", c_pressure});
    d.scalars.push_back({"contact_gap", c_gap});
    d.scalars.push_back({"contact_state", c_state});
    d.scalars.push_back({"contact_undefined", c_undefined});
    d.vectors.push_back({"contact_traction", c_traction});
  }
  write_vtk_grid(path, pts, static_cast<int>(us.size()), static_cast<int>(vs.size()), d, title);
}

/// A contact point seen from the rigid tool: its foot, the pressure and traction the body
/// exerts there, its state (1 stick, 2 slip) and its footprint radius.
struct ToolFoot {
  Vector3d x;
  double pressure, state, radius;
  Vector3d traction;
};

/// The contact on a grid of a rigid piece (issue 12 item 6): every grid node takes the weighted
/// mean of the feet within their footprint radius h of it, weight (1 - d/h)^2, and 0 where no
/// foot reaches (the state: the foot of the largest weight). h is 1.5 times the point's share of
/// the body (sqrt of its area for shells, its length for rods), at least 0.75 times the grid's
/// spacing so that every foot reaches a node. A transfer for viewing, not a conservative one:
/// the mean keeps the pressure level of a uniform contact, and the field falls to 0 within h of
/// the contact zone's edge (rods: a band of width about 2h along the rope). The feet are sorted
/// into cubic cells of the largest h, so a node looks at the 27 cells around its own only.
VtkPointData tool_fields(const std::vector<Vector3d>& grid, double spacing,
                         const std::vector<ToolFoot>& feet) {
  std::vector<double> pressure(grid.size(), 0.0), state(grid.size(), 0.0);
  std::vector<Vector3d> traction(grid.size(), Vector3d::Zero());
  // The cells: key floor(x / c) per coordinate, c the largest footprint radius.
  double c = 0.75 * spacing;
  for (const ToolFoot& f : feet)
    if (std::isfinite(f.radius)) c = std::max(c, f.radius);
  using Cell = std::array<long long, 3>;
  const auto cell_of = [c](const Vector3d& x) {
    Cell k;
    for (int i = 0; i < 3; ++i)  // clamped: a far or huge coordinate stays a valid key
      k[static_cast<std::size_t>(i)] =
          static_cast<long long>(std::clamp(std::floor(x[i] / c), -1e15, 1e15));
    return k;
  };
  std::vector<std::pair<Cell, std::size_t>> sorted;  // (cell, foot), by cell
  if (c > 0.0 && std::isfinite(c))
    for (std::size_t i = 0; i < feet.size(); ++i)
      if (feet[i].x.allFinite()) sorted.push_back({cell_of(feet[i].x), i});
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t g = 0; g < grid.size(); ++g) {
    if (sorted.empty() || !grid[g].allFinite()) continue;
    double wsum = 0.0, wmax = 0.0;
    const Cell home = cell_of(grid[g]);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const Cell key{home[0] + dx, home[1] + dy, home[2] + dz};
          auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair{key, std::size_t{0}});
          for (; it != sorted.end() && it->first == key; ++it) {
            const ToolFoot& f = feet[it->second];
            const double h = std::max(f.radius, 0.75 * spacing);
            const double d = (grid[g] - f.x).norm();
            if (!(d < h)) continue;
            const double w = (1.0 - d / h) * (1.0 - d / h);
            wsum += w;
            pressure[g] += w * f.pressure;
            traction[g] += w * f.traction;
            if (w > wmax) {
              wmax = w;
              state[g] = f.state;
            }
          }
        }
    if (wsum > 0.0) {  // a non-finite value (a foot's): 0 and non_finite = 1 (write_vtk_grid)
      pressure[g] /= wsum;
      traction[g] /= wsum;
    }
  }
  VtkPointData d;
  d.scalars = {{"contact_pressure", pressure}, {"contact_state", state}};
  d.vectors = {{"contact_traction", traction}};
  return d;
}

/// The 41 x 41 grid of a bounded rigid piece (empty for an unbounded one) and its spacing.
constexpr int kToolGrid = 41;
std::pair<std::vector<Vector3d>, double> tool_grid(const Surface& S) {
  const Domain2 D = S.domain();
  if (!std::isfinite(D.u.lo) || !std::isfinite(D.u.hi) || !std::isfinite(D.v.lo) ||
      !std::isfinite(D.v.hi))
    return {};
  constexpr int n = kToolGrid;
  std::vector<Vector3d> pts;
  pts.reserve(n * n);
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k)
      pts.push_back(S.derivs(D.u.lo + (D.u.hi - D.u.lo) * k / (n - 1),
                             D.v.lo + (D.v.hi - D.v.lo) * j / (n - 1), 0)
                        .S);
  double spacing = 0.0;  // the largest distance between neighbouring nodes
  for (int j = 0; j < n; ++j)
    for (int k = 0; k < n; ++k) {
      const Vector3d& p = pts[static_cast<std::size_t>(j * n + k)];
      if (k + 1 < n)
        spacing = std::max(spacing, (pts[static_cast<std::size_t>(j * n + k + 1)] - p).norm());
      if (j + 1 < n)
        spacing = std::max(spacing, (pts[static_cast<std::size_t>((j + 1) * n + k)] - p).norm());
    }
  return {std::move(pts), spacing};
}

}  // namespace

std::vector<std::string> Analysis::write_vtk(const std::string& dir, const std::string& stem,
                                             const VectorXd& u, double t) {
  const std::vector<Vector3d> x = problem_->current_points(u, t);
  const int n = output_.samples_per_element > 0 ? output_.samples_per_element : (rod_ ? 16 : 4);
  std::vector<std::string> files;
  if (rod_) {
    files.push_back(stem + "_rod.vtk");
    write_rod_vtk((fs::path(dir) / files[0]).string(), rod_->rod(), x, n,
                  name_ + " rod, t = " + fmt(t), rod_contact_ ? &rod_contact_->contact() : nullptr);
  } else {
    files.push_back(stem + "_shell.vtk");
    write_shell_vtk((fs::path(dir) / files[0]).string(), shell_->shell(), x, n,
                    name_ + " shell, t = " + fmt(t),
                    shell_contact_ ? &shell_contact_->contact() : nullptr);
  }
  VtkPointData cd, td;
  std::vector<Vector3d> pts, feet, foot_traction;
  std::vector<double> foot_pressure, foot_state, foot_radius;
  if (rod_contact_) {
    std::vector<Vector3d> normal;
    std::vector<double> N, T, B, slip;
    for (const CurveContactPoint& cp : rod_contact_->contact().points()) {
      if (!cp.law.active) continue;
      feet.push_back(cp.law.foot);
      foot_pressure.push_back(-cp.N);
      foot_traction.push_back(-cp.law.T_vector);  // on the tool: opposite to the rope's
      foot_state.push_back(cp.law.slip ? 2.0 : 1.0);
      foot_radius.push_back(1.5 * cp.weight);  // its length share of the rope
      pts.push_back(cp.x);
      normal.push_back(cp.law.normal);
      N.push_back(cp.N);
      T.push_back(cp.T);
      B.push_back(cp.B);
      slip.push_back(cp.law.slip ? 1.0 : 0.0);
    }
    cd.scalars = {{"N", N}, {"T", T}, {"B", B}, {"slip", slip}};
    cd.vectors = {{"normal", normal}};
  } else if (shell_contact_) {
    std::vector<Vector3d> normal, ft;
    std::vector<double> N, gap, slip;
    for (const SurfaceContactPoint& cp : shell_contact_->contact().points()) {
      if (!cp.active) continue;
      feet.push_back(cp.foot.point);
      foot_pressure.push_back(-cp.N);
      foot_traction.push_back(-cp.T_vector);  // on the tool: opposite to the shell's
      foot_state.push_back(shell_contact_->contact().sticks(cp) ? 1.0 : 2.0);
      foot_radius.push_back(1.5 * std::sqrt(cp.weight));  // its area share of the shell
      pts.push_back(cp.x);
      normal.push_back(cp.normal);
      ft.push_back(cp.T_vector);
      N.push_back(cp.N);
      gap.push_back(cp.gap);
      slip.push_back(shell_contact_->contact().sticks(cp) ? 0.0 : 1.0);
    }
    cd.scalars = {{"N", N}, {"gap", gap}, {"slip", slip}};
    cd.vectors = {{"shell_normal", normal}, {"tangential_force", ft}};
  }
  if (has_contact()) {
    files.push_back(stem + "_contact.vtk");
    write_vtk_polydata((fs::path(dir) / files[1]).string(), pts, false, cd,
                       name_ + " contact points, t = " + fmt(t));
    // The same contact seen from the rigid tool: its surface points (the feet) with the
    // pressure, the traction the body exerts on the tool, and the state (1 stick, 2 slip).
    files.push_back(stem + "_tool_contact.vtk");
    td.scalars = {{"contact_pressure", foot_pressure}, {"contact_state", foot_state}};
    td.vectors = {{"tangential_traction", foot_traction}};
    write_vtk_polydata((fs::path(dir) / files[2]).string(), feet, false, td,
                       name_ + " contact on the rigid tool, t = " + fmt(t));
    // ... and as fields on a grid of each bounded piece of the tool (tool_fields).
    std::vector<ToolFoot> tf;
    for (std::size_t k = 0; k < feet.size(); ++k)
      tf.push_back({feet[k], foot_pressure[k], foot_state[k], foot_radius[k], foot_traction[k]});
    for (int i = 0; i < rigid_->num_patches(); ++i) {
      const auto [grid, spacing] = tool_grid(rigid_->patch(i));
      if (grid.empty()) continue;
      files.push_back(stem + "_tool" + (rigid_->num_patches() == 1 ? "" : "_" + std::to_string(i)) +
                      ".vtk");
      write_vtk_grid((fs::path(dir) / files.back()).string(), grid, kToolGrid, kToolGrid,
                     tool_fields(grid, spacing, tf),
                     name_ + " contact on rigid piece " + std::to_string(i) + ", t = " + fmt(t));
    }
  }
  return files;
}

bool Analysis::write_rigid_vtk(const std::string& dir, const std::string& stem) const {
  if (!rigid_) return false;
  // One 41 x 41 grid per bounded piece: <stem>.vtk for a single piece, else <stem>_<i>.vtk.
  int written = 0;
  for (int i = 0; i < rigid_->num_patches(); ++i) {
    const std::vector<Vector3d> pts = tool_grid(rigid_->patch(i)).first;
    if (pts.empty()) continue;
    constexpr int n = kToolGrid;
    const std::string file =
        rigid_->num_patches() == 1 ? stem + ".vtk" : stem + "_" + std::to_string(i) + ".vtk";
    write_vtk_grid((fs::path(dir) / file).string(), pts, n, n, {}, name_ + " rigid surface");
    ++written;
  }
  return written > 0;
}

}  // namespace iga
