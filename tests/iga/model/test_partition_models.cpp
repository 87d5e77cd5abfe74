// A model's parts over P processes add up to the model (iga/core/partition.hpp,
// BodySystem::distribute), checked in one process: each part is the analysis built as process
// r of P standing alone (SerialCommunicator(r, P): it says so but sums nothing), assembled at a
// state of the serial run. Its residual and tangent are then its own share; summed over r they must
// be the model's (every shell element, contact point, load and spring once: a shell's surface load
// split with its elements, point loads and springs on the process that owns the point, a rod
// whole on one process, a membrane cut like a shell),
// and so must the pairs' counts and tool forces. Each part's layout (DofLayout) must hold what
// it assembles: every unknown owned by one process, the same owners on every process, and the
// rows and entries of a part's residual and tangent among its own unknowns and its ghosts. The
// processor grid and the parts' sizes are checked too. The same analyses run under mpirun in
// tests/mpi/mpi_models.cpp; this test needs neither MPI nor PETSc, so it runs in every build (the
// sanitizers' too).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "iga/core/partition.hpp"
#include "iga/membrane/membrane.hpp"
#include "iga/model/analysis.hpp"
#include "iga/parallel/communicator.hpp"
#include "iga/parallel/dof_layout.hpp"
#include "iga/shell/shell_problem.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_partition_models {

using namespace iga;

namespace {

const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

struct State {
  VectorXd u;
  double t = 0.0;
};

/// The model at its state after `steps` converged steps of the serial run (no output).
/// The model at a state of its serial run with contact: the first converged step with active
/// contact points after at least `steps` converged steps (whatever steps the run takes: the
/// round-off probe may cut some back).
State serial_state(Json doc, const std::string& file, int steps) {
  if (doc.contains("output")) doc["output"]["vtk"] = "none";
  Analysis a = Analysis::from_json(doc, file);
  int converged = 0;
  const AnalysisResult r = a.run(nullptr, {}, [&](const VectorXd&, double, const AnalysisStep& st) {
    return !(++converged >= steps && st.contact.active > 0);
  });
  REQUIRE(!r.steps.empty());
  REQUIRE(r.steps.back().contact.active > 0);
  return {r.u, r.solver.t};
}

struct Assembly {
  VectorXd R;
  SparseMatrix K;
  std::vector<ContactCounts> counts;
  std::vector<Vector3d> forces;
};

Assembly assemble(Analysis& a, const State& s) {
  Assembly out;
  a.problem().assemble(s.u, s.t, out.R, &out.K);
  for (int k = 0; k < a.num_pairs(); ++k) {
    out.counts.push_back(a.pair(k).counts());
    out.forces.push_back(a.pair(k).tool_force());
  }
  return out;
}

/// The elements built of the surface bodies (shells and membranes) of a model or part, and
/// their patches' elements.
std::pair<int, int> surface_elements(const Analysis& a) {
  int built = 0, patch = 0;
  for (int b = 0; b < a.num_bodies(); ++b) {
    if (const auto* shell = dynamic_cast<const ShellProblem*>(&a.body(b))) {
      built += shell->shell().num_elements();
      patch += shell->shell().num_patch_elements();
    } else if (const auto* m = dynamic_cast<const MembraneProblem*>(&a.body(b))) {
      built += m->num_elements();
      patch += static_cast<int>((m->reference().knots_u().breaks().size() - 1) *
                                (m->reference().knots_v().breaks().size() - 1));
    }
  }
  return {built, patch};
}

void check_parts_of(const Json& doc, const std::string& path, int steps, int P);

/// The parts of the model on P processes, assembled at s, summed; against the whole.
void check_parts(const std::string& file, int steps, int P, const Json& loads = Json()) {
  CAPTURE(file, P);
  const std::string path = kData + file;
  Json doc = read_json_file(path);
  if (!loads.is_null()) doc["loads"] = loads;
  check_parts_of(doc, path, steps, P);
}

void check_parts_of(const Json& doc, const std::string& path, int steps, int P) {
  const State s = serial_state(doc, path, steps);
  Analysis whole = Analysis::from_json(doc, path);
  const Assembly w = assemble(whole, s);
  Assembly sum;
  sum.R = VectorXd::Zero(w.R.size());
  sum.K.resize(w.K.rows(), w.K.cols());
  sum.counts.resize(w.counts.size());
  sum.forces.assign(w.forces.size(), Vector3d::Zero());
  int built = 0;            // surface elements built over the parts
  std::vector<int> owners;  // process 0's owner of each unknown
  std::vector<int> owned_by(static_cast<std::size_t>(w.R.size()), 0);  // how many own it
  for (int r = 0; r < P; ++r) {
    const SerialCommunicator comm(r, P);
    Analysis part = Analysis::from_json(doc, path, comm);
    CHECK(part.problem().distributed());
    const Assembly p = assemble(part, s);
    const DofLayout* L = part.problem().layout();
    REQUIRE(L != nullptr);
    REQUIRE(L->size() == w.R.size());
    std::vector<int> own(static_cast<std::size_t>(L->size()));
    for (int i = 0; i < L->size(); ++i) own[static_cast<std::size_t>(i)] = L->owner(i);
    if (r == 0) owners = own;
    CHECK(own == owners);
    std::vector<char> holds(own.size(), 0);  // own unknowns and ghosts
    for (const int i : L->owned()) {
      ++owned_by[static_cast<std::size_t>(i)];
      holds[static_cast<std::size_t>(i)] = 1;
      CHECK(L->owner(i) == r);
    }
    for (const int i : L->ghosts()) {
      CHECK(L->owner(i) != r);
      holds[static_cast<std::size_t>(i)] = 1;
    }
    int outside = 0;  // entries of the part outside what it holds
    for (Eigen::Index i = 0; i < p.R.size(); ++i)
      if (p.R[i] != 0.0 && holds[static_cast<std::size_t>(i)] == 0) ++outside;
    for (int j = 0; j < p.K.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(p.K, j); it; ++it)
        if (holds[static_cast<std::size_t>(it.row())] == 0 ||
            holds[static_cast<std::size_t>(it.col())] == 0)
          ++outside;
    CHECK(outside == 0);
    sum.R += p.R;
    sum.K = SparseMatrix(sum.K + p.K);
    for (std::size_t k = 0; k < p.counts.size(); ++k) {
      sum.counts[k].active += p.counts[k].active;
      sum.counts[k].stick += p.counts[k].stick;
      sum.counts[k].slip += p.counts[k].slip;
      sum.forces[k] += p.forces[k];
    }
    built += surface_elements(part).first;
  }
  CHECK(std::count(owned_by.begin(), owned_by.end(), 1) == static_cast<long>(owned_by.size()));
  const auto [whole_built, patch] = surface_elements(whole);
  CHECK(whole_built == patch);
  CHECK(built == patch);
  CHECK((sum.R - w.R).norm() <= 1e-12 * w.K.norm() * std::max(1.0, s.u.norm()));
  CHECK(SparseMatrix(sum.K - w.K).norm() <= 1e-12 * w.K.norm());
  for (std::size_t k = 0; k < w.counts.size(); ++k) {
    CHECK(sum.counts[k].active == w.counts[k].active);
    CHECK(sum.counts[k].stick == w.counts[k].stick);
    CHECK(sum.counts[k].slip == w.counts[k].slip);
    CHECK((sum.forces[k] - w.forces[k]).norm() <= 1e-10 * std::max(1e-300, w.forces[k].norm()));
  }
  // Some contact is active at the state: the contact points' split is tested.
  int active = 0;
  for (const ContactCounts& c : w.counts) active += c.active;
  CHECK(active > 0);
}

}  // namespace

TEST_CASE("processor grid: the shortest cut, every block at least one element", "[partition]") {
  CHECK(processor_grid(1, 5, 7) == std::array<int, 2>{1, 1});
  // 2 processes on 20 x 10 elements: cut across u (10 edges), not across v (20).
  CHECK(processor_grid(2, 20, 10) == std::array<int, 2>{2, 1});
  CHECK(processor_grid(2, 10, 20) == std::array<int, 2>{1, 2});
  CHECK(processor_grid(4, 10, 10) == std::array<int, 2>{2, 2});  // cut 20, against 30 for 4 x 1
  CHECK(processor_grid(4, 100, 3) == std::array<int, 2>{4, 1});
  CHECK(processor_grid(3, 2, 5) == std::array<int, 2>{1, 3});  // 3 x 1 has a block of no element
  CHECK_THROWS_WITH(processor_grid(7, 4, 4), Catch::Contains("cannot be cut into 7 blocks"));
  CHECK_THROWS_AS(processor_grid(0, 4, 4), std::invalid_argument);
}

TEST_CASE("element blocks tile the patch, as even as whole elements allow", "[partition]") {
  for (const auto& [P, nu, nv] :
       std::vector<std::array<int, 3>>{{2, 7, 3}, {3, 10, 10}, {4, 9, 5}, {6, 13, 4}}) {
    CAPTURE(P, nu, nv);
    std::vector<int> owner(static_cast<std::size_t>(nu * nv), -1);
    int smallest = nu * nv, largest = 0;
    for (int r = 0; r < P; ++r) {
      const ElementBlock b = element_block(r, P, nu, nv);
      CHECK(!b.whole());
      const int n = (b.u1 - b.u0) * (b.v1 - b.v0);
      smallest = std::min(smallest, n);
      largest = std::max(largest, n);
      for (int ev = 0; ev < nv; ++ev)
        for (int eu = 0; eu < nu; ++eu)
          if (b.contains(eu, ev)) {
            CHECK(owner[static_cast<std::size_t>(eu + nu * ev)] == -1);  // no element twice
            owner[static_cast<std::size_t>(eu + nu * ev)] = r;
          }
    }
    CHECK(std::count(owner.begin(), owner.end(), -1) == 0);  // none left out
    CHECK(smallest >= 1);
    const std::array<int, 2> g = processor_grid(P, nu, nv);
    // rows and columns differ by at most one element between blocks
    CHECK(largest <= (nu / g[0] + 1) * (nv / g[1] + 1));
  }
  CHECK(ElementBlock{}.whole());
  CHECK(element_block(1, 2, 4, 2).describe() == "elements [2, 4) x [0, 2)");
}

TEST_CASE(
    "a cut patch's control points: owned where their Greville point is, read by the blocks "
    "of their support",
    "[partition]") {
  // Degree 2 x 3, non-uniform knots with a double knot (a C^0 line) in u.
  const KnotVector U(2, {0, 0, 0, 0.1, 0.3, 0.3, 0.45, 0.7, 0.8, 1, 1, 1});
  const KnotVector V(3, {0, 0, 0, 0, 0.2, 0.5, 0.6, 0.9, 1, 1, 1, 1});
  const std::vector<double> bu = U.breaks(), bv = V.breaks();
  const int nu = U.num_elements(), nv = V.num_elements(), mu = U.num_basis();
  // whether basis i of W is non-zero inside element e (at its midpoint)
  const auto supports = [](const KnotVector& W, const std::vector<double>& b, int i, int e) {
    const double mid = 0.5 * (b[static_cast<std::size_t>(e)] + b[static_cast<std::size_t>(e) + 1]);
    return W[i] < mid && mid < W[i + W.degree() + 1];
  };
  for (const int P : {2, 3, 4, 6}) {
    CAPTURE(P);
    std::vector<std::vector<int>> owners(static_cast<std::size_t>(P));
    std::vector<std::vector<char>> reads(static_cast<std::size_t>(P));
    for (int r = 0; r < P; ++r)
      patch_point_partition(U, V, r, P, owners[static_cast<std::size_t>(r)],
                            reads[static_cast<std::size_t>(r)]);
    const std::vector<double> gu = U.greville(), gv = V.greville();
    for (int r = 0; r < P; ++r) {
      CHECK(owners[static_cast<std::size_t>(r)] == owners[0]);
      const ElementBlock b = element_block(r, P, nu, nv);
      for (int j = 0; j < V.num_basis(); ++j)
        for (int i = 0; i < mu; ++i) {
          const auto k = static_cast<std::size_t>(i + mu * j);
          bool read = false;
          for (int ev = b.v0; ev < b.v1; ++ev)
            for (int eu = b.u0; eu < b.u1; ++eu)
              read = read || (supports(U, bu, i, eu) && supports(V, bv, j, ev));
          CHECK(static_cast<bool>(reads[static_cast<std::size_t>(r)][k]) == read);
          // the owner's block holds the Greville point (u, v), and the owner reads the point
          const bool holds =
              bu[static_cast<std::size_t>(b.u0)] <= gu[static_cast<std::size_t>(i)] &&
              gu[static_cast<std::size_t>(i)] <= bu[static_cast<std::size_t>(b.u1)] &&
              bv[static_cast<std::size_t>(b.v0)] <= gv[static_cast<std::size_t>(j)] &&
              gv[static_cast<std::size_t>(j)] <= bv[static_cast<std::size_t>(b.v1)];
          if (owners[0][k] == r) {
            CHECK(holds);
            CHECK(read);
          }
        }
    }
  }
}

TEST_CASE("whole bodies go to the least loaded process, in order", "[partition]") {
  std::vector<double> load{10.0, 0.0, 0.0};
  CHECK(assign_whole({5.0, 5.0, 3.0, 4.0}, load) == std::vector<int>{1, 2, 1, 2});
  CHECK(load == std::vector<double>{10.0, 8.0, 9.0});
}

TEST_CASE("a model's parts over 2 and 3 processes add up to it: shell with friction on a CAD die",
          "[partition]") {
  for (int P : {2, 3}) check_parts("plate_on_die.json", 4, P);
}

TEST_CASE("a model's parts over 2 and 4 processes add up to it: plate indented by a sphere",
          "[partition]") {
  for (int P : {2, 4}) check_parts("indented_plate.json", 3, P);
  // with loads of every kind: split over the elements (surface) or added once (point, edge)
  const Json loads = Json::parse(R"([
    {"type": "point_force", "body": "plate", "at": [0.3, 0.6], "force": [0, 0, -0.02],
     "curve": "press"},
    {"type": "edge_load", "body": "plate", "edge": "u_min", "q": [0, 0, -0.01], "curve": "press"},
    {"type": "surface_load", "body": "plate", "q": [0, 0, -0.002], "curve": "press"}])");
  for (int P : {2, 3}) check_parts("indented_plate.json", 3, P, loads);
}

TEST_CASE(
    "a model's parts over 2 and 3 processes add up to it: a membrane tube inflated against a "
    "rigid wall",
    "[partition]") {
  // data/balloon.json (a quarter tube, follower pressure, symmetry edges) refined, with a
  // rigid plane 1.05 from its axis across the 45 degree line that the tube reaches at t ~ 0.3.
  const std::string path = kData + "balloon.json";
  Json doc = read_json_file(path);
  doc["geometry"]["tube"]["refine"]["subdivide"] = Json::array({8, 4});
  const double c = 1.05 / std::sqrt(2.0);
  doc["geometry"]["wall"] = {{"type", "plane"},
                             {"center", {c, c, 0.25}},
                             {"axis", {-1.0 / std::sqrt(2.0), -1.0 / std::sqrt(2.0), 0.0}}};
  doc["contact"] = Json::array({{{"type", "surface_to_rigid"},
                                 {"body", "tube"},
                                 {"rigid", "wall"},
                                 {"eps_N", 1000.0},
                                 {"face", "mid"},
                                 {"search_distance", 0.2}}});
  doc["loads"].push_back({{"type", "surface_load"}, {"body", "tube"}, {"q", {0.0, 0.0, -0.01}}});
  for (int P : {2, 3}) {
    CAPTURE(P);
    check_parts_of(doc, path, 2, P);
  }
}

TEST_CASE("a model's parts over 2 and 3 processes add up to it: two ropes, each whole on one",
          "[partition]") {
  // The penalty law, not the model's augmented Lagrange: the parts are assembled afresh at the
  // run's state, without its multipliers, and an augmented state's gaps are round-off that may
  // leave no point active (the round-off probe's seed 4 with libm's FMA paths masked did); a
  // penalty state's points penetrate by N / eps_N.
  const std::string path = kData + "two_ropes.json";
  Json doc = read_json_file(path);
  for (Json& c : doc["contact"]) {
    c["enforcement"] = "penalty";
    for (const char* key : {"penetration_tol", "max_augmentations", "slip_tol"}) c.erase(key);
  }
  for (int P : {2, 3}) {
    CAPTURE(P);
    check_parts_of(doc, path, 5, P);
  }
}

TEST_CASE("a shell cut over more processes than it has elements is refused at its surface",
          "[partition]") {
  const Json doc = read_json_file(kData + "indented_plate.json");
  const SerialCommunicator comm(0, 100000);
  CHECK_THROWS_WITH(Analysis::from_json(doc, "indented_plate.json", comm),
                    Catch::Contains("/bodies/plate/surface") &&
                        Catch::Contains("cannot be cut into 100000 blocks"));
}

TEST_CASE("the bound of a shell's control points is a process's: a shell too large for one",
          "[partition]") {
  // 300 x 300 bicubic elements: 91,809 control points, above the bound of one process, within
  // it on each of two (their halves touch 153 x 303 = 46,359). 400 x 400: 162,409 control
  // points, above it on each of three (the first block touches 137 x 403 = 55,211).
  Json doc = read_json_file(kData + "indented_plate.json");
  const std::string file = kData + "indented_plate.json";
  doc["geometry"]["plate"]["refine"]["subdivide"] = 300;
  CHECK_THROWS_WITH(Analysis::from_json(doc, file),
                    Catch::Contains("/bodies/plate/surface: the surface has 91809 control points, "
                                    "above the limit of 50000 of a shell body"));
  doc["geometry"]["plate"]["refine"]["subdivide"] = 400;
  const SerialCommunicator first(0, 3);
  CHECK_THROWS_WITH(Analysis::from_json(doc, file, first),
                    Catch::Contains("the part of process 0 of 3 (elements [0, 400) x [0, 134), "
                                    "55211 control points) is above the limit of 50000"));
}

}  // namespace test_partition_models
