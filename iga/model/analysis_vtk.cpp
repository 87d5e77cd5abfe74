// ParaView output of an analysis: each body sampled with its fields and its pairs' (Body::sample),
// each pair's contact points and feet, and the contact fields on the rigid tools' pieces.
#include "iga/model/analysis.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <tuple>
#include <type_traits>

#include "geometry/constructions.hpp"
#include "iga/model/model.hpp"
#include "iga/model/sections.hpp"
#include "iga/output/mesh_parts.hpp"
#include "iga/output/output_format.hpp"
#include "iga/output/vtk_writer.hpp"

namespace iga {

namespace fs = std::filesystem;
using model_detail::fmt;

namespace {

/// "_<i>" when there are several (n > 1), else "": file names of one of several pairs or pieces.
std::string index_suffix(int i, int n) {
  if (n <= 1) return {};
  char buf[16];  // (not "_" + std::to_string(i): a false -Wrestrict of GCC 12)
  std::snprintf(buf, sizeof buf, "_%d", i);
  return buf;
}

/// The feet sorted into cubic cells of side c, the largest footprint radius (at least 0.75
/// times the grid's spacing): key floor(x / c) per coordinate.
struct FootCells {
  using Cell = std::array<long long, 3>;
  double c = 0.0;
  std::vector<std::pair<Cell, std::size_t>> sorted;  // (cell, foot), by cell

  FootCells(double spacing, const std::vector<ContactFoot>& feet) : c(0.75 * spacing) {
    for (const ContactFoot& f : feet)
      if (std::isfinite(f.radius)) c = std::max(c, f.radius);
    if (c > 0.0 && std::isfinite(c))
      for (std::size_t i = 0; i < feet.size(); ++i)
        if (feet[i].x.allFinite()) sorted.push_back({cell_of(feet[i].x), i});
    std::sort(sorted.begin(), sorted.end());
  }

  Cell cell_of(const Vector3d& x) const {
    Cell k;
    for (int i = 0; i < 3; ++i)  // clamped: a far or huge coordinate stays a valid key
      k[static_cast<std::size_t>(i)] =
          static_cast<long long>(std::clamp(std::floor(x[i] / c), -1e15, 1e15));
    return k;
  }
};

/// The sums of one grid node x over the feet within their footprint radius: the weights
/// (their sum and largest), the weighted pressure and traction, and the state of the foot of
/// the largest weight.
struct NodeSums {
  double& wsum;
  double& wmax;
  double& pressure;
  Vector3d& traction;
  double& state;

  /// Adds the feet of cell `key` that reach x, weight (1 - d/h)^2.
  void add_cell(const FootCells& cells, const FootCells::Cell& key, const Vector3d& x,
                double spacing, const std::vector<ContactFoot>& feet) {
    auto it =
        std::lower_bound(cells.sorted.begin(), cells.sorted.end(), std::pair{key, std::size_t{0}});
    for (; it != cells.sorted.end() && it->first == key; ++it) {
      const ContactFoot& f = feet[it->second];
      const double h = std::max(f.radius, 0.75 * spacing);
      const double d = (x - f.x).norm();
      if (!(d < h)) continue;
      const double w = (1.0 - d / h) * (1.0 - d / h);
      wsum += w;
      pressure += w * f.pressure;
      traction += w * f.traction;
      if (w > wmax) {
        wmax = w;
        state = f.state;
      }
    }
  }
};

/// The contact on a grid of a rigid piece (issue 12 item 6): every grid node takes the weighted
/// mean of the feet within their footprint radius h of it, weight (1 - d/h)^2, and 0 where no
/// foot reaches (the state: the foot of the largest weight). h is 1.5 times the point's share of
/// the body (sqrt of its area for shells, its length for rods), at least 0.75 times the grid's
/// spacing so that every foot reaches a node. A transfer for viewing, not a conservative one:
/// the mean keeps the pressure level of a uniform contact, and the field falls to 0 within h of
/// the contact zone's edge (rods: a band of width about 2h along the rope). The feet are sorted
/// into cubic cells of the largest h, so a node looks at the 27 cells around its own only.
/// Spread over several processes, each process sums over its own feet and the sums are
/// combined over the processes (the weights' sums added, the state that of the largest weight
/// of any process) before the means are taken.
struct ToolFieldSums {
  std::vector<double> wsum, wmax, pressure, state;
  std::vector<Vector3d> traction;

  ToolFieldSums(const std::vector<Vector3d>& grid, double spacing,
                const std::vector<ContactFoot>& feet)
      : wsum(grid.size(), 0.0),
        wmax(grid.size(), 0.0),
        pressure(grid.size(), 0.0),
        state(grid.size(), 0.0),
        traction(grid.size(), Vector3d::Zero()) {
    const FootCells cells(spacing, feet);
    for (std::size_t g = 0; g < grid.size(); ++g) {
      if (cells.sorted.empty() || !grid[g].allFinite()) continue;
      NodeSums sums{wsum[g], wmax[g], pressure[g], traction[g], state[g]};
      const FootCells::Cell home = cells.cell_of(grid[g]);
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
          for (long long dz = -1; dz <= 1; ++dz)
            sums.add_cell(cells, {home[0] + dx, home[1] + dy, home[2] + dz}, grid[g], spacing,
                          feet);
    }
  }

  /// The sums of every process's feet (a collective operation).
  void combine(const Communicator& comm) {
    const std::size_t n = wsum.size();
    std::vector<double> sums(5 * n);
    for (std::size_t g = 0; g < n; ++g) {
      sums[5 * g] = wsum[g];
      sums[5 * g + 1] = pressure[g];
      for (int k = 0; k < 3; ++k) sums[5 * g + 2 + static_cast<std::size_t>(k)] = traction[g][k];
    }
    comm.sum(sums);
    std::vector<double> largest = wmax;
    comm.max(largest);
    for (std::size_t g = 0; g < n; ++g) {
      wsum[g] = sums[5 * g];
      pressure[g] = sums[5 * g + 1];
      traction[g] = Vector3d(sums[5 * g + 2], sums[5 * g + 3], sums[5 * g + 4]);
      // the state of the process whose foot weighs most (0 where its weight is another's)
      if (wmax[g] < largest[g]) state[g] = 0.0;
    }
    comm.max(state);
  }

  /// The fields: the weighted means (a non-finite value, a foot's: 0 and non_finite = 1).
  PointFields fields() && {
    for (std::size_t g = 0; g < wsum.size(); ++g)
      if (wsum[g] > 0.0) {
        pressure[g] /= wsum[g];
        traction[g] /= wsum[g];
      }
    PointFields d;
    d.scalars = {{"contact_pressure", std::move(pressure)}, {"contact_state", std::move(state)}};
    d.vectors = {{"contact_traction", std::move(traction)}};
    return d;
  }
};

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

namespace {

/// The feet of a pair as a mesh of points (the output's tool_contact mesh), with their
/// footprint radius as one more field (for the tool's fields; taken off before writing).
SampledMesh feet_mesh(const std::vector<ContactFoot>& feet) {
  SampledMesh m;
  std::vector<double> pressure, state, radius;
  std::vector<Vector3d> traction;
  for (auto* v : {&pressure, &state, &radius}) v->reserve(feet.size());
  traction.reserve(feet.size());
  m.points.reserve(feet.size());
  for (const ContactFoot& f : feet) {
    m.points.push_back(f.x);
    pressure.push_back(f.pressure);
    state.push_back(f.state);
    radius.push_back(f.radius);
    traction.push_back(f.traction);
  }
  m.fields.scalars = {{"contact_pressure", pressure}, {"contact_state", state}, {"radius", radius}};
  m.fields.vectors = {{"tangential_traction", traction}};
  return m;
}

/// The feet of feet_mesh back, the radius field taken off the mesh.
std::vector<ContactFoot> take_feet(SampledMesh& m) {
  std::vector<ContactFoot> feet(m.points.size());
  const auto& sc = m.fields.scalars;
  const auto& tr = m.fields.vectors.at(0).second;
  for (std::size_t i = 0; i < feet.size(); ++i)
    feet[i] = {m.points[i], sc.at(0).second[i], sc.at(1).second[i], sc.at(2).second[i], tr[i]};
  m.fields.scalars.pop_back();
  return feet;
}

}  // namespace

namespace {

bool has_non_finite(const SampledMesh& m) {
  const auto bad = [](const auto& v) {
    return std::any_of(v.begin(), v.end(), [](const auto& x) {
      if constexpr (std::is_same_v<std::decay_t<decltype(x)>, double>)
        return !std::isfinite(x);
      else
        return !x.allFinite();
    });
  };
  if (bad(m.points)) return true;
  for (const auto& f : m.fields.scalars)
    if (bad(f.second)) return true;
  for (const auto& f : m.fields.vectors)
    if (bad(f.second)) return true;
  return false;
}

/// Each process's meshes become its pieces of the spread meshes (MeshPieces; a collective
/// operation): which process writes a piece, whether every piece needs the non_finite flag,
/// and on process 0 the pieces each collection lists, with their places and fields (process 0
/// gets every process's sizes and field names, never their values). std::runtime_error naming
/// the mesh, on process 0, if pieces with points have other fields.
void make_pieces(const Communicator& comm, std::vector<MeshOutput>& meshes) {
  const std::size_t n = meshes.size();
  std::vector<long long> points(n);
  std::vector<double> maxima(3 * n);  // per mesh: a non-finite value, the whole grid's size
  Json headers = Json::array();
  for (std::size_t i = 0; i < n; ++i) {
    const SampledMesh& m = meshes[i].mesh;
    points[i] = static_cast<long long>(m.points.size());
    maxima[3 * i] = has_non_finite(m) ? 1.0 : 0.0;
    maxima[3 * i + 1] = m.points.empty() ? 0.0 : m.i0 + m.nu;
    maxima[3 * i + 2] = m.points.empty() ? 0.0 : m.j0 + m.nv;
    Json scalars = Json::array(), vectors = Json::array();
    for (const auto& f : m.fields.scalars) scalars.push_back(f.first);
    for (const auto& f : m.fields.vectors) vectors.push_back(f.first);
    headers.push_back({{"points", m.points.size()},
                       {"nu", m.nu},
                       {"nv", m.nv},
                       {"i0", m.i0},
                       {"j0", m.j0},
                       {"scalars", scalars},
                       {"vectors", vectors}});
  }
  std::vector<long long> total = points;
  comm.sum(total);
  comm.max(maxima);
  const std::vector<std::string> all = comm.gather(headers.dump());
  for (std::size_t i = 0; i < n; ++i) {
    MeshPieces& p = meshes[i].pieces;
    p.rank = comm.rank();
    p.write = points[i] > 0 || (total[i] == 0 && comm.root());
    p.non_finite = maxima[3 * i] > 0.0;
    p.nu = static_cast<int>(maxima[3 * i + 1]);
    p.nv = static_cast<int>(maxima[3 * i + 2]);
  }
  if (!comm.root()) return;
  std::vector<Json> of_rank;
  of_rank.reserve(all.size());
  for (const std::string& h : all) of_rank.push_back(Json::parse(h));
  for (std::size_t i = 0; i < n; ++i) {
    MeshPieces& p = meshes[i].pieces;
    const Json* fields = nullptr;  // those of the first piece listed
    for (std::size_t r = 0; r < of_rank.size(); ++r) {
      const Json& h = of_rank[r].at(i);
      if (h.at("points").get<long long>() == 0 && !(total[i] == 0 && r == 0)) continue;
      MeshPieces::Piece piece{static_cast<int>(r), h.at("nu").get<int>(), h.at("nv").get<int>(),
                              h.at("i0").get<int>(), h.at("j0").get<int>()};
      p.listed.push_back(piece);
      if (fields == nullptr) {
        fields = &h;
      } else if (h.at("scalars") != fields->at("scalars") ||
                 h.at("vectors") != fields->at("vectors")) {
        throw std::runtime_error("the output mesh " + meshes[i].stem +
                                 ": its pieces on processes " +
                                 std::to_string(p.listed.front().rank) + " and " +
                                 std::to_string(r) + " have other fields");
      }
    }
    for (const Json& name : fields->at("scalars"))
      p.fields.scalars.emplace_back(name.get<std::string>(), std::vector<double>{});
    for (const Json& name : fields->at("vectors"))
      p.fields.vectors.emplace_back(name.get<std::string>(), std::vector<Vector3d>{});
  }
}

/// The parts of every process gathered to process 0 and joined there into whole meshes (a
/// collective operation; the other processes' parts are left as they are).
void join_on_root(const Communicator& comm, std::vector<MeshOutput>& parts) {
  const std::vector<std::string> packed = comm.gather(pack_meshes(parts));
  if (!comm.root()) return;
  std::vector<std::vector<MeshOutput>> of_rank;
  of_rank.reserve(packed.size());
  for (const std::string& p : packed) of_rank.push_back(unpack_meshes(p));
  for (std::size_t i = 0; i < parts.size(); ++i) {
    std::vector<MeshOutput> pieces;
    pieces.reserve(of_rank.size());
    for (std::vector<MeshOutput>& r : of_rank) pieces.push_back(std::move(r.at(i)));
    parts[i] = join_parts(std::move(pieces));
  }
}

}  // namespace

std::vector<MeshOutput> Analysis::output_meshes(const std::string& stem, const VectorXd& u,
                                                double t, bool in_pieces) {
  // This process's part: each body sampled (its share), each pair's contact points and feet.
  std::vector<MeshOutput> meshes;
  meshes.reserve(static_cast<std::size_t>(num_bodies() + 3 * num_pairs()));
  for (int b = 0; b < num_bodies(); ++b) {
    const Body& B = body(b);
    const std::string series = num_bodies() == 1 ? B.type() : body_name(b);
    const int n =
        output_.samples_per_element > 0 ? output_.samples_per_element : B.default_samples();
    meshes.push_back({series,
                      stem + "_" + series,
                      name_ + " " + series + ", t = " + fmt(t),
                      B.sample(system_->block(u, b), t, n),
                      {}});
  }
  for (int k = 0; k < num_pairs(); ++k) {
    const ContactPair& P = pair(k);
    const std::string ps = index_suffix(k, num_pairs());
    meshes.push_back({"contact" + ps,
                      stem + "_contact" + ps,
                      name_ + " contact points, t = " + fmt(t),
                      P.points(),
                      {}});
    // The same contact seen from the rigid tool: its surface points (the feet) with the
    // pressure, the traction the body exerts on the tool, and the state (1 stick, 2 slip).
    meshes.push_back({"",
                      stem + "_tool_contact" + ps,
                      name_ + " contact on the rigid tool, t = " + fmt(t),
                      feet_mesh(P.feet()),
                      {}});
  }
  // Over several processes, either each process keeps its parts as its pieces, or process 0
  // gathers and joins them.
  const Communicator& comm = communicator();
  const bool spread = comm.size() > 1;
  const bool pieces = spread && in_pieces;
  if (spread && !pieces) {
    join_on_root(comm, meshes);
    if (!comm.root()) return {};
  }
  // The tool grids of each pair: process 0 writes them whole.
  std::vector<std::vector<MeshOutput>> tools(static_cast<std::size_t>(num_pairs()));
  for (int k = 0; k < num_pairs(); ++k) {
    const ContactPair& P = pair(k);
    const std::string ps = index_suffix(k, num_pairs());
    MeshOutput& feet_out = meshes[static_cast<std::size_t>(num_bodies() + 2 * k + 1)];
    const std::vector<ContactFoot> feet = take_feet(feet_out.mesh);
    // ... and as fields on a grid of each bounded piece of the tool (ToolFieldSums).
    const RigidSurface& rigid = P.rigid();
    for (int i = 0; i < rigid.num_patches(); ++i) {
      auto [grid, spacing] = tool_grid(rigid.patch(i));
      if (grid.empty()) continue;
      for (Vector3d& x : grid) x = P.pose().to_world(x);  // where the tool is (feet: world)
      ToolFieldSums sums(grid, spacing, feet);
      if (pieces) sums.combine(comm);
      const std::string series = "tool" + ps + index_suffix(i, rigid.num_patches());
      SampledMesh gm;
      gm.shape = SampledMesh::Shape::kGrid;
      gm.nu = gm.nv = kToolGrid;
      gm.fields = std::move(sums).fields();
      gm.points = std::move(grid);
      tools[static_cast<std::size_t>(k)].push_back(
          {series,
           stem + "_" + series,
           name_ + " contact on rigid piece " + std::to_string(i) + ", t = " + fmt(t),
           std::move(gm),
           {}});
    }
  }
  if (pieces) make_pieces(comm, meshes);
  if (!comm.root()) return meshes;  // the pieces of this process
  // The tool grids after their pair's meshes, as the meshes of one process are ordered.
  std::vector<MeshOutput> out;
  out.reserve(meshes.size() + tools.size());
  auto next = meshes.begin();
  for (int b = 0; b < num_bodies(); ++b) out.push_back(std::move(*next++));
  for (std::vector<MeshOutput>& of_pair : tools) {
    out.push_back(std::move(*next++));  // the contact points
    out.push_back(std::move(*next++));  // the feet
    for (MeshOutput& m : of_pair) out.push_back(std::move(m));
  }
  // Moving tools where they are at t (a .pvd series per tool and piece).
  for (MeshOutput& m : tool_meshes(stem + "_rigid", t, true)) out.push_back(std::move(m));
  return out;
}

std::vector<Analysis::OutputFile> Analysis::write_output(const std::string& dir,
                                                         const std::string& stem, const VectorXd& u,
                                                         double t) {
  std::vector<OutputFile> files;
  for (OutputFileRef& f : write_meshes(output_.field_format, dir, output_meshes(stem, u, t)))
    files.push_back({std::move(f.series), std::move(f.file)});
  return files;
}

std::vector<std::string> Analysis::write_vtk(const std::string& dir, const std::string& stem,
                                             const VectorXd& u, double t) {
  std::vector<std::string> names;
  for (const OutputFile& f : write_output(dir, stem, u, t)) names.push_back(f.file);
  return names;
}

std::vector<Analysis::Tool> Analysis::tools() const {
  std::vector<Tool> tools;
  for (int k = 0; k < num_pairs(); ++k) {
    const std::string& name = pairs_[static_cast<std::size_t>(k)].rigid;
    const auto same = [&](const Tool& t) { return t.name == name; };
    if (std::find_if(tools.begin(), tools.end(), same) != tools.end()) continue;
    tools.push_back({name, &pair(k)});
  }
  return tools;
}

std::vector<MeshOutput> Analysis::tool_meshes(const std::string& stem, double t,
                                              bool moving_only) const {
  // One 41 x 41 grid per bounded piece: <stem> for a single piece, else <stem>_<i>; with
  // several tools <stem>_<j> in place of <stem>; each at its pose at t.
  const std::vector<Tool> all = tools();
  const int n_tools = static_cast<int>(all.size());
  std::vector<MeshOutput> meshes;
  for (int j = 0; j < n_tools; ++j) {
    const ContactPair& P = *all[static_cast<std::size_t>(j)].pair;
    if (moving_only && P.motion() == nullptr) continue;
    const RigidPose pose = P.pose(t);
    const RigidSurface& rigid = P.rigid();
    for (int i = 0; i < rigid.num_patches(); ++i) {
      SampledMesh m;
      m.points = tool_grid(rigid.patch(i)).first;
      if (m.points.empty()) continue;
      for (Vector3d& x : m.points) x = pose.to_world(x);
      m.shape = SampledMesh::Shape::kGrid;
      m.nu = m.nv = kToolGrid;
      const std::string suffix = index_suffix(j, n_tools) + index_suffix(i, rigid.num_patches());
      meshes.push_back({"rigid" + suffix,
                        stem + suffix,
                        name_ + " rigid surface" +
                            (n_tools > 1 ? " " + all[static_cast<std::size_t>(j)].name : "") +
                            (P.motion() ? ", t = " + fmt(t) : std::string()),
                        std::move(m),
                        {}});
    }
  }
  return meshes;
}

bool Analysis::write_rigid_vtk(const std::string& dir, const std::string& stem) const {
  return !write_meshes(output_.field_format, dir, tool_meshes(stem, settings_.t0, false)).empty();
}

}  // namespace iga
