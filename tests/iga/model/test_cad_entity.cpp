// The "cad" geometry entity (issue 15, item 1): a rigid tool from a STEP or IGES file in a
// model. The capstan on the drum read from data/cad/cylinder.step (made by
// scripts/make_cad_data.sh) gives the T/T0 of the built-in analytic cylinder; bad entries are
// located errors.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "iga/model/analysis.hpp"
#include "iga/model/model.hpp"
#include "tests/iga/analysis_error.hpp"
#include "tests/support/files.hpp"

using namespace iga;

namespace {
const std::string kData = std::string(IGA_SOURCE_DIR) + "/data/";

/// data/capstan.json with the drum of data/cad/cylinder.step as "cylinder_step" (the side face;
/// the end discs are trimmed faces), found relative to the model file in data/.
Json capstan_with_step() {
  Json doc = read_json_file(kData + "capstan.json");
  doc["geometry"]["cylinder_step"] = {
      {"type", "cad"}, {"file", "cad/cylinder.step"}, {"faces", {0}}};
  return doc;
}
}  // namespace

TEST_CASE("cad entity: the capstan on the drum read from STEP gives the analytic cylinder's T/T0",
          "[iga][analysis][cad]") {
  const Json base = test::cubic_penalty_capstan(capstan_with_step());
  const Model m = parse_model(base, kData + "capstan.json");
  // The entity is a patch group of its faces, each named <name>.face<k>.
  const auto* group = std::get_if<PatchGroup>(m.geometry.find("cylinder_step"));
  REQUIRE(group != nullptr);
  CHECK(group->patches == std::vector<std::string>{"cylinder_step.face0"});
  CHECK(std::holds_alternative<Cylinder>(*m.geometry.find("cylinder_step.face0")));

  Json analytic = base, step = base;
  analytic["contact"][0]["rigid"] = "cylinder_analytic";
  step["contact"][0]["rigid"] = "cylinder_step";
  // (the file is found relative to the model file's folder)
  const AnalysisResult ra = Analysis::from_json(analytic, kData + "capstan.json").run();
  const AnalysisResult rs = Analysis::from_json(step, kData + "capstan.json").run();
  REQUIRE(ra.full_slip);
  REQUIRE(rs.full_slip);
  const double T0 = 10.0;
  const double ta = ra.steps.back().reactions.at(0).norm() / T0;
  const double ts = rs.steps.back().reactions.at(0).norm() / T0;
  INFO("T/T0 analytic " << ta << ", from STEP " << ts << ", exp(mu pi) " << std::exp(0.3 * M_PI));
  // The same surface up to the 12 digits the STEP file prints: T/T0 to 1e-9.
  CHECK(std::abs(ts / ta - 1.0) < 1e-9);
  CHECK(std::abs(ts / std::exp(0.3 * M_PI) - 1.0) < 0.005);
}

TEST_CASE("cad entity: bad entries name the model file, the JSON path and the CAD file",
          "[iga][analysis][cad][errors]") {
  const Json base = capstan_with_step();
  auto error = [&](auto&& edit) {
    Json doc = base;
    edit(doc["geometry"]["cylinder_step"]);
    try {
      (void)parse_model(doc, kData + "m.json");
    } catch (const ModelError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK_THAT(error([](Json& e) { e["file"] = "cad/none.step"; }),
             Catch::Contains("m.json: /geometry/cylinder_step/file: ") &&
                 Catch::Contains("cad/none.step: no such file"));
  CHECK_THAT(error([](Json& e) { e["file"] = "capstan.json"; }),
             Catch::Contains("not a CAD file this program reads"));
  CHECK_THAT(error([](Json& e) { e["faces"] = Json::array({5}); }),
             Catch::Contains("face 5 does not exist (the file has 3 faces"));
  CHECK(error([](Json& e) { e.erase("faces"); }) == "no error");  // trimmed end discs too
  CHECK_THAT(error([](Json& e) { e["faces"] = Json::array({-1}); }),
             Catch::Contains("/geometry/cylinder_step/faces/0: face numbers start at 0"));
  CHECK_THAT(error([](Json& e) { e["unit"] = "furlong"; }),
             Catch::Contains("/geometry/cylinder_step/unit"));
  CHECK_THAT(error([](Json& e) { e["scale"] = 2; }),
             Catch::Contains("/geometry/cylinder_step/scale"));
  CHECK_THAT(
      error([](Json& e) {
        e["placement"] = {{"rotation", {{"point", {0, 0, 0}}, {"axis", {0, 0, 0}}, {"angle", 1}}}};
      }),
      Catch::Contains("/geometry/cylinder_step/placement/rotation/axis: must not be zero"));
  {  // a face name already taken
    Json doc = base;
    doc["geometry"]["cylinder_step.face0"] = doc["geometry"]["cylinder_analytic"];
    CHECK_THROWS_WITH(parse_model(doc, kData + "m.json"),
                      Catch::Contains("the entity \"cylinder_step.face0\" it makes is already a "
                                      "name of this section"));
  }
}

TEST_CASE("cad entity: a rope lying across the hole of a plate read from STEP sags into it",
          "[iga][analysis][cad][trimmed]") {
  // data/cad/plate_with_hole.step: a square plate of side 4 (z = 0) with a hole of radius 1 at
  // its centre, a trimmed plane. A rod along the x axis (EI = 1, radius 0.02) from x = -1.9 to
  // 1.9, pinned at both ends on the plate, under its weight q = 1 per length. Over the plate the
  // rope rests on it (centre line at z = r); over the hole nothing holds it: it sags into the
  // hole, below the plate's surface. The same rope on the untrimmed plane stays on top.
  const double r = 0.02;
  Json doc = Json::parse(R"({
    "format": "iga-contact-model", "version": 1, "name": "rope_over_hole",
    "geometry": {
      "plate": {"type": "cad", "file": "cad/plate_with_hole.step"},
      "floor": {"type": "plane", "center": [0, 0, 0], "axis": [0, 0, 1]},
      "rope": {"type": "construction", "shape": "line", "start": [-1.9, 0, 0.02],
               "end": [1.9, 0, 0.02], "degree": 3, "elements": 38}
    },
    "materials": {"rope": {"type": "rod", "EA": 1000.0, "EI": 1.0}},
    "bodies": {"rope": {"type": "rod", "curve": "rope", "material": "rope"}},
    "boundary_conditions": [{"type": "fix", "body": "rope", "points": ["start", "end"]},
                            {"type": "fix", "body": "rope", "points": "all", "components": [1]}],
    "loads": [{"type": "line_load", "body": "rope", "q": [0, 0, -1]}],
    "contact": [{"type": "curve_to_rigid", "body": "rope", "rigid": "plate", "eps_N": 1e5,
                 "radius": 0.02, "points_per_element": 4}],
    "solver": {"t_end": 1, "initial_step": 0.1, "max_step": 0.25},
    "output": {"monitors": [{"name": "mid", "at": 0.5}, {"name": "over_plate", "at": 0.1}]}
  })");
  Analysis holed = Analysis::from_json(doc, kData + "rope_over_hole.json");
  doc["contact"][0]["rigid"] = "floor";
  Analysis flat = Analysis::from_json(doc, kData + "rope_over_hole.json");
  const AnalysisResult rh = holed.run(), rf = flat.run();
  REQUIRE(rh.solver.status == NonlinearSolverStatus::converged);
  REQUIRE(rf.solver.status == NonlinearSolverStatus::converged);
  const double z_mid_hole = r + rh.steps.back().displacements.at(0).z();
  const double z_mid_flat = r + rf.steps.back().displacements.at(0).z();
  const double z_side_hole = r + rh.steps.back().displacements.at(1).z();
  INFO("centre line height at the middle: over the hole " << z_mid_hole << ", on the plain plane "
                                                          << z_mid_flat << "; over the plate "
                                                          << z_side_hole);
  CHECK(z_mid_hole < 0.0);                 // into the hole
  CHECK(std::abs(z_mid_flat - r) < 1e-3);  // on the whole plane: resting on it
  // Over the plate the rope is held above it (no penetration beyond eps_N's); next to the rim
  // it lifts a little, as a beam bent over a support does.
  CHECK(z_side_hole > r - 1e-3);
  CHECK(z_side_hole < r + 0.01);
}

TEST_CASE("cad entity: a plate pressed onto a filleted die read from STEP (data/plate_on_die.json)",
          "[iga][analysis][cad][trimmed]") {
  // The die's top is flat (3 x 3), its edges filleted (trimmed cylinders). Under the uniform
  // load q = 1 the plate rests on the flat top: there the contact pressure is q and the lower
  // face sits q / eps_N below the die (penalty), 1e-4 + 1e-4 below where it started. The
  // overhang bends down over the fillets; the problem is symmetric.
  const std::string dir = test::fresh_out_dir("cad_entity", "plate_on_die");
  Json doc = read_json_file(kData + "plate_on_die.json");
  doc["output"]["monitors"].push_back({{"name", "xm"}, {"at", {0.0, 0.5}}});
  doc["output"]["monitors"].push_back({{"name", "yp"}, {"at", {0.5, 1.0}}});
  Analysis a = Analysis::from_json(doc, kData + "plate_on_die.json");
  const AnalysisResult r = a.run(nullptr, dir);
  REQUIRE(r.solver.status == NonlinearSolverStatus::converged);
  const auto& d = r.steps.back().displacements;  // centre, edge_mid (x = +1.8), xm, yp
  CHECK(d.at(0).z() == Approx(-2e-4).epsilon(0.01));
  // The overhang at the four edge midpoints alike (measured: x -0.05871 / -0.05866, y -0.05869).
  CHECK(d.at(1).z() == Approx(d.at(3).z()).epsilon(0.005));
  CHECK(d.at(2).z() == Approx(d.at(3).z()).epsilon(0.005));
  CHECK(d.at(1).z() < -0.03);  // bent down over the fillet
  // The pressure on the middle of the flat top is q.
  const std::string vtk = test::slurp(dir + "/last_shell.vtk");
  const std::vector<double> x = test::vtk_points(vtk);
  const std::vector<double> p = test::vtk_array(vtk, "SCALARS", "contact_pressure");
  REQUIRE(p.size() * 3 == x.size());
  int n = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::abs(x[3 * i]) < 0.5 && std::abs(x[3 * i + 1]) < 0.5) {
      ++n;
      CHECK(p[i] == Approx(1.0).epsilon(0.02));
    }
  CHECK(n > 100);
}
