// Sound bounds over rational Bezier patches (see patch_bounds.hpp).
#include "contact/patch_bounds.hpp"

#include <limits>
#include <tuple>
#include <type_traits>
#include <vector>

namespace iga::detail {

namespace {

// Component-wise hull of 4-vectors.
struct Hull4 {
  Vector4d lo = Vector4d::Constant(std::numeric_limits<double>::infinity());
  Vector4d hi = Vector4d::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vector4d& q) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  // An empty hull (a derivative of order above the degree) is the zero interval.
  IVec3 xyz() const {
    if (lo[0] > hi[0]) return {};
    return {{{lo[0], hi[0]}, {lo[1], hi[1]}, {lo[2], hi[2]}}};
  }
  Iv w() const { return lo[3] > hi[3] ? Iv{} : Iv{lo[3], hi[3]}; }
};

IVec3 sub(const IVec3& a, const IVec3& b) {
  return {{a.c[0] - b.c[0], a.c[1] - b.c[1], a.c[2] - b.c[2]}};
}
IVec3 mul(Iv s, const IVec3& a) {
  return {{s * a.c[0], s * a.c[1], s * a.c[2]}};
}
IVec3 div_pos(const IVec3& a, Iv w) {
  return {{div_pos(a.c[0], w), div_pos(a.c[1], w), div_pos(a.c[2], w)}};
}

// A polynomial in Bernstein form of degree (m, n) on the patch's range, coefficients u fastest
// (T: double or Vector3d): the numerators and denominators of the rational patch's derivatives.
template <class T>
struct Poly {
  int m = 0, n = 0;
  std::vector<T> c;
  const T& at(int i, int j) const { return c[static_cast<std::size_t>(i + (m + 1) * j)]; }
  T& at(int i, int j) { return c[static_cast<std::size_t>(i + (m + 1) * j)]; }
};
template <class T>
T zero() {
  if constexpr (std::is_same_v<T, double>)
    return 0.0;
  else
    return T::Zero();
}
template <class T>
Poly<T> make_poly(int m, int n) {
  Poly<T> f;
  f.m = m;
  f.n = n;
  f.c.assign(static_cast<std::size_t>((m + 1) * (n + 1)), zero<T>());
  return f;
}
// Binomial coefficients C(n, k) for n < 32 (degrees up to 3 kMaxHighNetDegree).
static_assert(3 * kMaxHighNetDegree < 32);
struct Binomials {
  double c[32][32] = {};
  constexpr Binomials() {
    for (int n = 0; n < 32; ++n) {
      c[n][0] = 1.0;
      for (int k = 1; k <= n; ++k) c[n][k] = c[n - 1][k - 1] + (k < n ? c[n - 1][k] : 0.0);
    }
  }
};
constexpr Binomials kBinomials;
double binom(int n, int k) {
  return kBinomials.c[n][k];
}
// d/du (dir 0) or d/dv (dir 1), `scale` = 1 / (width of the range in that direction)
template <class T>
Poly<T> derivative(const Poly<T>& f, int dir, double scale) {
  const int m = dir == 0 ? f.m - 1 : f.m, n = dir == 0 ? f.n : f.n - 1;
  Poly<T> g = make_poly<T>(std::max(m, 0), std::max(n, 0));
  if (m < 0 || n < 0) return g;  // a constant's derivative: zero
  const double k = (dir == 0 ? f.m : f.n) * scale;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= m; ++i)
      g.at(i, j) = k * (dir == 0 ? f.at(i + 1, j) - f.at(i, j) : f.at(i, j + 1) - f.at(i, j));
  return g;
}
template <class T>
Poly<T> elevate(Poly<T> f, int m, int n) {
  while (f.m < m) {
    Poly<T> g = make_poly<T>(f.m + 1, f.n);
    for (int j = 0; j <= f.n; ++j)
      for (int i = 0; i <= g.m; ++i) {
        const double a = static_cast<double>(i) / g.m;
        g.at(i, j) = (i > 0 ? T(a * f.at(i - 1, j)) : zero<T>()) +
                     (i < g.m ? T((1.0 - a) * f.at(i, j)) : zero<T>());
      }
    f = std::move(g);
  }
  while (f.n < n) {
    Poly<T> g = make_poly<T>(f.m, f.n + 1);
    for (int j = 0; j <= g.n; ++j)
      for (int i = 0; i <= f.m; ++i) {
        const double a = static_cast<double>(j) / g.n;
        g.at(i, j) = (j > 0 ? T(a * f.at(i, j - 1)) : zero<T>()) +
                     (j < g.n ? T((1.0 - a) * f.at(i, j)) : zero<T>());
      }
    f = std::move(g);
  }
  return f;
}
// The product in Bernstein form: with the scaled coefficients C(m, i) C(n, j) c_ij of each
// factor, the product's scaled coefficients are the plain 2-D convolution of the factors'.
template <class T>
Poly<T> times(const Poly<T>& f, const Poly<double>& g) {
  Poly<T> h = make_poly<T>(f.m + g.m, f.n + g.n);
  thread_local std::vector<T> fs;
  thread_local std::vector<double> gs;
  fs.resize(f.c.size());
  gs.resize(g.c.size());
  for (int j = 0; j <= f.n; ++j)
    for (int i = 0; i <= f.m; ++i)
      fs[static_cast<std::size_t>(i + (f.m + 1) * j)] =
          (binom(f.m, i) * binom(f.n, j)) * f.at(i, j);
  for (int j = 0; j <= g.n; ++j)
    for (int i = 0; i <= g.m; ++i)
      gs[static_cast<std::size_t>(i + (g.m + 1) * j)] = binom(g.m, i) * binom(g.n, j) * g.at(i, j);
  for (int d = 0; d <= g.n; ++d)
    for (int c = 0; c <= f.n; ++c) {
      const T* fr = &fs[static_cast<std::size_t>((f.m + 1) * c)];
      for (int b = 0; b <= g.m; ++b) {
        const double gb = gs[static_cast<std::size_t>(b + (g.m + 1) * d)];
        T* hr = &h.at(b, c + d);
        for (int a = 0; a <= f.m; ++a) hr[a] += gb * fr[a];
      }
    }
  for (int j = 0; j <= h.n; ++j)
    for (int i = 0; i <= h.m; ++i) h.at(i, j) /= binom(h.m, i) * binom(h.n, j);
  return h;
}
template <class T>
Poly<T> minus(const Poly<T>& f, const Poly<T>& g) {
  const int m = std::max(f.m, g.m), n = std::max(f.n, g.n);
  Poly<T> a = elevate(f, m, n);
  const Poly<T> b = elevate(g, m, n);
  for (std::size_t k = 0; k < a.c.size(); ++k) a.c[k] = a.c[k] - b.c[k];
  return a;
}
// The box of N / D over the patch from the rational convex hull property (D's coefficients
// positive): N / D lies in the hull of the ratios of their coefficients in one basis.
IVec3 ratio_box(const Poly<Vector3d>& N, const Poly<double>& D) {
  const int m = std::max(N.m, D.m), n = std::max(N.n, D.n);
  const Poly<Vector3d> a = elevate(N, m, n);
  const Poly<double> b = elevate(D, m, n);
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t k = 0; k < a.c.size(); ++k) {
    const Vector3d q = a.c[k] / b.c[k];
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  return {{{lo[0], hi[0]}, {lo[1], hi[1]}, {lo[2], hi[2]}}};
}
IVec3 meet3(const IVec3& a, const IVec3& b) {
  IVec3 r;
  for (int k = 0; k < 3; ++k)
    r.c[k] = {std::max(a.c[k].lo, b.c[k].lo), std::min(a.c[k].hi, b.c[k].hi)};
  return r;
}

}  // namespace

template <int D>
bool to_net(const BezierPatch& b, NetOf<D>& out) {
  if (b.degree_u > D || b.degree_v > D) return false;
  out.range = b.range;
  out.p = b.degree_u;
  out.q = b.degree_v;
  std::copy(b.pw.begin(), b.pw.end(), out.pw.begin());
  return true;
}

Eigen::Matrix3d tangent_frame(const SurfaceDerivs& d) {
  const Vector3d n = d.Su.cross(d.Sv);
  if (!(d.Su.norm() > 0.0) || !(n.norm() > 0.0) || !n.allFinite())
    return Eigen::Matrix3d::Identity();
  Eigen::Matrix3d R;
  R.row(0) = d.Su.normalized();
  R.row(2) = n.normalized();
  R.row(1) = R.row(2).cross(R.row(0));
  return R;
}

PatchBounds patch_bounds(const BezierPatch& b, const Eigen::Matrix3d& frame) {
  return patch_bounds(b.pw.data(), b.degree_u, b.degree_v, b.range, frame);
}

namespace {

// patch_bounds; `rational`: false skips the products of the rational derivatives' numerators
// and denominators (patch_bounds_within, which meets the result with the whole patch's bounds).
PatchBounds bounds_of(const Vector4d* pw, int p, int q, const Domain2& range,
                      const Eigen::Matrix3d& frame, bool rational) {
  PatchBounds out;
  out.frame = frame;
  const std::size_t n = static_cast<std::size_t>((p + 1) * (q + 1));
  Box3 box;
  for (std::size_t k = 0; k < n; ++k) box.extend(pw[k].head<3>() / pw[k].w());
  const Vector3d c = 0.5 * (box.lo + box.hi);
  out.centre = c;
  const double du = range.u.hi - range.u.lo, dv = range.v.hi - range.v.lo;
  // Homogeneous control points of the patch moved by -centre and turned: (R (A - w c), w).
  thread_local std::vector<Vector4d> moved;
  moved.resize(n);
  Iv w{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k < n; ++k) {
    moved[k].head<3>() = frame * (pw[k].head<3>() - pw[k].w() * c);
    moved[k].w() = pw[k].w();
    w.lo = std::min(w.lo, pw[k].w());
    w.hi = std::max(w.hi, pw[k].w());
  }
  auto P = [&](int i, int j) -> const Vector4d& {
    return moved[static_cast<std::size_t>(i + (p + 1) * j)];
  };
  Hull4 Au, Av, Auu, Auv, Avv;
  const double su = p / du, sv = q / dv, suu = p * (p - 1) / (du * du),
               svv = q * (q - 1) / (dv * dv), suv = p * q / (du * dv);
  for (int j = 0; j <= q; ++j)
    for (int i = 0; i <= p; ++i) {
      const Vector4d& h = P(i, j);
      if (i < p) {
        const Vector4d d = P(i + 1, j) - h;
        Au.add(su * d);
        if (i + 1 < p) Auu.add(suu * (P(i + 2, j) - P(i + 1, j) - d));
        if (j < q) Auv.add(suv * (P(i + 1, j + 1) - P(i, j + 1) - d));
      }
      if (j < q) {
        const Vector4d d = P(i, j + 1) - h;
        Av.add(sv * d);
        if (j + 1 < q) Avv.add(svv * (P(i, j + 2) - P(i, j + 1) - d));
      }
    }
  Box3 sbox;
  for (std::size_t k = 0; k < n; ++k) sbox.extend(moved[k].head<3>() / moved[k].w());
  out.S = to_ivec(sbox);
  // A = w S differentiated (Leibniz), solved for the derivatives of S.
  out.Su = div_pos(sub(Au.xyz(), mul(Au.w(), out.S)), w);
  out.Sv = div_pos(sub(Av.xyz(), mul(Av.w(), out.S)), w);
  out.Suu = div_pos(sub(sub(Auu.xyz(), mul(2.0 * Au.w(), out.Su)), mul(Auu.w(), out.S)), w);
  out.Svv = div_pos(sub(sub(Avv.xyz(), mul(2.0 * Av.w(), out.Sv)), mul(Avv.w(), out.S)), w);
  out.Suv = div_pos(
      sub(sub(sub(Auv.xyz(), mul(Au.w(), out.Sv)), mul(Av.w(), out.Su)), mul(Auv.w(), out.S)), w);
  if (rational && w.lo < w.hi) {
    // Rational: the interval quotient rule above ignores that S, its derivatives and w move
    // together, and is loose. The derivatives as rational Bezier functions instead, with the
    // denominators w^2 and w^3 (positive coefficients):
    //   S_u = (A_u w - A w_u) / w^2 = N_u / w^2,
    //   S_uu = (N_u,u w - 2 N_u w_u) / w^3, S_uv = (N_u,v w - 2 N_u w_v) / w^3, and alike in v.
    Poly<Vector3d> A = make_poly<Vector3d>(p, q);
    Poly<double> W = make_poly<double>(p, q);
    for (int j = 0; j <= q; ++j)
      for (int i = 0; i <= p; ++i) {
        A.at(i, j) = P(i, j).head<3>();
        W.at(i, j) = P(i, j).w();
      }
    const double iu = 1.0 / du, iv = 1.0 / dv;
    const Poly<double> Wu = derivative(W, 0, iu), Wv = derivative(W, 1, iv);
    const Poly<Vector3d> Nu = minus(times(derivative(A, 0, iu), W), times(A, Wu));
    const Poly<Vector3d> Nv = minus(times(derivative(A, 1, iv), W), times(A, Wv));
    const Poly<double> W2 = times(W, W), W3 = times(W2, W);
    Poly<double> Wu2 = Wu, Wv2 = Wv;  // 2 w_u, 2 w_v
    for (double& k : Wu2.c) k *= 2.0;
    for (double& k : Wv2.c) k *= 2.0;
    out.Su = meet3(out.Su, ratio_box(Nu, W2));
    out.Sv = meet3(out.Sv, ratio_box(Nv, W2));
    out.Suu = meet3(out.Suu, ratio_box(minus(times(derivative(Nu, 0, iu), W), times(Nu, Wu2)), W3));
    out.Suv = meet3(out.Suv, ratio_box(minus(times(derivative(Nu, 1, iv), W), times(Nu, Wv2)), W3));
    out.Svv = meet3(out.Svv, ratio_box(minus(times(derivative(Nv, 1, iv), W), times(Nv, Wv2)), W3));
  }
  return out;
}

}  // namespace

PatchBounds patch_bounds(const Vector4d* pw, int p, int q, const Domain2& range,
                         const Eigen::Matrix3d& frame) {
  return bounds_of(pw, p, q, range, frame, true);
}

PatchBounds patch_bounds_within(const Vector4d* pw, int p, int q, const Domain2& range,
                                const PatchBounds& whole) {
  PatchBounds out = bounds_of(pw, p, q, range, whole.frame, false);
  out.Su = meet3(out.Su, whole.Su);
  out.Sv = meet3(out.Sv, whole.Sv);
  out.Suu = meet3(out.Suu, whole.Suu);
  out.Suv = meet3(out.Suv, whole.Suv);
  out.Svv = meet3(out.Svv, whole.Svv);
  return out;
}

void unite(PatchBounds& a, const PatchBounds& b) {
  auto hull = [](IVec3& u, const IVec3& v, const Vector3d& shift) {
    for (int k = 0; k < 3; ++k)
      u.c[k] = {std::min(u.c[k].lo, v.c[k].lo + shift[k]),
                std::max(u.c[k].hi, v.c[k].hi + shift[k])};
  };
  hull(a.S, b.S, a.frame * (b.centre - a.centre));  // b's points in a's coordinates
  const Vector3d none = Vector3d::Zero();
  hull(a.Su, b.Su, none);
  hull(a.Sv, b.Sv, none);
  hull(a.Suu, b.Suu, none);
  hull(a.Suv, b.Suv, none);
  hull(a.Svv, b.Svv, none);
}

namespace {
Iv meet(Iv a, Iv b) {
  return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)};
}
}  // namespace

double refine_about_centre(DistanceBounds& d, const SurfaceDerivs& dc, const Vector3d& x, double a,
                           double bw) {
  const Vector3d rc = x - dc.S;
  const double gu = -dc.Su.dot(rc), gv = -dc.Sv.dot(rc);  // (16) at c
  const Iv A{-a, a}, B{-bw, bw};
  d.gu = meet(d.gu, Iv{gu, gu} + d.H11 * A + d.H12 * B);
  d.gv = meet(d.gv, Iv{gv, gv} + d.H12 * A + d.H22 * B);
  // F(c + t) >= F(c) + g.t + 1/2 (H11 tu^2 + 2 H12 tu tv + H22 tv^2) over the box
  const double h12max = std::max(std::abs(d.H12.lo), std::abs(d.H12.hi));
  return 0.5 * rc.squaredNorm() - std::abs(gu) * a - std::abs(gv) * bw +
         0.5 * (std::min(0.0, d.H11.lo) * a * a + std::min(0.0, d.H22.lo) * bw * bw) -
         h12max * a * bw;
}

namespace {

// sigma_min of the tangential block [[S_u.e1, S_v.e1], [S_u.e2, S_v.e2]] over the patch, from
// below: the centre's sigma_min less the radius' Frobenius norm (Weyl).
double jacobian_floor(const PatchBounds& b) {
  Eigen::Matrix2d K0, E;
  const IVec3* col[2] = {&b.Su, &b.Sv};
  for (int j = 0; j < 2; ++j)
    for (int k = 0; k < 2; ++k) {
      const Iv& c = col[j]->c[k];
      K0(k, j) = 0.5 * (c.lo + c.hi);
      E(k, j) = 0.5 * (c.hi - c.lo);
    }
  const double T = K0.squaredNorm(), D = std::abs(K0.determinant());
  const double disc = std::sqrt(std::max(0.0, 0.25 * T * T - D * D));
  const double s_min2 = std::max(0.0, 0.5 * T - disc);  // smaller eigenvalue of K0^T K0
  // the same eigenvalue as D^2 / larger one: better conditioned when it is small
  const double s_max2 = 0.5 * T + disc;
  const double s_min = s_max2 > 0.0 ? std::max(std::sqrt(s_min2), D / std::sqrt(s_max2)) : 0.0;
  return std::max(0.0, s_min - E.norm());
}

// Upper bound of the largest eigenvalue of a symmetric matrix with interval entries.
double lambda_max_upper(Iv a11, Iv a12, Iv a22) {
  const double m12 = std::max(std::abs(a12.lo), std::abs(a12.hi));
  return std::max(a11.hi, a22.hi) + m12;
}

bool weyl_test(const PatchBounds& b, const IVec3& r) {
  const double sigma = jacobian_floor(b);
  const double lam = lambda_max_upper(dot(b.Suu, r), dot(b.Suv, r), dot(b.Svv, r));
  return sigma * sigma > lam * (1.0 + 1e-9) + 1e-300;
}

}  // namespace

bool convex_weyl(const PatchBounds& b, const Vector3d& x) {
  const Vector3d xc = b.frame * (x - b.centre);
  IVec3 r;  // x - S
  for (int k = 0; k < 3; ++k) r.c[k] = Iv{xc[k] - b.S.c[k].hi, xc[k] - b.S.c[k].lo};
  return weyl_test(b, r);
}

namespace {
// a . r for a point r: the same as dot(a, point(r)), with one product per bound.
Iv dot_point(const IVec3& a, const Vector3d& r) {
  return r[0] * a.c[0] + r[1] * a.c[1] + r[2] * a.c[2];
}

// The chord test from its parts; sigma() (the Jacobian floor) only where the Gram test fails.
template <class Sigma>
bool chord_test_of(const Eigen::Matrix3d& frame, const IVec3& Suu, const IVec3& Suv,
                   const IVec3& Svv, Iv G11, Iv G22, Iv G12, Sigma&& sigma,
                   const Vector3d& r_star) {
  const Vector3d r = frame * r_star;
  const Iv puu = dot_point(Suu, r), puv = dot_point(Suv, r), pvv = dot_point(Svv, r);
  DistanceBounds m;
  m.H11 = G11 - puu;
  m.H22 = G22 - pvv;
  m.H12 = G12 - puv;
  if (convex_gram(m)) return true;
  const double s = sigma();  // weyl_test
  return s * s > lambda_max_upper(puu, puv, pvv) * (1.0 + 1e-9) + 1e-300;
}
}  // namespace

bool chord_test(const PatchBounds& b, const Vector3d& r_star) {
  return chord_test_of(
      b.frame, b.Suu, b.Suv, b.Svv, norm2(b.Su), norm2(b.Sv), dot(b.Su, b.Sv),
      [&] { return jacobian_floor(b); }, r_star);
}

ChordData chord_data(const PatchBounds& b) {
  ChordData c;
  c.frame = b.frame;
  c.Suu = b.Suu;
  c.Suv = b.Suv;
  c.Svv = b.Svv;
  c.G11 = norm2(b.Su);
  c.G22 = norm2(b.Sv);
  c.G12 = dot(b.Su, b.Sv);
  c.sigma = jacobian_floor(b);
  return c;
}

bool chord_test(const ChordData& c, const Vector3d& r_star) {
  return chord_test_of(
      c.frame, c.Suu, c.Suv, c.Svv, c.G11, c.G22, c.G12, [&] { return c.sigma; }, r_star);
}

DistanceBounds distance_bounds(const PatchBounds& b, const Vector3d& x) {
  const Vector3d xc = b.frame * (x - b.centre);
  IVec3 r;  // x - S
  for (int k = 0; k < 3; ++k) r.c[k] = Iv{xc[k] - b.S.c[k].hi, xc[k] - b.S.c[k].lo};
  DistanceBounds d;
  const Iv su_r = dot(b.Su, r), sv_r = dot(b.Sv, r);
  d.gu = Iv{-su_r.hi, -su_r.lo};  // (16)
  d.gv = Iv{-sv_r.hi, -sv_r.lo};
  d.H11 = norm2(b.Su) - dot(b.Suu, r);  // (17)
  d.H22 = norm2(b.Sv) - dot(b.Svv, r);
  d.H12 = dot(b.Su, b.Sv) - dot(b.Suv, r);
  return d;
}

template <int D>
void split_at(const NetOf<D>& b, int dir, double t, NetOf<D>& low, NetOf<D>& high) {
  low.p = high.p = b.p;
  low.q = high.q = b.q;
  low.range = high.range = b.range;
  const int p = b.p;
  const int n = dir == 0 ? b.p : b.q;  // degree along the split
  const int rows = dir == 0 ? b.q + 1 : b.p + 1;
  const Interval whole = dir == 0 ? b.range.u : b.range.v;
  const double s = (t - whole.lo) / (whole.hi - whole.lo);  // local parameter in [0, 1]
  auto at = [&](int k, int row) {  // index of point k along the split direction in a row
    return static_cast<std::size_t>(dir == 0 ? k + (p + 1) * row : row + (p + 1) * k);
  };
  std::array<Vector4d, D + 1> tri;
  for (int row = 0; row < rows; ++row) {
    for (int k = 0; k <= n; ++k) tri[static_cast<std::size_t>(k)] = b.pw[at(k, row)];
    low.pw[at(0, row)] = tri[0];
    high.pw[at(n, row)] = tri[static_cast<std::size_t>(n)];
    for (int level = 1; level <= n; ++level) {
      for (int k = 0; k <= n - level; ++k)
        tri[static_cast<std::size_t>(k)] =
            (1.0 - s) * tri[static_cast<std::size_t>(k)] + s * tri[static_cast<std::size_t>(k + 1)];
      low.pw[at(level, row)] = tri[0];
      high.pw[at(n - level, row)] = tri[static_cast<std::size_t>(n - level)];
    }
  }
  Interval& lo_range = dir == 0 ? low.range.u : low.range.v;
  Interval& hi_range = dir == 0 ? high.range.u : high.range.v;
  lo_range.hi = t;
  hi_range.lo = t;
}

template <int D>
void split_half(const NetOf<D>& b, int dir, NetOf<D>& low, NetOf<D>& high) {
  const Interval whole = dir == 0 ? b.range.u : b.range.v;
  split_at(b, dir, 0.5 * (whole.lo + whole.hi), low, high);
}

template bool to_net(const BezierPatch&, Net&);
template bool to_net(const BezierPatch&, HighNet&);
template void split_at(const Net&, int, double, Net&, Net&);
template void split_at(const HighNet&, int, double, HighNet&, HighNet&);
template void split_half(const Net&, int, Net&, Net&);
template void split_half(const HighNet&, int, HighNet&, HighNet&);

}  // namespace iga::detail
