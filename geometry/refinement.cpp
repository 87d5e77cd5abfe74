// Knot refinement ([PT97] A5.4; A5.1 is its single-knot case), degree elevation (exact
// representation in the elevated space, [PT97] Sect. 5.5) and Bezier extraction (A5.6's result
// obtained by refinement). One kernel per operation works on the rows of a matrix whose columns
// are independent homogeneous coordinates, so curves and both directions of a surface share it.
#include "geometry/refinement.hpp"

#include <algorithm>
#include <string>

#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

namespace iga {

namespace {

using RowNet = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Refined {
  std::vector<double> U;
  RowNet Q;
};

// A5.4 (p. 164) on the rows of P (n+1 rows); X non-decreasing, strictly inside the domain or at
// interior knots.
Refined refine_rows(int p, const std::vector<double>& U, const RowNet& P,
                    std::span<const double> X) {
  const int n = static_cast<int>(P.rows()) - 1;
  const int m = n + p + 1;
  const int r = static_cast<int>(X.size()) - 1;
  if (r < 0) return {U, P};
  const double lo = U[p], hi = U[m - p];
  for (int j = 0; j <= r; ++j) {
    if (!(X[j] > lo && X[j] < hi))
      throw GeometryError("knot to insert " + std::to_string(X[j]) +
                          " is outside the open domain (" + std::to_string(lo) + ", " +
                          std::to_string(hi) + ")");
    if (j > 0 && X[j] < X[j - 1]) throw GeometryError("knots to insert must be non-decreasing");
  }
  const int a = find_span(n + 1, p, X[0], U);
  const int b = find_span(n + 1, p, X[r], U) + 1;
  Refined out;
  out.U.assign(static_cast<std::size_t>(m + r + 2), 0.0);
  out.Q.resize(n + r + 2, P.cols());
  std::vector<double>& Ub = out.U;
  RowNet& Q = out.Q;
  for (int j = 0; j <= a - p; ++j) Q.row(j) = P.row(j);
  for (int j = b - 1; j <= n; ++j) Q.row(j + r + 1) = P.row(j);
  for (int j = 0; j <= a; ++j) Ub[j] = U[j];
  for (int j = b + p; j <= m; ++j) Ub[j + r + 1] = U[j];
  int i = b + p - 1, k = b + p + r;
  for (int j = r; j >= 0; --j) {
    while (X[j] <= U[i] && i > a) {
      Q.row(k - p - 1) = P.row(i - p - 1);
      Ub[k] = U[i];
      --k;
      --i;
    }
    Q.row(k - p - 1) = Q.row(k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alfa = Ub[k + l] - X[j];
      if (alfa == 0.0) {
        Q.row(ind - 1) = Q.row(ind);
      } else {
        alfa /= (Ub[k + l] - U[i - p + l]);
        Q.row(ind - 1) = alfa * Q.row(ind - 1) + (1.0 - alfa) * Q.row(ind);
      }
    }
    Ub[k] = X[j];
    --k;
  }
  return out;
}

// Collocation matrix B(r, c) = N_c(x_r) of a knot vector: p + 1 entries a row, stored sparse
// so that elevating a curve of many elements stays O(n).
Eigen::SparseMatrix<double> collocation(int p, const std::vector<double>& U,
                                        const std::vector<double>& x) {
  const int n = static_cast<int>(U.size()) - p - 1;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(x.size() * static_cast<std::size_t>(p + 1));
  BasisValues N;
  for (std::size_t r = 0; r < x.size(); ++r) {
    const int span = find_span(n, p, x[r], U);
    basis_funs(span, x[r], p, U, N);
    for (int j = 0; j <= p; ++j)
      if (N[static_cast<std::size_t>(j)] != 0.0)
        trip.emplace_back(static_cast<int>(r), span - p + j, N[static_cast<std::size_t>(j)]);
  }
  Eigen::SparseMatrix<double> B(static_cast<Eigen::Index>(x.size()), n);
  B.setFromTriplets(trip.begin(), trip.end());
  return B;
}

// Degree elevation by t: knots with each distinct value's multiplicity raised by t; control
// points from B_new(g) Q = B_old(g) P at the Greville abscissae g of the new knots.
Refined elevate_rows(int p, const std::vector<double>& U, const RowNet& P, int t) {
  if (t < 0) throw GeometryError("degree elevation needs t >= 0, got " + std::to_string(t));
  if (t == 0) return {U, P};
  if (p + t > kMaxDegree)
    throw GeometryError("elevated degree " + std::to_string(p + t) + " exceeds the maximum " +
                        std::to_string(kMaxDegree));
  Refined out;
  for (std::size_t i = 0; i < U.size();) {
    std::size_t j = i;
    while (j < U.size() && U[j] == U[i]) ++j;
    out.U.insert(out.U.end(), j - i + static_cast<std::size_t>(t), U[i]);
    i = j;
  }
  const KnotVector Knew(p + t, out.U);
  const std::vector<double> g = Knew.greville();
  const Eigen::SparseMatrix<double> Bnew = collocation(p + t, out.U, g);
  const Eigen::SparseMatrix<double> Bold = collocation(p, U, g);
  const Eigen::MatrixXd rhs = Bold * P;
  // Banded and totally positive (Schoenberg-Whitney holds at the Greville abscissae): sparse LU
  // in the natural order keeps the band.
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::NaturalOrdering<int>> lu(Bnew);
  if (lu.info() != Eigen::Success)
    throw GeometryError("degree elevation: the collocation matrix is singular");
  const Eigen::MatrixXd Q = lu.solve(rhs);
  out.Q = Q;
  return out;
}

RowNet curve_rows(const NurbsCurve& c) {
  RowNet M(c.num_control_points(), 4);
  for (int i = 0; i < c.num_control_points(); ++i)
    M.row(i) = c.homogeneous()[static_cast<std::size_t>(i)].transpose();
  return M;
}

std::vector<Vector4d> rows_to_points(const RowNet& M) {
  std::vector<Vector4d> pw(static_cast<std::size_t>(M.rows()));
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    pw[static_cast<std::size_t>(i)] = M.row(i).transpose();
  return pw;
}

// Surface nets as matrices: direction 0 (u) has one row per i and 4*n_v columns; direction 1
// (v) one row per j and 4*n_u columns.
RowNet surface_rows(const NurbsSurface& s, int dir) {
  const int nu = s.num_u(), nv = s.num_v();
  RowNet M(dir == 0 ? nu : nv, 4 * (dir == 0 ? nv : nu));
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const Vector4d& q = s.homogeneous()[static_cast<std::size_t>(s.index(i, j))];
      if (dir == 0)
        M.block<1, 4>(i, 4 * j) = q.transpose();
      else
        M.block<1, 4>(j, 4 * i) = q.transpose();
    }
  return M;
}

std::vector<Vector4d> surface_net(const RowNet& M, int dir) {
  const Eigen::Index nu = dir == 0 ? M.rows() : M.cols() / 4;
  const Eigen::Index nv = dir == 0 ? M.cols() / 4 : M.rows();
  std::vector<Vector4d> pw(static_cast<std::size_t>(nu * nv));
  for (Eigen::Index j = 0; j < nv; ++j)
    for (Eigen::Index i = 0; i < nu; ++i)
      pw[static_cast<std::size_t>(i + nu * j)] =
          (dir == 0 ? M.block<1, 4>(i, 4 * j) : M.block<1, 4>(j, 4 * i)).transpose();
  return pw;
}

// Applies a row operation in one direction of a surface.
template <class Op>
NurbsSurface surface_op(const NurbsSurface& s, int dir, Op op) {
  const KnotVector& K = dir == 0 ? s.knots_u() : s.knots_v();
  Refined r = op(K.degree(), K.knots(), surface_rows(s, dir));
  const int p_new = static_cast<int>(r.U.size()) - static_cast<int>(r.Q.rows()) - 1;
  KnotVector Knew(p_new, std::move(r.U));
  NurbsSurface out = dir == 0 ? NurbsSurface(Knew, s.knots_v(), surface_net(r.Q, 0))
                              : NurbsSurface(s.knots_u(), Knew, surface_net(r.Q, 1));
  out.set_normal_sign(s.normal_sign());
  return out;
}

// Knots to insert so that every interior knot reaches multiplicity p (Bezier extraction).
std::vector<double> bezier_knots(const KnotVector& K) {
  std::vector<double> X;
  const std::vector<double> br = K.breaks();
  for (std::size_t e = 1; e + 1 < br.size(); ++e)
    X.insert(X.end(), static_cast<std::size_t>(K.degree() - K.multiplicity(br[e])), br[e]);
  return X;
}

std::vector<double> subdivision_knots(const KnotVector& K, int parts) {
  if (parts < 1) throw GeometryError("subdivision needs parts >= 1, got " + std::to_string(parts));
  std::vector<double> X;
  const std::vector<double> br = K.breaks();
  for (std::size_t e = 0; e + 1 < br.size(); ++e)
    for (int k = 1; k < parts; ++k) X.push_back(br[e] + (br[e + 1] - br[e]) * k / parts);
  return X;
}

}  // namespace

NurbsCurve refine_knots(const NurbsCurve& c, std::span<const double> X) {
  Refined r = refine_rows(c.degree(), c.knots().knots(), curve_rows(c), X);
  return NurbsCurve(KnotVector(c.degree(), std::move(r.U)), rows_to_points(r.Q));
}

NurbsCurve insert_knot(const NurbsCurve& c, double u, int r) {
  // A5.1 inserts one value r times; it is A5.4 with X = {u, ..., u}.
  if (r < 1) throw GeometryError("knot insertion needs r >= 1, got " + std::to_string(r));
  const std::vector<double> X(static_cast<std::size_t>(r), u);
  return refine_knots(c, X);
}

NurbsSurface refine_knots(const NurbsSurface& s, std::span<const double> Xu,
                          std::span<const double> Xv) {
  NurbsSurface t = surface_op(s, 0, [&](int p, const std::vector<double>& U, const RowNet& P) {
    return refine_rows(p, U, P, Xu);
  });
  return surface_op(t, 1, [&](int p, const std::vector<double>& U, const RowNet& P) {
    return refine_rows(p, U, P, Xv);
  });
}

NurbsCurve subdivide(const NurbsCurve& c, int parts) {
  return refine_knots(c, subdivision_knots(c.knots(), parts));
}

NurbsSurface subdivide(const NurbsSurface& s, int parts_u, int parts_v) {
  return refine_knots(s, subdivision_knots(s.knots_u(), parts_u),
                      subdivision_knots(s.knots_v(), parts_v));
}

NurbsCurve elevate_degree(const NurbsCurve& c, int t) {
  Refined r = elevate_rows(c.degree(), c.knots().knots(), curve_rows(c), t);
  return NurbsCurve(KnotVector(c.degree() + t, std::move(r.U)), rows_to_points(r.Q));
}

NurbsSurface elevate_degree(const NurbsSurface& s, int tu, int tv) {
  NurbsSurface t = surface_op(s, 0, [&](int p, const std::vector<double>& U, const RowNet& P) {
    return elevate_rows(p, U, P, tu);
  });
  return surface_op(t, 1, [&](int p, const std::vector<double>& U, const RowNet& P) {
    return elevate_rows(p, U, P, tv);
  });
}

std::vector<BezierSegment> bezier_extract(const NurbsCurve& c) {
  const NurbsCurve b = refine_knots(c, bezier_knots(c.knots()));
  const std::vector<double> br = b.knots().breaks();
  const int p = b.degree();
  std::vector<BezierSegment> segs(br.size() - 1);
  for (std::size_t e = 0; e + 1 < br.size(); ++e) {
    segs[e].range = {br[e], br[e + 1]};
    const auto first = b.homogeneous().begin() + static_cast<std::ptrdiff_t>(e) * p;
    segs[e].pw.assign(first, first + p + 1);
  }
  return segs;
}

std::vector<BezierPatch> bezier_extract(const NurbsSurface& s) {
  const NurbsSurface b = refine_knots(s, bezier_knots(s.knots_u()), bezier_knots(s.knots_v()));
  const std::vector<double> bu = b.knots_u().breaks(), bv = b.knots_v().breaks();
  const int p = b.degree_u(), q = b.degree_v();
  std::vector<BezierPatch> patches;
  patches.reserve((bu.size() - 1) * (bv.size() - 1));
  for (std::size_t ev = 0; ev + 1 < bv.size(); ++ev)
    for (std::size_t eu = 0; eu + 1 < bu.size(); ++eu) {
      BezierPatch bp;
      bp.range = {{bu[eu], bu[eu + 1]}, {bv[ev], bv[ev + 1]}};
      bp.degree_u = p;
      bp.degree_v = q;
      bp.element_u = static_cast<int>(eu);
      bp.element_v = static_cast<int>(ev);
      bp.pw.reserve(static_cast<std::size_t>((p + 1) * (q + 1)));
      for (int j = 0; j <= q; ++j)
        for (int i = 0; i <= p; ++i)
          bp.pw.push_back(b.homogeneous()[static_cast<std::size_t>(
              b.index(static_cast<int>(eu) * p + i, static_cast<int>(ev) * q + j))]);
      patches.push_back(std::move(bp));
    }
  return patches;
}

Box3 bounding_box(const BezierPatch& b) {
  Box3 box;
  for (const Vector4d& q : b.pw) box.extend(q.head<3>() / q.w());
  return box;
}

Box3 bounding_box(const BezierSegment& b) {
  Box3 box;
  for (const Vector4d& q : b.pw) box.extend(q.head<3>() / q.w());
  return box;
}

}  // namespace iga
