// Internal to iga/model: the parsers of the analysis sections (sections.cpp) as used by the
// loader (analysis.cpp) and the ParaView output (analysis_vtk.cpp). Not a public interface.
//
// Notation: a JsonCursor is a position in the model document (file + JSON path) that every
// error names; Context carries what later sections need of earlier ones.
#pragma once

#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "iga/model/analysis.hpp"

namespace iga::model_detail {

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
  BodyKind kind = BodyKind::kRod;
  const NurbsCurve* curve = nullptr;      // rod
  const NurbsSurface* surface = nullptr;  // shell
  int n_points = 0;
  int nu = 0, nv = 0;  // shell: control points in u and v
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
/// Materials ("materials" entries).
ShellMaterial parse_shell_material(const JsonCursor& m);
RodSection parse_rod_material(const JsonCursor& m);
/// The "rigid_motions" section: each entry a rigid surface or patch group of the geometry
/// with a "rotation" and/or a "translation" along load curves (ctx.curves).
std::map<std::string, std::shared_ptr<const RigidMotion>> parse_rigid_motions(
    const JsonCursor& section, const Context& ctx, const GeometryModel& geometry);
/// Every entry of the arrays "boundary_conditions", "loads" and "contact" is an object whose
/// "body" names one of ctx.bodies (ModelError at the first that does not).
void check_entry_bodies(const JsonCursor& root, const Context& ctx);
/// The rod (shell) body b of the model root with its contact pairs attached (in the file's
/// order), its boundary conditions and loads: the entries whose "body" is ctx.body.
std::unique_ptr<Body> build_rod(const JsonCursor& root, const JsonCursor& b, Context& ctx,
                                const GeometryModel& geometry, const JsonCursor& materials);
std::unique_ptr<ShellProblem> build_shell(const JsonCursor& root, const JsonCursor& b, Context& ctx,
                                          const GeometryModel& geometry,
                                          const JsonCursor& materials);
/// The "solver" and "output" sections; `bodies` holds the context of every body as it was read.
NonlinearSolverSettings parse_solver(const JsonCursor& s, double& stop_after, int& slip_steps);
AnalysisOutput parse_output(const JsonCursor& o, const std::vector<Context>& bodies);
/// Every term of the output's plots names one of `columns` (ModelError at the term).
void check_plot_columns(const JsonCursor& o, const AnalysisOutput& out,
                        const std::vector<std::string>& columns);

}  // namespace iga::model_detail
