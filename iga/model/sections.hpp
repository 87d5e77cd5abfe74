// Internal to iga/model: the parsers of the analysis sections (sections.cpp) as used by the
// loader (analysis.cpp), the body types' readers (rod_body.cpp, shell_body.cpp; body_types.hpp)
// and the ParaView output (analysis_vtk.cpp). Not a public interface.
//
// Notation: a JsonCursor is a position in the model document (file + JSON path) that every
// error names; Context carries what later sections need of earlier ones; a body's shape is what
// the shared parsers need of it (its control points, how a point or a parameter is named).
#pragma once

#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "contact/contact_law.hpp"
#include "contact/rigid_motion.hpp"
#include "iga/core/control_point_problem.hpp"
#include "iga/model/analysis.hpp"

namespace iga::model_detail {

/// What the shared parsers (conditions, loads, output entries) need of the body being read; its
/// type's reader fills it in (body_types.hpp).
struct BodyShape {
  int n_points = 0;          ///< control points (indices 0 .. n_points - 1)
  std::vector<int> corners;  ///< "corners": a rod's ends, a surface's four corners
  /// A control point named otherwise than by its index (a rod's "start" and "end", a surface's
  /// [i, j]), or -1 if c is not such a name (then c must be an index). ModelError at c for a
  /// malformed name.
  std::function<int(const JsonCursor& c)> named_point;
  /// Whether an array at c names one point (a surface's [i, j]) rather than a list of points.
  std::function<bool(const JsonCursor& c)> array_is_point;
  /// The body's parameters (u, v) of a point given at c ("at": a rod's curve parameter, "start"
  /// or "end", v = 0; a surface's [u, v]); ModelError at c outside the body.
  std::function<Vector2d(const JsonCursor& c)> parameters;
  /// A direction given by name at d (a rod's "outward_tangent" at its end `where`: 0 start, 1
  /// end, -1 neither); null: the body names no directions.
  std::function<Vector3d(const JsonCursor& d, int where)> named_direction;
};

/// What later sections need of earlier ones while a model is read.
struct Context {
  std::map<std::string, LoadCurve> curves;
  // The rigid surfaces of the contact pairs, one per name: pairs that name one tool share it.
  std::map<std::string, std::shared_ptr<const RigidSurface>>* rigids = nullptr;
  // The prescribed motions of rigid tools by the tool's name ("rigid_motions").
  std::map<std::string, std::shared_ptr<const RigidMotion>> motions;
  std::vector<std::string> bodies;  // every body's name, in the file's order
  std::string body;                 // the body being read
  int body_index = 0;               // its index in the model
  BodyShape shape;                  // the body's, once its reader has built it
};

/// The string at c as a name that heads steps.csv columns: non-empty, without commas, quotes or
/// line breaks (ModelError at c otherwise).
std::string column_name(const JsonCursor& c);
/// The vector [x, y, z] at c.
Vector3d vec3(const JsonCursor& c);
/// A number with 10 significant digits (messages, titles).
std::string fmt(double v);
/// The number at c, > 0 (>= 0 with allow_zero); ModelError otherwise.
double positive(const JsonCursor& c, bool allow_zero = false);
/// The string at c, which must be one of `names`.
std::string one_of(const JsonCursor& c, std::initializer_list<const char*> names);
std::string one_of(const JsonCursor& c, const std::vector<std::string>& names);
/// A load curve ("load_curves" entry).
LoadCurve parse_load_curve(const JsonCursor& c);
/// The load curve must stay finite over the solver's pseudo-time.
void check_finite_curve(const JsonCursor& c, const LoadCurve& f, const NonlinearSolverSettings& s);
/// The number at key of o, or `fallback` without the key.
double number_or(const JsonCursor& o, const char* key, double fallback);
/// An integer key of `o` in [lo, hi] (message `range`), or `fallback` if absent.
int int_or(const JsonCursor& o, const char* key, int fallback, int lo, int hi, const char* range);
/// The penalty and friction keys of a contact pair: eps_N > 0, eps_T >= 0 (0), mu >= 0 (0).
inline void penalty_and_friction(const JsonCursor& c, ContactParameters& p) {
  p.eps_n = positive(c["eps_N"]);
  p.eps_t = c.has("eps_T") ? positive(c["eps_T"], true) : 0.0;
  p.mu = c.has("mu") ? positive(c["mu"], true) : 0.0;
}
/// The enforcement keys of a contact pair (penalty or augmented Lagrange).
ContactEnforcement parse_enforcement(const JsonCursor& c);
/// The load curve an entry names ("curve"; default: the ramp t).
LoadCurve curve_of(const JsonCursor& o, const Context& ctx);
/// The entry's "body" names one of ctx.bodies (ModelError listing them otherwise).
void check_body(const JsonCursor& o, const Context& ctx);
/// A control point of the body (ctx.shape): its name or index.
int point_index(const JsonCursor& c, const Context& ctx);
/// "all", "corners", one point or a list of points.
std::vector<int> point_list(const JsonCursor& pc, const Context& ctx);
/// "components": a list of 0, 1, 2 (default all three).
std::vector<int> components(const JsonCursor& o);
/// A vector given as [x, y, z] (key `vec_key`), or as "magnitude" along "direction" ([x, y, z]
/// or a direction the body names at its point `where`, BodyShape::named_direction).
Vector3d vector_value(const JsonCursor& o, const char* vec_key, const Context& ctx, int where);
/// 0 for "start", 1 for "end", -1 otherwise.
int end_of(const JsonCursor& c);
/// The moving tool an entry follows ("motion": a key of "rigid_motions"); null without the key.
std::shared_ptr<const RigidMotion> motion_of(const JsonCursor& o, const Context& ctx);
/// Point i prescribed to follow a moving tool m: x(t) = c(t) + Q(t) (X + d curve(t) - c0).
void prescribe_following(const JsonCursor& o, ControlPointProblem& p, int i, const Vector3d& d,
                         const LoadCurve& curve, const std::shared_ptr<const RigidMotion>& m);
/// A force that turns with a moving tool, F(t) = Q(t) F curve(t): three loads along the axes,
/// each along its own curve; add(direction, curve) adds one.
template <class Add>
void turning_force(const Vector3d& F, const LoadCurve& curve,
                   const std::shared_ptr<const RigidMotion>& m, Add add) {
  for (int k = 0; k < 3; ++k)
    add(Vector3d::Unit(k), [m, F, curve, k](double t) { return (m->pose(t).Q * F)[k] * curve(t); });
}
/// {"type": "fix", "points": ..., "components": [...]}.
void fix_points(const JsonCursor& o, const Context& ctx, ControlPointProblem& p);
/// The rigid surface named at rc, shared by every pair that names it (ctx.rigids).
std::shared_ptr<const RigidSurface> rigid_surface(const JsonCursor& rc, const GeometryModel& g,
                                                  const Context& ctx);
/// Calls f on every entry of the array root[key] (if present) that belongs to the body
/// ctx.body (check_entry_bodies has checked that each names a body).
template <class F>
void for_each_entry(const JsonCursor& root, const char* key, const Context& ctx, F f) {
  if (!root.has(key)) return;
  const JsonCursor list = root[key];
  list.expect_array();
  for (std::size_t k = 0; k < list.size(); ++k)
    if (list[k]["body"].as_string() == ctx.body) f(list[k]);
}
/// The material entry that a body's "material" key names, of one of the `types` of its body
/// type (ModelError at the key otherwise; `body_type` names the body's type in the message).
JsonCursor body_material(const JsonCursor& b, const JsonCursor& materials,
                         const std::vector<std::string>& types, const std::string& body_type);
/// The "rigid_motions" section: each entry a rigid surface or patch group of the geometry
/// with a "rotation" and/or a "translation" along load curves (ctx.curves).
std::map<std::string, std::shared_ptr<const RigidMotion>> parse_rigid_motions(
    const JsonCursor& section, const Context& ctx, const GeometryModel& geometry);
/// Every entry of the arrays "boundary_conditions", "loads" and "contact" is an object whose
/// "body" names one of ctx.bodies (ModelError at the first that does not).
void check_entry_bodies(const JsonCursor& root, const Context& ctx);
/// The "solver" and "output" sections; `bodies` holds the context of every body as it was read.
NonlinearSolverSettings parse_solver(const JsonCursor& s, double& stop_after, int& slip_steps);
AnalysisOutput parse_output(const JsonCursor& o, const std::vector<Context>& bodies);
/// Every term of the output's plots names one of `columns` (ModelError at the term).
void check_plot_columns(const JsonCursor& o, const AnalysisOutput& out,
                        const std::vector<std::string>& columns);

}  // namespace iga::model_detail
