// The STAS pair of a shell with a rigid surface; see surface_contact_pair.hpp.
#include "iga/contact_integrals/surface_contact_pair.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace iga {

namespace {

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
  ShellContactField(const SurfaceContact& contact, std::vector<double> bu, std::vector<double> bv)
      : contact_(contact), bu_(std::move(bu)), bv_(std::move(bv)) {
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

  /// The fields at (u, v) in element e (e_u + n_u e_v; -1: the span of (u, v), a border
  /// belonging to the span after it). A sample on a border takes the element it belongs to
  /// (SampledMesh::elements): on a shell cut over several processes, the one whose process
  /// sampled it.
  Value at(double u, double v, int e = -1) const {
    const std::size_t k = e >= 0 && static_cast<std::size_t>(e) < elements_.size()
                              ? static_cast<std::size_t>(e)
                              : span_of(bv_, v) * (bu_.size() - 1) + span_of(bu_, u);
    const Element& el = elements_[k];
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

SurfaceContact make_contact(const NurbsSurface& reference, const RigidSurface* rigid,
                            const SurfaceContactParameters& params, const ElementBlock& block) {
  if (rigid == nullptr)
    throw std::invalid_argument("SurfaceContactPair: the rigid surface is null");
  return SurfaceContact(reference, *rigid, params, block);
}

}  // namespace

SurfaceContactPair::SurfaceContactPair(const NurbsSurface& reference,
                                       const std::shared_ptr<const RigidSurface>& rigid,
                                       const SurfaceContactParameters& params,
                                       const ElementBlock& block)
    : RigidContactPair(rigid, make_contact(reference, rigid.get(), params, block)),
      breaks_u_(reference.knots_u().breaks()),
      breaks_v_(reference.knots_v().breaks()) {}

std::unique_ptr<ContactPair> SurfaceContactPair::clone() const {
  return std::make_unique<SurfaceContactPair>(*this);
}

bool SurfaceContactPair::symmetric() const {
  const SurfaceContactParameters& p = contact().parameters();
  const bool friction = p.law.friction();
  const bool slave = p.strategy == SurfaceContactStrategy::kRigidSlave;
  return !friction && !slave;
}

ContactCounts SurfaceContactPair::local_counts() const {
  const SurfaceContactCounts c = contact().counts();
  return {c.active, c.stick, c.slip};
}

std::string SurfaceContactPair::describe() const {
  const SurfaceContactParameters& p = contact().parameters();
  std::ostringstream s;
  s << "STAS contact (rigid "
    << (p.strategy == SurfaceContactStrategy::kRigidMaster ? "master" : "slave")
    << ", mu = " << p.law.mu << ") with a rigid surface of " << rigid().num_patches()
    << " piece(s), ";
  // A shell cut over several processes: its pair's points over the whole patch, and here.
  const std::size_t whole =
      (breaks_u_.size() - 1) * (breaks_v_.size() - 1) *
      static_cast<std::size_t>(p.points_per_direction * p.points_per_direction);
  s << whole << " contact points";
  if (contact().points().size() != whole) s << " (" << contact().points().size() << " here)";
  return s.str();
}

void SurfaceContactPair::add_tool_fields(SampledMesh& body) const {
  const ShellContactField field(contact(), breaks_u_, breaks_v_);
  PointFields c;
  c.name({"contact_pressure", "contact_gap", "contact_state", "contact_undefined"},
         {"contact_traction"});
  const bool by_element = body.elements.size() == body.params.size();
  for (std::size_t i = 0; i < body.params.size(); ++i) {
    const std::array<double, 2>& uv = body.params[i];
    const ShellContactField::Value cv = field.at(uv[0], uv[1], by_element ? body.elements[i] : -1);
    const bool finite =
        std::isfinite(cv.pressure) && std::isfinite(cv.gap) && cv.traction.allFinite();
    c.append({finite ? cv.pressure : 0.0, finite ? cv.gap : 0.0, cv.state,
              finite && cv.gap_known ? 0.0 : 1.0},
             {finite ? cv.traction : Vector3d::Zero()});
  }
  body.fields.add(std::move(c));
}

SampledMesh SurfaceContactPair::tool_points() const {
  SampledMesh m;
  m.fields.name({"N", "gap", "slip"}, {"shell_normal", "tangential_force"});
  for (const SurfaceContactPoint& cp : contact().points()) {
    if (!cp.active) continue;
    m.points.push_back(cp.x);
    m.fields.append({cp.N, cp.gap, contact().sticks(cp) ? 0.0 : 1.0}, {cp.normal, cp.T_vector});
  }
  return m;
}

std::vector<ContactFoot> SurfaceContactPair::tool_feet() const {
  std::vector<ContactFoot> f;
  for (const SurfaceContactPoint& cp : contact().points()) {
    if (!cp.active) continue;
    // On the tool the traction is opposite to the shell's; the footprint is 1.5 times the
    // square root of the point's area share of the shell.
    f.push_back({cp.foot.point, -cp.N, contact().sticks(cp) ? 1.0 : 2.0, 1.5 * std::sqrt(cp.weight),
                 -cp.T_vector});
  }
  return f;
}

}  // namespace iga
