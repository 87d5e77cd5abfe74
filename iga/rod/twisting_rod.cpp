// Kirchhoff rod with torsion: nodal triads, the section frame by smallest rotations and a
// relative twist, the energy and its derivatives by automatic differentiation, assembly.
// References and notation: see twisting_rod.hpp ([MPW14], [SVQ86], [KS15]).
#include "iga/rod/twisting_rod.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "geometry/number_text.hpp"
#include "iga/core/jet.hpp"
#include "iga/core/quadrature.hpp"
#include "iga/core/state_archive.hpp"
#include "iga/rod/rod_common.hpp"

namespace iga {

namespace {

/// SR(a -> t) v for v normal to a (the header's formula): v - (t.v)/(1 + a.t) (a + t).
template <int N>
JetVec3<N> sr(const JetVec3<N>& a, const JetVec3<N>& t, const JetVec3<N>& v) {
  return v - (dot(t, v) * inverse(1.0 + dot(a, t))) * (a + t);
}

template <int N>
JetVec3<N> unit(const JetVec3<N>& a) {
  return inverse(sqrt(dot(a, a))) * a;
}

/// The derivative of a rational basis function j of element `first` in `B` (0 when j is not
/// among B's functions: at the end of a span the next span's basis holds the same values).
double basis_value(const BasisValues& values, const RationalBasis& B, int point) {
  const int j = point - B.first;
  return j >= 0 && j < B.count ? values[static_cast<std::size_t>(j)] : 0.0;
}

std::string num(double v) {
  return num_text(v, 6);
}

}  // namespace

TwistingRod::TwistingRod(NurbsCurve reference, RodSection section, RodOptions options)
    : reference_(std::move(reference)), section_(std::move(section)), options_(options) {
  const int p = reference_.degree();
  if (p < 2 || p > 5)
    throw RodError("TwistingRod: the curve must be of degree 2 to 5, got " + std::to_string(p));
  detail::check_rod_curve_and_section(reference_, section_, "TwistingRod");
  const KnotVector& U = reference_.knots();
  if (!(section_.GJ > 0.0) || !std::isfinite(section_.GJ))
    throw RodError("TwistingRod: GJ must be finite and > 0, got " + num(section_.GJ));
  if (!section_.isotropic() && !(section_.ref_direction.norm() > 0.0))
    throw RodError("TwistingRod: a general section (EI1 != EI2) needs a ref_direction");
  if (options_.quadrature_points < 0 || options_.quadrature_points > kMaxGaussPoints ||
      options_.axial_quadrature_points < 0 || options_.axial_quadrature_points > kMaxGaussPoints)
    throw RodError("TwistingRod: quadrature point counts must be in [0, 20]");

  const int ng = options_.quadrature_points > 0 ? options_.quadrature_points : p + 1;
  const int na = options_.axial_quadrature_points > 0 ? options_.axial_quadrature_points : ng;
  std::array<double, kMaxGaussPoints> gx{}, gw{}, ax{}, aw{};
  gauss_legendre(ng, gx, gw);
  gauss_legendre(na, ax, aw);
  const std::vector<double>& k = U.knots();
  const int n = reference_.num_control_points();
  auto make_point = [&](const Element& el, double xi, double weight) {
    QuadraturePoint q;
    q.xi = xi;
    q.s = (xi - el.range.lo) / (el.range.hi - el.range.lo);
    q.basis = rational_basis(reference_, xi);
    Vector3d R1 = Vector3d::Zero();
    for (int j = 0; j < q.basis.count; ++j)
      R1 += q.basis.dN[static_cast<std::size_t>(j)] * reference_.control_point(q.basis.first + j);
    q.A = R1.squaredNorm();
    q.J = std::sqrt(q.A);
    q.wJ = weight * q.J;
    return q;
  };
  for (int i = p; i < n; ++i) {
    const double lo = k[static_cast<std::size_t>(i)], hi = k[static_cast<std::size_t>(i + 1)];
    if (!(hi > lo)) continue;
    Element el;
    el.first = i - p;
    el.range = {lo, hi};
    const RationalBasis Blo = rational_basis(reference_, lo), Bhi = rational_basis(reference_, hi);
    for (int j = 0; j <= p; ++j) {
      el.dN_lo[static_cast<std::size_t>(j)] = basis_value(Blo.dN, Blo, el.first + j);
      el.dN_hi[static_cast<std::size_t>(j)] = basis_value(Bhi.dN, Bhi, el.first + j);
    }
    el.qp_begin = static_cast<int>(qps_.size());
    const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
    for (int g = 0; g < ng; ++g) {
      const std::size_t gi = static_cast<std::size_t>(g);
      qps_.push_back(make_point(el, mid + half * gx[gi], half * gw[gi]));
      qps_.back().axial = (na == ng);
    }
    if (na != ng)
      for (int g = 0; g < na; ++g) {
        const std::size_t gi = static_cast<std::size_t>(g);
        qps_.push_back(make_point(el, mid + half * ax[gi], half * aw[gi]));
        qps_.back().bending = false;
      }
    el.qp_count = static_cast<int>(qps_.size()) - el.qp_begin;
    if (knots_.empty()) knots_.push_back(lo);
    knots_.push_back(hi);
    elements_.push_back(el);
  }

  const std::vector<Vector3d> X = reference_.control_points();
  set_reference_triads(X);
  committed_ = ref_;
  set_stress_free_strains(X);
}

void TwistingRod::set_reference_triads(const std::vector<Vector3d>& X) {
  // D_1 from ref_direction, or carried by SR from the first knot.
  const int p = degree();
  ref_.resize(knots_.size());
  for (std::size_t kk = 0; kk < knots_.size(); ++kk) {
    const Element& el = elements_[std::min(kk, elements_.size() - 1)];
    const auto& dN = kk < elements_.size() ? el.dN_lo : el.dN_hi;
    Vector3d a = Vector3d::Zero();
    for (int j = 0; j <= p; ++j)
      a += dN[static_cast<std::size_t>(j)] * X[static_cast<std::size_t>(el.first + j)];
    if (!(a.norm() > 0.0))
      throw RodError("TwistingRod: zero tangent at the knot " + num(knots_[kk]));
    Triad& T = ref_[kk];
    T.t = a.normalized();
    if (section_.ref_direction.norm() > 0.0) {
      const Vector3d D = section_.ref_direction - section_.ref_direction.dot(T.t) * T.t;
      if (!(D.norm() > 1e-8 * section_.ref_direction.norm()))
        throw RodError(
            "TwistingRod: the section's ref_direction is parallel to the tangent at "
            "the knot " +
            num(knots_[kk]));
      T.d1 = D.normalized();
    } else if (kk == 0) {
      int axis = 0;  // the coordinate axis most normal to the tangent
      T.t.cwiseAbs().minCoeff(&axis);
      const Vector3d e = Vector3d::Unit(axis);
      T.d1 = (e - e.dot(T.t) * T.t).normalized();
    } else {
      const Triad& L = ref_[kk - 1];
      T.d1 = L.d1 - (T.t.dot(L.d1) / (1.0 + L.t.dot(T.t))) * (L.t + T.t);
      T.d1 = (T.d1 - T.d1.dot(T.t) * T.t).normalized();
    }
  }
}

void TwistingRod::set_stress_free_strains(const std::vector<Vector3d>& X) {
  // The formulas at the reference (x = X, alpha = 0).
  const std::vector<double> zero(knots_.size(), 0.0);
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    Eval ev;
    evaluate(static_cast<int>(e), X, zero, ref_, ev);
    elements_[e].Delta = ev.Delta;
    for (int g = 0; g < elements_[e].qp_count; ++g) {
      Eval at;
      QuadraturePoint& q = qps_[static_cast<std::size_t>(elements_[e].qp_begin + g)];
      at.xi = &q.xi;
      evaluate(static_cast<int>(e), X, zero, ref_, at);
      q.K = at.strains.kappa;
      if (options_.straight_stress_free) q.K.head<2>().setZero();
    }
  }
}

Interval TwistingRod::element_range(int e) const {
  return elements_.at(static_cast<std::size_t>(e)).range;
}
int TwistingRod::element_first_point(int e) const {
  return elements_.at(static_cast<std::size_t>(e)).first;
}
double TwistingRod::reference_length() const {
  double L = 0.0;
  for (const QuadraturePoint& q : qps_)
    if (q.bending) L += q.wJ;
  return L;
}

void TwistingRod::check(std::span<const Vector3d> x, std::span<const double> alpha) const {
  if (static_cast<int>(x.size()) < num_control_points() ||
      static_cast<int>(alpha.size()) < num_knots())
    throw RodError("TwistingRod: " + std::to_string(x.size()) + " points and " +
                   std::to_string(alpha.size()) + " twists given, expected " +
                   std::to_string(num_control_points()) + " and " + std::to_string(num_knots()));
}

template <int P>
void TwistingRod::kernel(int e, std::span<const Vector3d> x, std::span<const double> alpha,
                         const std::vector<Triad>& triads, Eval& out) const {
  constexpr int N = 3 * (P + 1) + 2;
  using Jt = Jet<N>;
  using JV = JetVec3<N>;
  const Element& el = elements_[static_cast<std::size_t>(e)];
  const int ia = 3 * (P + 1);  // alpha_k; alpha_k+1 is ia + 1
  // sum_j c_j x_{first + j} as a linear function of the element DOFs
  auto combo = [&](auto&& coeff) {
    JV r;
    for (int c = 0; c < 3; ++c) {
      typename Jt::Grad gc = Jt::Grad::Zero();
      double v = 0.0;
      for (int j = 0; j <= P; ++j) {
        const double w = coeff(j);
        v += w * x[static_cast<std::size_t>(el.first + j)][c];
        gc[3 * j + c] = w;
      }
      r.c[c] = Jt::linear(v, gc);
    }
    return r;
  };
  // The nodal triad at knot k (the chart of the committed triad, turned by alpha_k - alpha_k^c).
  auto nodal = [&](const std::array<double, kMaxDegree + 1>& dN, int knot, int dof, JV& t, JV& d1) {
    t = unit(combo([&](int j) { return dN[static_cast<std::size_t>(j)]; }));
    const Triad& c = triads[static_cast<std::size_t>(knot)];
    const JV g = sr(JV::constant(c.t), t, JV::constant(c.d1));
    const Jt beta = Jt::variable(alpha[static_cast<std::size_t>(knot)], dof) - c.alpha;
    d1 = cos(beta) * g + sin(beta) * cross(t, g);
  };
  JV t0, d10, t1, d11;
  nodal(el.dN_lo, e, ia, t0, d10);
  nodal(el.dN_hi, e + 1, ia + 1, t1, d11);
  // A couple and a torque on the frame (t, d1): virtual work M.(t x dt) + a dd1.d2,
  // a = M.t + Mt: f_j = sum_c v_c t_c,j + a d1_c,j d2_c with v = M x t; K_jk = d f_j / d q_k
  // from the jets' gradients and Hessians.
  auto moment_terms = [&](const JV& t, const JV& d1) {
    const JV d2 = cross(t, d1);
    const JV v = cross(JV::constant(out.M), t);
    const Jt a = dot(t, out.M) + out.Mt;
    out.f = Eigen::VectorXd::Zero(N);
    out.K = Eigen::MatrixXd::Zero(N, N);
    for (std::size_t c = 0; c < 3; ++c) {
      out.f += v.c[c].v * t.c[c].g + (a.v * d2.c[c].v) * d1.c[c].g;
      out.K += t.c[c].g * v.c[c].g.transpose() + v.c[c].v * t.c[c].H;
      out.K += (d2.c[c].v * d1.c[c].g) * a.g.transpose() + (a.v * d2.c[c].v) * d1.c[c].H;
      out.K += a.v * (d1.c[c].g * d2.c[c].g.transpose());
    }
  };
  // Delta_e: the angle about t1 from SR(t0 -> t1) d10 to d11, continued from the committed one.
  const JV m = sr(t0, t1, d10);
  Jt Delta = atan2(dot(cross(m, d11), t1), dot(m, d11));
  Delta.v += 2.0 * std::numbers::pi * std::round((el.Delta - Delta.v) / (2.0 * std::numbers::pi));
  out.t0 = t0.value();
  out.d10 = d10.value();
  out.t1 = t1.value();
  out.d11 = d11.value();
  out.Delta = Delta.v;
  const double h = el.range.hi - el.range.lo;
  const Jt dphi = Delta / h;

  // The strains at one point: basis B there, s = (xi - xi_k)/h, J = |R'| there.
  struct Strain {
    Jt eps, k1, k2, k3;
    JV t, d1, d2;
    double phi = 0.0;
  };
  auto strain_at = [&](const RationalBasis& B, double s, double J, double A) {
    Strain r;
    const JV a = combo([&](int j) { return basis_value(B.dN, B, el.first + j); });
    const JV b = combo([&](int j) { return basis_value(B.ddN, B, el.first + j); });
    const Jt aa = dot(a, a);
    const Jt il = inverse(sqrt(aa));
    const JV t = il * a;
    const JV dt = il * (b - dot(t, b) * t);  // t'
    // g = SR(t0 -> t) d10 and g' (the header's formula, differentiated in xi)
    const Jt ic = inverse(1.0 + dot(t0, t));
    const Jt w = dot(t, d10) * ic;                        // (t.d10) / (1 + t0.t)
    const Jt dw = (dot(dt, d10) - w * dot(t0, dt)) * ic;  // w'
    const JV apt = t0 + t;
    const JV g = d10 - w * apt;
    const JV dg = -1.0 * (dw * apt + w * dt);
    const JV hv = cross(t, g);
    const Jt phi = s * Delta;
    const Jt cp = cos(phi), sp = sin(phi);
    r.d1 = cp * g + sp * hv;
    r.d2 = cp * hv - sp * g;
    r.t = t;
    r.k1 = -dot(r.d2, dt) / J;
    r.k2 = dot(r.d1, dt) / J;
    r.k3 = (dphi + dot(dg, hv)) / J;
    r.eps = (aa - A) / (2.0 * A);
    r.phi = phi.v;
    return r;
  };

  const RodSection& S = section_;
  if (out.xi) {  // strains at one parameter; at an inner right end, its left limit (r'' jumps
                 // where the curve is only C1)
    const double xi = std::min(*out.xi, el.range.hi - (e + 1 < num_elements() ? 1e-12 * h : 0.0));
    const RationalBasis B = rational_basis(reference_, xi);
    Vector3d R1 = Vector3d::Zero();
    for (int j = 0; j < B.count; ++j)
      R1 += B.dN[static_cast<std::size_t>(j)] * reference_.control_point(B.first + j);
    const double A = R1.squaredNorm();
    const Strain r = strain_at(B, (xi - el.range.lo) / h, std::sqrt(A), A);
    if (out.moment) {  // the frame at xi is the nodal triad at a knot: continuous
      moment_terms(r.t, r.d1);
      return;
    }
    if (out.spin_from) {  // the spin about t since the frame (t_c, d1_c): atan2 as for Delta_e
      const JV carried =
          sr(JV::constant(out.spin_from->first), r.t, JV::constant(out.spin_from->second));
      const Jt spin = atan2(dot(cross(carried, r.d1), r.t), dot(carried, r.d1));
      out.W = spin.v;
      out.f = spin.g;
      out.K = spin.H;
    }
    TwistStrains& o = out.strains;
    o.eps = r.eps.v;
    o.axial_force = S.EA * o.eps;
    o.kappa = Vector3d(r.k1.v, r.k2.v, r.k3.v);
    o.t = r.t.value();
    o.d1 = r.d1.value();
    o.d2 = r.d2.value();
    o.twist = alpha[static_cast<std::size_t>(e)] + r.phi;
    return;
  }
  Jt W(0.0);
  for (int gq = 0; gq < el.qp_count; ++gq) {
    const QuadraturePoint& q = qps_[static_cast<std::size_t>(el.qp_begin + gq)];
    const Strain r = strain_at(q.basis, q.s, q.J, q.A);
    Jt Wq(0.0);
    if (q.axial) Wq += 0.5 * S.EA * (r.eps * r.eps);
    if (q.bending) {
      const Jt e1 = r.k1 - q.K[0], e2 = r.k2 - q.K[1], e3 = r.k3 - q.K[2];
      Wq += 0.5 * S.EI1 * (e1 * e1) + 0.5 * S.EI2 * (e2 * e2) + 0.5 * S.GJ * (e3 * e3);
    }
    W += q.wJ * Wq;
  }
  out.W = W.v;
  if (out.derivatives) {
    out.f = W.g;
    out.K = W.H;
  }
}

void TwistingRod::evaluate(int e, std::span<const Vector3d> x, std::span<const double> alpha,
                           const std::vector<Triad>& triads, Eval& out) const {
  switch (degree()) {
    case 2:
      return kernel<2>(e, x, alpha, triads, out);
    case 3:
      return kernel<3>(e, x, alpha, triads, out);
    case 4:
      return kernel<4>(e, x, alpha, triads, out);
    default:
      return kernel<5>(e, x, alpha, triads, out);
  }
}

double TwistingRod::element_energy(int e, std::span<const Vector3d> x,
                                   std::span<const double> alpha) const {
  check(x, alpha);
  Eval ev;
  evaluate(e, x, alpha, committed_, ev);
  return ev.W;
}

double TwistingRod::energy(std::span<const Vector3d> x, std::span<const double> alpha) const {
  double W = 0.0;
  for (int e = 0; e < num_elements(); ++e) W += element_energy(e, x, alpha);
  return W;
}

void TwistingRod::element_tangent(int e, std::span<const Vector3d> x, std::span<const double> alpha,
                                  Eigen::VectorXd& f, Eigen::MatrixXd* K) const {
  check(x, alpha);
  Eval ev;
  ev.derivatives = true;
  evaluate(e, x, alpha, committed_, ev);
  f = ev.f;
  if (K) *K = ev.K;
}

void TwistingRod::assemble(std::span<const Vector3d> x, std::span<const double> alpha,
                           Eigen::VectorXd& f, std::vector<Triplet>* K) const {
  check(x, alpha);
  // Elements in parallel (OpenMP), each into its own Eval; summed and emitted in element order
  // by one thread, so f and K are the same bit for bit for any number of threads.
  const int nel = num_elements();
  const int ne = 3 * (degree() + 1) + 2;
  std::vector<Eval> evs(static_cast<std::size_t>(nel));
#pragma omp parallel for schedule(static) if (nel >= kParallelTwistingRodElements)
  for (int e = 0; e < nel; ++e) {
    Eval& ev = evs[static_cast<std::size_t>(e)];
    ev.derivatives = true;
    evaluate(e, x, alpha, committed_, ev);
  }
  f.setZero(num_dofs());
  for (int e = 0; e < nel; ++e) {
    const Eval& ev = evs[static_cast<std::size_t>(e)];
    auto global = [&](int l) { return global_dof(e, l); };
    for (int i = 0; i < ne; ++i) {
      f[global(i)] += ev.f[i];
      if (K)
        for (int j = 0; j < ne; ++j)
          if (ev.K(i, j) != 0.0) K->emplace_back(global(i), global(j), ev.K(i, j));
    }
  }
}

int TwistingRod::global_dof(int e, int l) const {
  const int np = degree() + 1;
  return l < 3 * np ? 3 * elements_.at(static_cast<std::size_t>(e)).first + l
                    : 3 * num_control_points() + e + l - 3 * np;
}

void TwistingRod::moment_at(double xi, const Vector3d& M, double Mt, std::span<const Vector3d> x,
                            std::span<const double> alpha, int& e, Eigen::VectorXd& f,
                            Eigen::MatrixXd& K) const {
  check(x, alpha);
  const Interval dom = reference_.domain();
  if (!(xi >= dom.lo && xi <= dom.hi))
    throw RodError("TwistingRod::moment_at: parameter " + num(xi) + " outside the curve's domain");
  e = element_at(xi);
  Eval ev;
  ev.xi = &xi;
  ev.moment = true;
  ev.M = M;
  ev.Mt = Mt;
  evaluate(e, x, alpha, committed_, ev);
  f = ev.f;
  K = ev.K;
}

SectionSpin TwistingRod::spin_since(double xi, const Vector3d& t_c, const Vector3d& d1_c,
                                    std::span<const Vector3d> x,
                                    std::span<const double> alpha) const {
  check(x, alpha);
  const int e = element_at(xi);
  Eval ev;
  ev.xi = &xi;
  const std::pair<Vector3d, Vector3d> from{t_c, d1_c};
  ev.spin_from = &from;
  evaluate(e, x, alpha, committed_, ev);
  SectionSpin sp;
  sp.value = ev.W;
  sp.gradient = ev.f;
  sp.hessian = ev.K;
  sp.positions = 3 * (degree() + 1);
  sp.dofs.resize(static_cast<std::size_t>(ev.f.size()));
  for (std::size_t l = 0; l < sp.dofs.size(); ++l) sp.dofs[l] = global_dof(e, static_cast<int>(l));
  sp.t = ev.strains.t;
  sp.d1 = ev.strains.d1;
  return sp;
}

int TwistingRod::element_at(double xi) const {
  int e = 0;
  while (e + 1 < num_elements() && xi >= elements_[static_cast<std::size_t>(e)].range.hi) ++e;
  return e;
}

TwistStrains TwistingRod::strains_at(double xi, std::span<const Vector3d> x,
                                     std::span<const double> alpha) const {
  check(x, alpha);
  Eval ev;
  ev.xi = &xi;
  evaluate(element_at(xi), x, alpha, committed_, ev);
  return ev.strains;
}

void TwistingRod::frame(double xi, std::span<const Vector3d> x, std::span<const double> alpha,
                        Vector3d& t, Vector3d& d1) const {
  const TwistStrains s = strains_at(xi, x, alpha);
  t = s.t;
  d1 = s.d1;
}

TwistStrains TwistingRod::strains(double xi, std::span<const Vector3d> x,
                                  std::span<const double> alpha) const {
  TwistStrains s = strains_at(xi, x, alpha);
  const int e = element_at(xi);
  // The stress-free strains at xi: the formulas at the reference with its triads.
  const std::vector<Vector3d> X = reference_.control_points();
  const std::vector<double> zero(knots_.size(), 0.0);
  Eval ref;
  ref.xi = &xi;
  evaluate(e, X, zero, ref_, ref);
  Vector3d K = ref.strains.kappa;
  if (options_.straight_stress_free) K.head<2>().setZero();
  s.moment = Vector3d(section_.EI1 * (s.kappa[0] - K[0]), section_.EI2 * (s.kappa[1] - K[1]),
                      section_.GJ * (s.kappa[2] - K[2]));
  const Vector3d d = s.kappa - K;
  s.energy_density = 0.5 * section_.EA * s.eps * s.eps + 0.5 * section_.EI1 * d[0] * d[0] +
                     0.5 * section_.EI2 * d[1] * d[1] + 0.5 * section_.GJ * d[2] * d[2];
  return s;
}

Vector3d TwistingRod::point(double xi, std::span<const Vector3d> x) const {
  const RationalBasis B = rational_basis(reference_, xi);
  Vector3d r = Vector3d::Zero();
  for (int j = 0; j < B.count; ++j)
    r += B.N[static_cast<std::size_t>(j)] * x[static_cast<std::size_t>(B.first + j)];
  return r;
}

void TwistingRod::knot_triad(int k, std::span<const Vector3d> x, std::span<const double> alpha,
                             Vector3d& t, Vector3d& d1) const {
  check(x, alpha);
  const int e = std::min(k, num_elements() - 1);
  Eval ev;
  ev.xi = &knots_[static_cast<std::size_t>(k)];
  evaluate(e, x, alpha, committed_, ev);
  t = k == e ? ev.t0 : ev.t1;
  d1 = k == e ? ev.d10 : ev.d11;
}

void TwistingRod::commit(std::span<const Vector3d> x, std::span<const double> alpha) {
  check(x, alpha);
  std::vector<Triad> next = committed_;
  for (int e = 0; e < num_elements(); ++e) {
    Eval ev;
    ev.xi = &knots_[static_cast<std::size_t>(e)];
    evaluate(e, x, alpha, committed_, ev);
    elements_[static_cast<std::size_t>(e)].Delta = ev.Delta;
    next[static_cast<std::size_t>(e)] = {ev.t0, ev.d10, alpha[static_cast<std::size_t>(e)]};
    if (e + 1 == num_elements())
      next[static_cast<std::size_t>(e + 1)] = {ev.t1, ev.d11,
                                               alpha[static_cast<std::size_t>(e + 1)]};
  }
  committed_ = std::move(next);
}

TwistingRod::History TwistingRod::history() const {
  History h;
  for (const Triad& T : committed_) {
    h.t.push_back(T.t);
    h.d1.push_back(T.d1);
    h.alpha.push_back(T.alpha);
  }
  for (const Element& el : elements_) h.Delta.push_back(el.Delta);
  return h;
}

void TwistingRod::set_history(const History& h) {
  const std::size_t m = knots_.size();
  if (h.t.size() != m || h.d1.size() != m || h.alpha.size() != m ||
      h.Delta.size() != elements_.size())
    throw RodError("TwistingRod::set_history: sizes do not match the rod's " + std::to_string(m) +
                   " knots and " + std::to_string(elements_.size()) + " elements");
  for (std::size_t k = 0; k < m; ++k)
    if (!(std::abs(h.t[k].norm() - 1.0) < 1e-10) || !(std::abs(h.d1[k].norm() - 1.0) < 1e-10) ||
        !(std::abs(h.t[k].dot(h.d1[k])) < 1e-10) || !std::isfinite(h.alpha[k]))
      throw RodError("TwistingRod::set_history: the triad at knot " + std::to_string(k) +
                     " is not orthonormal");
  for (std::size_t k = 0; k < m; ++k) committed_[k] = {h.t[k], h.d1[k], h.alpha[k]};
  for (std::size_t e = 0; e < elements_.size(); ++e) elements_[e].Delta = h.Delta[e];
}

// ---------------------------------------------------------------------------------------------
// TwistingRodProblem

namespace {
[[noreturn]] void twist_fail(const std::string& msg) {
  throw RodError(msg);
}
}  // namespace

TwistingRodProblem::TwistingRodProblem(TwistingRod rod)
    : ControlPointProblem(rod.reference().control_points(), "TwistingRodProblem", &twist_fail,
                          rod.num_knots()),
      rod_(std::move(rod)) {}

void TwistingRodProblem::clamp(RodEnd end) {
  const int n = rod_.num_control_points();
  const int i0 = end == RodEnd::kStart ? 0 : n - 1, i1 = end == RodEnd::kStart ? 1 : n - 2;
  if (dofs_.rotated(i1) || dofs_.constrained(i1, 0) || dofs_.constrained(i1, 1) ||
      dofs_.constrained(i1, 2))
    throw RodError("TwistingRodProblem::clamp: control point " + std::to_string(i1) +
                   " (neighbour of the clamped end) already has a local basis or constraints");
  const int k = end_knot(end);
  const Vector3d T = rod_.reference_tangent(k);
  Matrix3d Q;
  Q.col(0) = T;
  Q.col(1) = T.unitOrthogonal();
  Q.col(2) = T.cross(Q.col(1));
  fix(i0);
  set_local_basis(i1, Q);
  fix(i1, 1);
  fix(i1, 2);
  fix_twist(k);
}

void TwistingRodProblem::symmetry(RodEnd end, const Vector3d& n) {
  const int last = rod_.num_control_points() - 1;
  end_symmetry(end == RodEnd::kStart ? 0 : last, end == RodEnd::kStart ? 1 : last - 1, n,
               "TwistingRodProblem::symmetry", &twist_fail);
}

void TwistingRodProblem::fix_twist(int knot) {
  if (knot < 0 || knot >= rod_.num_knots())
    throw RodError("TwistingRodProblem: knot " + std::to_string(knot) + " out of range [0, " +
                   std::to_string(rod_.num_knots() - 1) + "]");
  if (!dofs_.scalar_constrained(knot)) dofs_.fix_scalar(knot);
}

void TwistingRodProblem::prescribe_twist(int knot, double angle, LoadCurve curve) {
  if (knot < 0 || knot >= rod_.num_knots())
    throw RodError("TwistingRodProblem: knot " + std::to_string(knot) + " out of range [0, " +
                   std::to_string(rod_.num_knots() - 1) + "]");
  dofs_.prescribe_scalar(knot, angle, std::move(curve));
}

void TwistingRodProblem::split(const VectorXd& u, double t, std::vector<Vector3d>& x,
                               std::vector<double>& alpha) const {
  current_points(u, t, x);
  dofs_.current_scalars(u, t, alpha);
}

double TwistingRodProblem::twist(int knot, const VectorXd& u, double t) const {
  std::vector<Vector3d> x;
  std::vector<double> alpha;
  split(u, t, x, alpha);
  return alpha.at(static_cast<std::size_t>(knot));
}

void TwistingRodProblem::add_point_load(double xi, const Vector3d& F, LoadCurve curve) {
  add_nodal_load(detail::rod_point_load(rod_.reference(), xi, F), std::move(curve));
}

void TwistingRodProblem::add_torque_at(double xi, double Mt, LoadCurve curve) {
  check_parameter(xi);
  moments_.push_back({xi, Vector3d::Zero(), Mt, std::move(curve)});
}

void TwistingRodProblem::add_moment_at(double xi, const Vector3d& M, LoadCurve curve) {
  check_parameter(xi);
  moments_.push_back({xi, M, 0.0, std::move(curve)});
}

void TwistingRodProblem::check_parameter(double xi) const {
  const Interval dom = rod_.reference().domain();
  if (!(xi >= dom.lo && xi <= dom.hi))
    throw RodError("TwistingRodProblem: parameter " + num(xi) + " outside the curve's domain [" +
                   num(dom.lo) + ", " + num(dom.hi) + "]");
}

int TwistingRodProblem::check_knot(int knot) const {
  if (knot < 0 || knot >= rod_.num_knots())
    throw RodError("TwistingRodProblem: knot " + std::to_string(knot) + " out of range [0, " +
                   std::to_string(rod_.num_knots() - 1) + "]");
  return knot;
}

void TwistingRodProblem::assemble_model(std::span<const Vector3d> x, std::span<const double> s,
                                        double t, VectorXd& g, std::vector<Triplet>* K) {
  rod_.assemble(x, s, g, K);  // alpha = s
  Eigen::VectorXd f;
  Eigen::MatrixXd Km;
  for (const KnotMoment& mo : moments_) {
    const double lam = mo.curve(t);
    if (lam == 0.0) continue;
    int e = 0;
    rod_.moment_at(mo.xi, lam * mo.M, lam * mo.Mt, x, s, e, f, Km);
    for (Eigen::Index i = 0; i < f.size(); ++i) {
      const int gi = rod_.global_dof(e, static_cast<int>(i));
      g[gi] -= f[i];  // g = f_int - f_ext
      if (K)
        for (Eigen::Index j = 0; j < f.size(); ++j)
          if (Km(i, j) != 0.0)
            K->emplace_back(gi, rod_.global_dof(e, static_cast<int>(j)), -Km(i, j));
    }
  }
}

void TwistingRodProblem::commit(const VectorXd& u, double t) {
  std::vector<Vector3d> x;
  std::vector<double> alpha;
  split(u, t, x, alpha);
  rod_.commit(x, alpha);
  ControlPointProblem::commit(u, t);
}

void TwistingRodProblem::archive(StateArchive& a) {
  TwistingRod::History h = rod_.history();
  a.section("twisting rod");
  const auto vec3 = [&](Vector3d& v) { a.io(v); };
  a.items(h.t, vec3, "knot tangents", /*resize=*/false);
  a.items(h.d1, vec3, "knot directors", /*resize=*/false);
  a.io(h.alpha);
  a.io(h.Delta);
  if (a.loading()) {
    try {
      rod_.set_history(h);
    } catch (const RodError& e) {
      a.fail(e.what());
    }
  }
  ControlPointProblem::archive(a);
}

std::string TwistingRodProblem::describe() const {
  return "rod with torsion of " + std::to_string(rod_.num_elements()) + " elements (degree " +
         std::to_string(rod_.degree()) + ", " + std::to_string(rod_.num_control_points()) +
         " control points, " + std::to_string(rod_.num_knots()) + " twists)";
}

Vector3d TwistingRodProblem::displacement(double pu, double pv, const VectorXd& u, double t) const {
  (void)pv;
  std::vector<Vector3d> x;
  std::vector<double> alpha;
  split(u, t, x, alpha);
  return rod_.point(pu, x) - rod_.reference().point(pu);
}

SampledMesh TwistingRodProblem::sample_model(const VectorXd& u, double t, int samples) const {
  std::vector<Vector3d> x;
  std::vector<double> alpha;
  split(u, t, x, alpha);
  SampledMesh m;
  m.shape = SampledMesh::Shape::kPolyline;
  std::vector<double> force, m1, m2, torque, twist_angle, singular;
  std::vector<Vector3d> d1, d2;
  for (int e = 0; e < rod_.num_elements(); ++e) {
    const Interval I = rod_.element_range(e);
    for (int k = (e == 0 ? 0 : 1); k <= samples; ++k) {
      const double xi = I.lo + (I.hi - I.lo) * k / samples;
      m.points.push_back(rod_.point(xi, x));
      m.params.push_back({xi, 0.0});
      m.elements.push_back(e);
      TwistStrains st;
      bool ok = true;
      try {
        st = rod_.strains(xi, x, alpha);
        ok = std::isfinite(st.axial_force) && st.moment.allFinite() && std::isfinite(st.twist) &&
             st.d1.allFinite();
      } catch (const std::exception&) {
        ok = false;
      }
      if (!ok) st = TwistStrains{};
      force.push_back(st.axial_force);
      m1.push_back(st.moment[0]);
      m2.push_back(st.moment[1]);
      torque.push_back(st.moment[2]);
      twist_angle.push_back(st.twist);
      d1.push_back(st.d1);
      d2.push_back(st.d2);
      singular.push_back(ok ? 0.0 : 1.0);
    }
  }
  m.fields.scalars = {{"axial_force", force}, {"bending_moment_1", m1}, {"bending_moment_2", m2},
                      {"torque", torque},     {"twist", twist_angle},   {"singular", singular}};
  m.fields.vectors = {{"section_d1", d1}, {"section_d2", d2}};
  return m;
}

}  // namespace iga
