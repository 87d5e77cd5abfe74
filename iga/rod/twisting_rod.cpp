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

/// The relative twist Delta_e of an element from its knots' frames (d1, d2, t) as jets over
/// y_0 and y_1, continued from its committed value: a jet over (y_0, y_1).
Jet<8> relative_twist(const std::array<JetVec3<4>, 3>& F0, const std::array<JetVec3<4>, 3>& F1,
                      double committed) {
  // Delta_e = atan2(y, x) with m = SR(t_0 -> t_1) d1_0: x = m.d1_1, y = (m x d1_1).t_1 =
  // -m.d2_1; with t_1.d1_1 = t_1.d2_1 = 0 these are x = d1_0.d1_1 - (t_1.d1_0)(t_0.d1_1)/(1 +
  // t_0.t_1), y = -(d1_0.d2_1 - (t_1.d1_0)(t_0.d2_1)/(1 + t_0.t_1)): products of the two
  // frames' vectors, each a jet over y_0 times a jet over y_1.
  auto prod = [](const JetVec3<4>& u,
                 const JetVec3<4>& v) {  // u.v, u over variables 0-3, v over 4-7
    Jet<8> z(0.0);
    for (std::size_t c = 0; c < 3; ++c) {
      const Jet<4>&uc = u.c[c], &vc = v.c[c];
      z.v += uc.v * vc.v;
      z.g.template head<4>() += vc.v * uc.g;
      z.g.template tail<4>() += uc.v * vc.g;
      z.H.template topLeftCorner<4, 4>() += vc.v * uc.H;
      z.H.template bottomRightCorner<4, 4>() += uc.v * vc.H;
      z.H.template topRightCorner<4, 4>().noalias() += uc.g * vc.g.transpose();
    }
    z.H.template bottomLeftCorner<4, 4>() = z.H.template topRightCorner<4, 4>().transpose();
    return z;
  };
  const Jet<8> r = inverse(1.0 + prod(F0[2], F1[2]));
  const Jet<8> p = prod(F0[0], F1[2]) * r;  // (t_1.d1_0)/(1 + t_0.t_1)
  const Jet<8> xD = prod(F0[0], F1[0]) - p * prod(F0[2], F1[0]);
  const Jet<8> yD = p * prod(F0[2], F1[1]) - prod(F0[0], F1[1]);
  Jet<8> Delta = atan2(yD, xD);
  Delta.v += 2.0 * std::numbers::pi * std::round((committed - Delta.v) / (2.0 * std::numbers::pi));
  return Delta;
}

double value_of(double v) {
  return v;
}
template <int N>
double value_of(const Jet<N>& j) {
  return j.v;
}
double inverse(double a) {
  return 1.0 / a;
}
/// Numbers of spin_at: a double, or a jet over (a, y_0, y_1) from the frames' jets.
template <typename T>
struct SpinNumber {
  static double var(double v, int) { return v; }
  template <int M>
  static double lift(const Jet<M>& j) {
    return j.v;
  }
};
template <>
struct SpinNumber<Jet<11>> {
  static Jet<11> var(double v, int i) { return Jet<11>::variable(v, i); }
  template <int M>
  static Jet<11> lift(const Jet<M>& j) {
    return embed<11>(j, 3);
  }
};

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

// The written-out chain (the header's "Derivatives"). Per element: the end frames F_k = (d1_k,
// d2_k, t_k) as jets over y_k = (a_k, beta_k) (4 variables each) and Delta_e as a jet over (y_0,
// y_1) (8). Per quadrature point: a, b in the left frame, a^ = F_0^T a, b^ = F_0^T b; the SR
// frame's strain scalars c = (c_1, c_2, c_3) as jets over (a^, b^) (6); W_q as a function of
// (c, Delta) written out; then the chain rule to (a, b, y_0, Delta) and to the element DOFs.
namespace {

/// What a quadrature point gives: W_q and its derivatives in (a^, b^) and Delta.
struct PointTerms {
  Eigen::Matrix<double, 6, 1> gv = Eigen::Matrix<double, 6, 1>::Zero();
  Eigen::Matrix<double, 6, 6> Hv = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> HvD = Eigen::Matrix<double, 6, 1>::Zero();  ///< d2W/d(a^, b^) dDelta
  double gvD = 0.0, HDD = 0.0, W = 0.0;
};

/// The bending and torsion energy of a quadrature point (the header's "Derivatives"): a^, b^
/// in the left frame's components, s = (xi - xi_k)/h, J = |R'|, K the stress-free curvatures.
void bending_terms(const Vector3d& ah, const Vector3d& bh, double s, double J, const Vector3d& K,
                   double Delta, double h, const RodSection& S, PointTerms& d) {
  using J3 = Jet<3>;
  // c_1 = g.t', c_2 = (t x g).t', c_3 = g'.(t x g) in the left frame's components:
  // tau = t^ = a^/|a^|, del = t'^ = (b^ - (tau.b^) tau)/|a^|, w_i = tau_i/(1 + tau_3);
  // c_1 = del_1 - w_1 del_3, c_2 = del_2 - w_2 del_3, c_3 = (tau_2 c_1 - tau_1 c_2)/(1 +
  // tau_3) = w_2 del_1 - w_1 del_2. So c = M(a^) b^ with M's rows (using tau.(1, 0, -w_1)
  // = w_1): M_1 = ((1, 0, -w_1) - w_1 tau)/|a^|, M_2 = ((0, 1, -w_2) - w_2 tau)/|a^|,
  // M_3 = (w_2, -w_1, 0)/|a^|: M as jets over a^ only.
  std::array<J3, 3> av, tau;
  for (int i = 0; i < 3; ++i) av[static_cast<std::size_t>(i)] = J3::variable(ah[i], i);
  const J3 il = inverse(sqrt(av[0] * av[0] + av[1] * av[1] + av[2] * av[2]));
  for (std::size_t i = 0; i < 3; ++i) tau[i] = il * av[i];
  const J3 iR = inverse(1.0 + tau[2]);
  const J3 w1 = tau[0] * iR, w2 = tau[1] * iR;
  const J3 iw1 = il * w1, iw2 = il * w2;
  const std::array<std::array<J3, 3>, 3> M = {{
      {il - iw1 * tau[0], -1.0 * (iw1 * tau[1]), -1.0 * (iw1 + iw1 * tau[2])},
      {-1.0 * (iw2 * tau[0]), il - iw2 * tau[1], -1.0 * (iw2 + iw2 * tau[2])},
      {iw2, -1.0 * iw1, J3(0.0)},
  }};
  std::array<J3, 3> c;
  for (std::size_t i = 0; i < 3; ++i) {
    c[i] = bh[0] * M[i][0];
    c[i] += bh[1] * M[i][1];
    c[i] += bh[2] * M[i][2];
  }
  const J3& c3 = c[2];
  // kappa_1 = (sin phi c_1 - cos phi c_2)/J, kappa_2 = (cos phi c_1 + sin phi c_2)/J,
  // kappa_3 = (Delta/h + c_3)/J, phi = s Delta; u = (c_1, c_2, c_3, Delta).
  const double phi = s * Delta, sn = std::sin(phi), cs = std::cos(phi), iJ = 1.0 / J;
  const double k1 = (sn * c[0].v - cs * c[1].v) * iJ, k2 = (cs * c[0].v + sn * c[1].v) * iJ;
  const double k3 = (Delta / h + c3.v) * iJ;
  const Eigen::Vector4d g1(sn * iJ, -cs * iJ, 0.0, s * k2), g2(cs * iJ, sn * iJ, 0.0, -s * k1),
      g3(0.0, 0.0, iJ, iJ / h);
  const double e1 = k1 - K[0], e2 = k2 - K[1], e3 = k3 - K[2];
  const double C1 = S.EI1 * e1, C2 = S.EI2 * e2, C3 = S.GJ * e3;
  d.W += 0.5 * (C1 * e1 + C2 * e2 + C3 * e3);
  const Eigen::Vector4d gu = C1 * g1 + C2 * g2 + C3 * g3;
  Eigen::Matrix4d Hu =
      S.EI1 * g1 * g1.transpose() + S.EI2 * g2 * g2.transpose() + S.GJ * g3 * g3.transpose();
  // second derivatives of kappa_1, kappa_2 (kappa_3 is linear in u)
  const double sJ = s * iJ;
  Hu(0, 3) += C1 * sJ * cs - C2 * sJ * sn;
  Hu(1, 3) += C1 * sJ * sn + C2 * sJ * cs;
  Hu(3, 0) = Hu(0, 3);
  Hu(3, 1) = Hu(1, 3);
  Hu(3, 3) += -s * s * (C1 * k1 + C2 * k2);
  // c's gradient over (a^, b^): (grad c_i, M_i); its Hessian: [[H c_i, dM_i/da^], [., 0]]
  Eigen::Matrix<double, 6, 3> Cg;
  Matrix3d Hab = Matrix3d::Zero();  // sum_i gu_i d2c_i/da^ db^
  for (std::size_t i = 0; i < 3; ++i) {
    Cg.col(static_cast<int>(i)) << c[i].g, M[i][0].v, M[i][1].v, M[i][2].v;
    for (std::size_t mm = 0; mm < 3; ++mm)
      Hab.col(static_cast<int>(mm)) += gu[static_cast<int>(i)] * M[i][mm].g;
  }
  d.gv = Cg * gu.head<3>();
  d.Hv.noalias() = Cg * Hu.topLeftCorner<3, 3>() * Cg.transpose();
  d.Hv.topLeftCorner<3, 3>() += gu[0] * c[0].H + gu[1] * c[1].H + gu[2] * c3.H;
  d.Hv.topRightCorner<3, 3>() += Hab;
  d.Hv.bottomLeftCorner<3, 3>() += Hab.transpose();
  d.HvD = Cg * Hu.col(3).head<3>();
  d.gvD = gu[3];
  d.HDD = Hu(3, 3);
}

}  // namespace

struct TwistingRod::NodalFrame {
  std::array<JetVec3<4>, 3> F;  ///< d1, d2, t
};

// The nodal frame (d1_k, d2_k, t_k) over y_k = (a_k, beta_k), as in kernel(): t, g =
// SR(t_c -> t) d1_c and h = t x g as jets over a_k; then d1 = cos(beta) g + sin(beta) h and
// d2 = t x d1 = cos(beta) h - sin(beta) g (t x h = -g), their beta-derivatives written out.
void TwistingRod::nodal_frame(int knot, std::span<const Vector3d> x, std::span<const double> alpha,
                              const std::vector<Triad>& triads, NodalFrame& NF) const {
  using J3 = Jet<3>;
  using J4 = Jet<4>;
  const int nel = num_elements();
  const Element& el = elements_[static_cast<std::size_t>(std::min(knot, nel - 1))];
  const auto& dN = knot < nel ? el.dN_lo : el.dN_hi;
  std::array<JetVec3<4>, 3>& F = NF.F;
  Vector3d a = Vector3d::Zero();
  for (int j = 0; j <= degree(); ++j)
    a += dN[static_cast<std::size_t>(j)] * x[static_cast<std::size_t>(el.first + j)];
  JetVec3<3> av;
  for (int c = 0; c < 3; ++c) av.c[static_cast<std::size_t>(c)] = J3::variable(a[c], c);
  const JetVec3<3> t = unit(av);
  const Triad& tc = triads[static_cast<std::size_t>(knot)];
  const J3 w = dot(t, tc.d1) * inverse(1.0 + dot(t, tc.t));
  JetVec3<3> g;
  for (std::size_t c = 0; c < 3; ++c)
    g.c[c] = tc.d1[static_cast<int>(c)] - w * (t.c[c] + tc.t[static_cast<int>(c)]);
  const JetVec3<3> hv = cross(t, g);
  const double beta = alpha[static_cast<std::size_t>(knot)] - tc.alpha;
  const double cb = std::cos(beta), sb = std::sin(beta);
  // u = cb p + sb q as a jet over (a, beta)
  auto rotated = [&](const J3& pp, const J3& qq) {
    J4 z(cb * pp.v + sb * qq.v);
    z.g.template head<3>() = cb * pp.g + sb * qq.g;
    z.g[3] = -sb * pp.v + cb * qq.v;
    z.H.template topLeftCorner<3, 3>() = cb * pp.H + sb * qq.H;
    z.H.template topRightCorner<3, 1>() = -sb * pp.g + cb * qq.g;
    z.H.template bottomLeftCorner<1, 3>() = z.H.template topRightCorner<3, 1>().transpose();
    z.H(3, 3) = -z.v;
    return z;
  };
  for (std::size_t c = 0; c < 3; ++c) {
    F[0].c[c] = rotated(g.c[c], hv.c[c]);
    F[1].c[c] = rotated(hv.c[c], -1.0 * g.c[c]);
    F[2].c[c] = embed<4>(t.c[c], 0);
  }
}

template <int P>
double TwistingRod::fast_tangent(int e, std::span<const Vector3d> x, const NodalFrame& NF0,
                                 const NodalFrame& NF1, Eigen::VectorXd& f_out,
                                 Eigen::MatrixXd& K_out) const {
  constexpr int np = P + 1, N = 3 * np + 2;
  using V4 = JetVec3<4>;
  using J8 = Jet<8>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  const Element& el = elements_[static_cast<std::size_t>(e)];
  const auto xj = [&](int j) -> const Vector3d& {
    return x[static_cast<std::size_t>(el.first + j)];
  };
  const std::array<V4, 3>& F0 = NF0.F;
  const std::array<V4, 3>& F1 = NF1.F;
  J8 Delta = relative_twist(F0, F1, el.Delta);
  const double h = el.range.hi - el.range.lo;

  Matrix3d Fm;  // rows d1_0, d2_0, t_0
  for (int i = 0; i < 3; ++i) Fm.row(i) = F0[static_cast<std::size_t>(i)].value().transpose();

  Eigen::Matrix<double, N, 1> f = Eigen::Matrix<double, N, 1>::Zero();
  Eigen::Matrix<double, N, N> K = Eigen::Matrix<double, N, N>::Zero();
  Eigen::Matrix<double, N, 5> X = Eigen::Matrix<double, N, 5>::Zero();  // d2W/dq d(y_0, Delta)
  Matrix3d Cf = Matrix3d::Zero();  // sum of dW/da^_i a_c + dW/db^_i b_c: weights of F0's Hessians
  Eigen::Matrix<double, 5, 5> Hy = Eigen::Matrix<double, 5, 5>::Zero();  // over (y_0, Delta)
  double gD = 0.0, W = 0.0;
  const RodSection& S = section_;
  std::array<double, np> dN{}, ddN{};
  for (int gq = 0; gq < el.qp_count; ++gq) {
    const QuadraturePoint& q = qps_[static_cast<std::size_t>(el.qp_begin + gq)];
    Vector3d a = Vector3d::Zero(), b = Vector3d::Zero();
    for (int j = 0; j < np; ++j) {
      dN[static_cast<std::size_t>(j)] = basis_value(q.basis.dN, q.basis, el.first + j);
      ddN[static_cast<std::size_t>(j)] = basis_value(q.basis.ddN, q.basis, el.first + j);
      a += dN[static_cast<std::size_t>(j)] * xj(j);
      b += ddN[static_cast<std::size_t>(j)] * xj(j);
    }
    const Vector3d ah = Fm * a, bh = Fm * b;
    PointTerms d;
    if (q.bending) bending_terms(ah, bh, q.s, q.J, q.K, Delta.v, h, S, d);
    Vec6& gv = d.gv;  // dW_q/d(a^, b^)
    Mat6& Hv = d.Hv;
    Vec6& HvD = d.HvD;
    double &gvD = d.gvD, &HDD = d.HDD, &Wq = d.W;
    if (q.axial) {  // eps = (|a|^2 - A)/(2A), |a^| = |a|
      const double eps = (ah.squaredNorm() - q.A) / (2.0 * q.A);
      Wq += 0.5 * S.EA * eps * eps;
      gv.head<3>() += (S.EA * eps / q.A) * ah;
      Hv.topLeftCorner<3, 3>() += (S.EA / (q.A * q.A)) * (ah * ah.transpose());
      Hv.topLeftCorner<3, 3>().diagonal().array() += S.EA * eps / q.A;
    }
    const double wq = q.wJ;
    W += wq * Wq;
    gv *= wq;
    Hv *= wq;
    HvD *= wq;
    gvD *= wq;
    HDD *= wq;
    // Chain to (a, b, y_0, Delta): a^_i = f_i . a with f_i = F0[i] (a jet over y_0).
    Eigen::Matrix<double, 6, 4> My;                                         // d(a^, b^)/dy_0
    Eigen::Matrix<double, 6, 4> Sab = Eigen::Matrix<double, 6, 4>::Zero();  // sum_i g_i df_ic/dy_0
    for (std::size_t i = 0; i < 3; ++i) {
      Eigen::Vector4d ja = Eigen::Vector4d::Zero(), jb = Eigen::Vector4d::Zero();
      for (std::size_t c = 0; c < 3; ++c) {
        const Eigen::Vector4d& G = F0[i].c[c].g;
        ja += a[static_cast<int>(c)] * G;
        jb += b[static_cast<int>(c)] * G;
        Sab.row(static_cast<int>(c)) += gv[static_cast<int>(i)] * G.transpose();
        Sab.row(3 + static_cast<int>(c)) += gv[3 + static_cast<int>(i)] * G.transpose();
        Cf(static_cast<int>(i), static_cast<int>(c)) +=
            gv[static_cast<int>(i)] * a[static_cast<int>(c)] +
            gv[3 + static_cast<int>(i)] * b[static_cast<int>(c)];
      }
      My.row(static_cast<int>(i)) = ja.transpose();
      My.row(3 + static_cast<int>(i)) = jb.transpose();
    }
    // The positions in the left frame's components, x^_j = F_0 x_j (F_0 at its value): there
    // d(a^, b^)/d(a, b) = I; the mixed second derivatives turn with F_0.
    const Vec6& gz = gv;
    const Mat6& Hzz = Hv;
    Eigen::Matrix<double, 6, 5> Hz5;  // d2W/d(a^, b^) d(y_0, Delta)
    const Eigen::Matrix<double, 6, 4> HvMy = Hv * My;
    Hz5.leftCols<4>() = HvMy;
    Hz5.topLeftCorner<3, 4>().noalias() += Fm * Sab.topRows<3>();
    Hz5.bottomLeftCorner<3, 4>().noalias() += Fm * Sab.bottomRows<3>();
    Hz5.col(4) = HvD;
    Hy.topLeftCorner<4, 4>() += My.transpose() * HvMy;
    Hy.col(4).head<4>() += My.transpose() * HvD;
    Hy(4, 4) += HDD;
    gD += gvD;
    // to the positions: a = sum_j R_j' x_j, b = sum_j R_j'' x_j
    for (int j = 0; j < np; ++j) {
      const double Aj = dN[static_cast<std::size_t>(j)], Bj = ddN[static_cast<std::size_t>(j)];
      f.template segment<3>(3 * j) += Aj * gz.head<3>() + Bj * gz.tail<3>();
      X.template middleRows<3>(3 * j) += Aj * Hz5.topRows<3>() + Bj * Hz5.bottomRows<3>();
      const Matrix3d Ej = Aj * Hzz.topLeftCorner<3, 3>() + Bj * Hzz.bottomLeftCorner<3, 3>();
      const Matrix3d Gj = Aj * Hzz.topRightCorner<3, 3>() + Bj * Hzz.bottomRightCorner<3, 3>();
      for (int k = 0; k < np; ++k)
        K.template block<3, 3>(3 * j, 3 * k) +=
            Ej * dN[static_cast<std::size_t>(k)] + Gj * ddN[static_cast<std::size_t>(k)];
    }
  }
  // back from x^_j = F_0 x_j to x_j
  for (int j = 0; j < np; ++j) {
    f.template segment<3>(3 * j) = Fm.transpose() * f.template segment<3>(3 * j);
    X.template middleRows<3>(3 * j) = Fm.transpose() * X.template middleRows<3>(3 * j);
    for (int k = 0; k < np; ++k)
      K.template block<3, 3>(3 * j, 3 * k) =
          Fm.transpose() * K.template block<3, 3>(3 * j, 3 * k) * Fm;
  }
  // F0's second derivatives, weighted once per element
  Eigen::Vector4d gy = Eigen::Vector4d::Zero();
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      const double w = Cf(static_cast<int>(i), static_cast<int>(c));
      gy += w * F0[i].c[c].g;
      Hy.topLeftCorner<4, 4>() += w * F0[i].c[c].H;
    }
  // (y_0, Delta) -> w = (y_0, y_1) = (a_0, beta_0, a_1, beta_1)
  Eigen::Matrix<double, 5, 8> Dw = Eigen::Matrix<double, 5, 8>::Zero();
  Dw.topLeftCorner<4, 4>().setIdentity();
  Dw.row(4) = Delta.g.transpose();
  Hy.row(4).head<4>() = Hy.col(4).head<4>().transpose();
  Eigen::Matrix<double, 8, 1> gw = gD * Delta.g;
  gw.head<4>() += gy;
  const Eigen::Matrix<double, 8, 8> Hw = Dw.transpose() * Hy * Dw + gD * Delta.H;
  // w = Bw q, a linear function of the element DOFs: a_0 = sum_j R_j'(xi_k) x_j, beta_0 =
  // alpha_k, a_1 = sum_j R_j'(xi_k+1) x_j, beta_1 = alpha_k+1. A Bw for a matrix A of 8 columns:
  auto times_Bw = [&](const auto& A) {
    Eigen::Matrix<double, std::decay_t<decltype(A)>::RowsAtCompileTime, N> r;
    for (int j = 0; j < np; ++j)
      for (int c = 0; c < 3; ++c)
        r.col(3 * j + c) = el.dN_lo[static_cast<std::size_t>(j)] * A.col(c) +
                           el.dN_hi[static_cast<std::size_t>(j)] * A.col(4 + c);
    r.col(3 * np) = A.col(3);
    r.col(3 * np + 1) = A.col(7);
    return r;
  };
  f += times_Bw(gw.transpose()).transpose();
  const Eigen::Matrix<double, N, 8> XD = X.lazyProduct(Dw);
  const Eigen::Matrix<double, N, N> XB = times_Bw(XD);
  K += XB + XB.transpose();
  const Eigen::Matrix<double, N, 8> HB = times_Bw(Hw).transpose();  // (Hw Bw)^T
  K += times_Bw(HB);
  f_out = f;
  K_out = K;
  return W;
}

double TwistingRod::tangent(int e, std::span<const Vector3d> x, std::span<const double> alpha,
                            const std::vector<Triad>& triads, Eigen::VectorXd& f,
                            Eigen::MatrixXd& K, const NodalFrame* F0, const NodalFrame* F1) const {
  NodalFrame L, R;
  if (!F0) nodal_frame(e, x, alpha, triads, L);
  if (!F1) nodal_frame(e + 1, x, alpha, triads, R);
  const NodalFrame& A = F0 ? *F0 : L;
  const NodalFrame& B = F1 ? *F1 : R;
  switch (degree()) {
    case 2:
      return fast_tangent<2>(e, x, A, B, f, K);
    case 3:
      return fast_tangent<3>(e, x, A, B, f, K);
    case 4:
      return fast_tangent<4>(e, x, A, B, f, K);
    default:
      return fast_tangent<5>(e, x, A, B, f, K);
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
  Eigen::MatrixXd Ke;
  tangent(e, x, alpha, committed_, f, Ke);
  if (K) *K = std::move(Ke);
}

void TwistingRod::element_tangent_by_jets(int e, std::span<const Vector3d> x,
                                          std::span<const double> alpha, Eigen::VectorXd& f,
                                          Eigen::MatrixXd& K) const {
  check(x, alpha);
  Eval ev;
  ev.derivatives = true;
  evaluate(e, x, alpha, committed_, ev);
  f = ev.f;
  K = ev.K;
}

void TwistingRod::assemble(std::span<const Vector3d> x, std::span<const double> alpha,
                           Eigen::VectorXd& f, std::vector<Triplet>* K) const {
  check(x, alpha);
  // Elements in parallel (OpenMP), each into its own Eval; summed and emitted in element order
  // by one thread, so f and K are the same bit for bit for any number of threads.
  const int nel = num_elements();
  const int ne = 3 * (degree() + 1) + 2;
  std::vector<Eval> evs(static_cast<std::size_t>(nel));
  std::vector<NodalFrame> frames(static_cast<std::size_t>(nel + 1));  // shared by neighbours
#pragma omp parallel if (nel >= kParallelTwistingRodElements)
  {
#pragma omp for schedule(static)
    for (int k = 0; k <= nel; ++k)
      nodal_frame(k, x, alpha, committed_, frames[static_cast<std::size_t>(k)]);
#pragma omp for schedule(static)
    for (int e = 0; e < nel; ++e) {
      Eval& ev = evs[static_cast<std::size_t>(e)];
      ev.W = tangent(e, x, alpha, committed_, ev.f, ev.K, &frames[static_cast<std::size_t>(e)],
                     &frames[static_cast<std::size_t>(e + 1)]);
    }
  }
  f.setZero(num_dofs());
  std::vector<int> dofs(static_cast<std::size_t>(ne));
  for (int e = 0; e < nel; ++e) {
    const Eval& ev = evs[static_cast<std::size_t>(e)];
    for (int i = 0; i < ne; ++i) dofs[static_cast<std::size_t>(i)] = global_dof(e, i);
    for (int i = 0; i < ne; ++i) f[dofs[static_cast<std::size_t>(i)]] += ev.f[i];
    if (K)
      for (int j = 0; j < ne; ++j)  // K is column-major
        for (int i = 0; i < ne; ++i)
          if (ev.K(i, j) != 0.0)
            K->emplace_back(dofs[static_cast<std::size_t>(i)], dofs[static_cast<std::size_t>(j)],
                            ev.K(i, j));
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

SectionSpin TwistingRod::spin_since_by_jets(double xi, const Vector3d& t_c, const Vector3d& d1_c,
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

template <typename T>
T TwistingRod::spin_at(int e, double xi, const RationalBasis& B, const Vector3d& t_c,
                       const Vector3d& d1_c, std::span<const Vector3d> x, const NodalFrame& NF0,
                       const NodalFrame& NF1, Vector3d& t_out, Vector3d& d1_out) const {
  // As kernel() with xi and spin_from, the frame at xi from the knots' frames:
  // g = SR(t_0 -> t) d1_0, d1 = cos phi g + sin phi t x g, the spin the angle about t from
  // SR(t_c -> t) d1_c to d1.
  using std::atan2;
  using std::cos;
  using std::sin;
  using std::sqrt;
  using V = std::array<T, 3>;
  using Num = SpinNumber<T>;
  const Element& el = elements_[static_cast<std::size_t>(e)];
  const double h = el.range.hi - el.range.lo;
  Vector3d av = Vector3d::Zero();
  for (int j = 0; j <= degree(); ++j)
    av += basis_value(B.dN, B, el.first + j) * x[static_cast<std::size_t>(el.first + j)];
  V a, t0, d10;
  for (std::size_t c = 0; c < 3; ++c) {
    a[c] = Num::var(av[static_cast<int>(c)], static_cast<int>(c));
    t0[c] = Num::lift(NF0.F[2].c[c]);
    d10[c] = Num::lift(NF0.F[0].c[c]);
  }
  const T Delta = Num::lift(relative_twist(NF0.F, NF1.F, el.Delta));
  const auto dot = [](const V& u, const V& v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const auto dotc = [](const V& u, const Vector3d& v) {
    return v[0] * u[0] + v[1] * u[1] + v[2] * u[2];
  };
  const auto cross = [](const V& u, const V& v) {
    return V{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  };
  const T il = inverse(sqrt(dot(a, a)));
  V t;
  for (std::size_t c = 0; c < 3; ++c) t[c] = il * a[c];
  const T w = dot(t, d10) * inverse(1.0 + dot(t0, t));
  V g;
  for (std::size_t c = 0; c < 3; ++c) g[c] = d10[c] - w * (t0[c] + t[c]);
  const V hv = cross(t, g);
  const T phi = ((xi - el.range.lo) / h) * Delta;
  const T cphi = cos(phi), sphi = sin(phi);
  V d1;
  for (std::size_t c = 0; c < 3; ++c) d1[c] = cphi * g[c] + sphi * hv[c];
  const T wc = dotc(t, d1_c) * inverse(1.0 + dotc(t, t_c));
  V m;
  for (std::size_t c = 0; c < 3; ++c)
    m[c] = d1_c[static_cast<int>(c)] - wc * (t_c[static_cast<int>(c)] + t[c]);
  for (int c = 0; c < 3; ++c) {
    t_out[c] = value_of(t[static_cast<std::size_t>(c)]);
    d1_out[c] = value_of(d1[static_cast<std::size_t>(c)]);
  }
  return atan2(dot(cross(m, d1), t), dot(m, d1));
}

SectionSpin TwistingRod::spin_since(double xi, const Vector3d& t_c, const Vector3d& d1_c,
                                    std::span<const Vector3d> x, std::span<const double> alpha,
                                    bool derivatives) const {
  check(x, alpha);
  const int e = element_at(xi);
  NodalFrame F0, F1;
  nodal_frame(e, x, alpha, committed_, F0);
  nodal_frame(e + 1, x, alpha, committed_, F1);
  const int np = degree() + 1, ne = 3 * np + 2;
  SectionSpin sp;
  sp.positions = 3 * np;
  sp.dofs.resize(static_cast<std::size_t>(ne));
  for (int l = 0; l < ne; ++l) sp.dofs[static_cast<std::size_t>(l)] = global_dof(e, l);
  // at an inner right end, the element's left limit (as kernel())
  const Element& el = elements_[static_cast<std::size_t>(e)];
  const double h = el.range.hi - el.range.lo;
  const double xc = std::min(xi, el.range.hi - (e + 1 < num_elements() ? 1e-12 * h : 0.0));
  const RationalBasis B = rational_basis(reference_, xc);
  if (!derivatives) {
    sp.value = spin_at<double>(e, xc, B, t_c, d1_c, x, F0, F1, sp.t, sp.d1);
    return sp;
  }
  const Jet<11> s = spin_at<Jet<11>>(e, xc, B, t_c, d1_c, x, F0, F1, sp.t, sp.d1);
  sp.value = s.v;
  // (a, y_0, y_1) = L q: a = sum_j R_j'(xi) x_j, a_k = sum_j R_j'(xi_k) x_j, beta_k = alpha_k
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(11, ne);
  for (int j = 0; j < np; ++j)
    for (int c = 0; c < 3; ++c) {
      L(c, 3 * j + c) = basis_value(B.dN, B, el.first + j);
      L(3 + c, 3 * j + c) = el.dN_lo[static_cast<std::size_t>(j)];
      L(7 + c, 3 * j + c) = el.dN_hi[static_cast<std::size_t>(j)];
    }
  L(6, 3 * np) = 1.0;
  L(10, 3 * np + 1) = 1.0;
  sp.gradient = L.transpose() * s.g;
  sp.hessian = L.transpose() * s.H * L;
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
  add_moment_terms(x, s, t, g, K);
}

bool TwistingRodProblem::add_load_terms(std::span<const Vector3d> x, std::span<const double> s,
                                        double t, VectorXd& g) const {
  add_moment_terms(x, s, t, g, nullptr);
  return true;
}

void TwistingRodProblem::add_moment_terms(std::span<const Vector3d> x, std::span<const double> s,
                                          double t, VectorXd& g, std::vector<Triplet>* K) const {
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
