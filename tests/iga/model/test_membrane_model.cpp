// Membranes through the model file (body type "membrane", iga/model/membrane_body.cpp) against
// closed forms: a cylindrical balloon inflated by a follower pressure (both laws; the NURBS
// circle is exact, so the discrete answer is the closed form's up to the solver's tolerance), a
// flat circular membrane under a uniform load against Hencky's solution (the Foeppl membrane
// equations solved here by shooting), a membrane pressed onto a rigid plane (STAS: the contact
// pressure is the load), and bad input named by its JSON path.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/refinement.hpp"
#include "iga/model/analysis.hpp"
#include "tests/iga/analysis_error.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_membrane_model {

using namespace iga;

namespace {

/// A quarter of a cylinder of radius 1 (axis z, 0.5 long) inflated by p: symmetry on its
/// straight edges, the ends held axially (plane strain, lambda_z = 1), a prestress n_0.
Json balloon(const Json& material, double p) {
  Json doc = Json::parse(R"({
    "format": "iga-contact-model", "version": 1, "name": "balloon",
    "geometry": {"tube": {"type": "construction", "shape": "cylinder", "center": [0, 0, 0],
                          "axis": [0, 0, 1], "ref_dir": [1, 0, 0], "radius": 1, "height": 0.5,
                          "start_deg": 0, "end_deg": 90,
                          "refine": {"elevate": [0, 1], "subdivide": [4, 2]}}},
    "bodies": {"tube": {"type": "membrane", "surface": "tube", "material": "skin"}},
    "boundary_conditions": [
      {"type": "symmetry", "body": "tube", "edge": "u_min", "normal": [0, 1, 0]},
      {"type": "symmetry", "body": "tube", "edge": "u_max", "normal": [1, 0, 0]},
      {"type": "simply_supported", "body": "tube", "edge": "v_min", "components": [2]},
      {"type": "simply_supported", "body": "tube", "edge": "v_max", "components": [2]}],
    "solver": {"t_end": 1, "initial_step": 0.25},
    "output": {"vtk": "none", "monitors": [{"name": "mid", "at": [0.5, 0.5]}]}})");
  doc["materials"]["skin"] = material;
  doc["loads"] = Json::array();
  doc["loads"].push_back({{"type", "pressure"}, {"body", "tube"}, {"p", p}});
  return doc;
}

/// The hoop stretch of the balloon's run: the monitored point's radius (reference 1).
double hoop_stretch(const Json& doc) {
  Analysis a = Analysis::from_json(doc, "balloon.json");
  const AnalysisResult r = a.run();
  REQUIRE(r.solver.converged());
  const Vector3d X(std::cos(std::numbers::pi / 4), std::sin(std::numbers::pi / 4), 0.25);
  const Vector3d x = X + r.steps.back().displacements.at(0);
  CHECK(std::abs(x.z() - 0.25) < 1e-10);  // plane strain
  return std::hypot(x.x(), x.y());
}

/// Hencky's flat circular membrane (radius a, clamped, uniform load q): the Foeppl equations
/// N'' + 3 N'/r = -E t q^2 / (8 N^2) for the radial force N(r), N'(0) = 0, a N'(a) + (1 - nu)
/// N(a) = 0 (no radial displacement at the edge), scaled by N = (E t q^2 a^2 / 8)^(1/3) n(r/a);
/// the centre deflection w_0 = a (q a / (E t))^(1/3) int_0^1 rho / n d rho. Returns the
/// coefficient int_0^1 rho / n d rho: n(0) by bisection on the edge condition, n by RK4 from a
/// series start n = n0 - rho^2 / (8 n0^2).
double hencky_coefficient(double nu) {
  const auto shoot = [](double n0, double nu_, double* integral) {
    constexpr int kSteps = 4000;
    const double h = 1.0 / kSteps;
    double r = h, n = n0 - r * r / (8 * n0 * n0), dn = -r / (4 * n0 * n0);
    double I = 0.5 * h * (r / n), prev = r / n;
    const auto f = [](double rr, double nn, double dd) {
      return std::array<double, 2>{dd, -1.0 / (nn * nn) - 3.0 * dd / rr};
    };
    for (int i = 1; i < kSteps; ++i) {
      const auto k1 = f(r, n, dn);
      const auto k2 = f(r + h / 2, n + h / 2 * k1[0], dn + h / 2 * k1[1]);
      const auto k3 = f(r + h / 2, n + h / 2 * k2[0], dn + h / 2 * k2[1]);
      const auto k4 = f(r + h, n + h * k3[0], dn + h * k3[1]);
      n += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]);
      dn += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
      r += h;
      if (!(n > 0.0)) return -1.0;  // n0 too small: the force runs out before the edge
      I += 0.5 * h * (prev + r / n);
      prev = r / n;
    }
    if (integral) *integral = I;
    return dn + (1.0 - nu_) * n;
  };
  double lo = 0.3, hi = 3.0;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid, nu, nullptr) < 0.0 ? lo : hi) = mid;
  }
  double I = 0.0;
  shoot(hi, nu, &I);
  return I;
}

/// The unit disc as one biquadratic rational patch (each edge of the parameter square a 90
/// degree arc, corners at 45 degrees), subdivided n x n, as a model's "nurbs_surface" entry.
Json disc(int n) {
  const double r = std::sqrt(0.5), w = std::sqrt(0.5);
  std::vector<Vector3d> P{{-r, -r, 0},   {0, -2 * r, 0}, {r, -r, 0},    {-2 * r, 0, 0}, {0, 0, 0},
                          {2 * r, 0, 0}, {-r, r, 0},     {0, 2 * r, 0}, {r, r, 0}};
  const std::vector<double> W{1, w, 1, w, 1, w, 1, w, 1};
  const NurbsSurface s =
      subdivide(NurbsSurface(2, {0, 0, 0, 1, 1, 1}, 2, {0, 0, 0, 1, 1, 1}, P, W), n, n);
  Json pts = Json::array();
  for (const Vector3d& x : s.control_points()) pts.push_back({x.x(), x.y(), x.z()});
  const std::vector<double> ku(s.knots_u().span().begin(), s.knots_u().span().end());
  const std::vector<double> kv(s.knots_v().span().begin(), s.knots_v().span().end());
  return {{"type", "nurbs_surface"},
          {"degree", {2, 2}},
          {"knots", {{"u", ku}, {"v", kv}}},
          {"control_points", pts},
          {"weights", s.weights()}};
}

}  // namespace

TEST_CASE(
    "membrane model: a cylindrical balloon inflated by a follower pressure keeps the "
    "closed-form stretch (St. Venant-Kirchhoff and neo-Hookean)",
    "[iga][membrane][model]") {
  const double n0 = 1e-6;  // the prestress (a flat or unstressed membrane has no normal stiffness)
  SECTION("neo-Hookean: p R = mu t (1 - lambda^-4) + n_0") {
    const double mu_t = 1.0, p = 0.5;
    const Json mat = {{"type", "membrane"},
                      {"law", "neo_hookean"},
                      {"mu", 50.0},
                      {"thickness", 0.02},
                      {"prestress", n0}};
    const double lambda = std::pow(1.0 - (p - n0) / mu_t, -0.25);
    const double l = hoop_stretch(balloon(mat, p));
    INFO("lambda " << l << ", closed form " << lambda);
    CHECK(std::abs(l / lambda - 1.0) < 1e-3);  // the issue's bound
    // The circle is exact in the NURBS space: what is left is the Newton tolerance (measured
    // 8e-7).
    CHECK(std::abs(l / lambda - 1.0) < 1e-5);
  }
  SECTION("St. Venant-Kirchhoff: p R = t E / (1 - nu^2) (lambda^2 - 1) / 2 + n_0") {
    const double E = 500.0, t = 0.02, nu = 0.3, p = 1.0;
    const Json mat = {
        {"type", "membrane"}, {"E", E}, {"nu", nu}, {"thickness", t}, {"prestress", n0}};
    const double lambda = std::sqrt(1.0 + 2.0 * (1.0 - nu * nu) * (p - n0) / (t * E));
    const double l = hoop_stretch(balloon(mat, p));
    INFO("lambda " << l << ", closed form " << lambda);
    CHECK(std::abs(l / lambda - 1.0) < 1e-3);
    CHECK(std::abs(l / lambda - 1.0) < 1e-5);  // measured 7e-7
  }
}

TEST_CASE(
    "membrane model: a clamped circular membrane under a uniform load deflects as "
    "Hencky's solution",
    "[iga][membrane][model]") {
  // w_0 / a about 0.02: the Foeppl equations (moderate rotations) and the finite-strain
  // membrane agree to O((w_0/a)^2) = 4e-4; the prestress n_0 = 1e-8 E t is 3e-5 of the centre
  // force. Measured: 7e-6 of Hencky's w_0 at 16 x 16 elements (the issue's bound: 0.5 %).
  const double nu = 0.3, Et = 1.0, w_target = 0.02;
  const double c = hencky_coefficient(nu);
  // Hencky's series as corrected (Chien; Fichter, NASA TP-3658, 1997) gives 0.653 at nu = 0.3.
  CHECK(c == Approx(0.653).epsilon(1e-3));
  const double q = Et * std::pow(w_target / c, 3.0);
  Json doc = Json::parse(R"({
    "format": "iga-contact-model", "version": 1, "name": "hencky",
    "materials": {"sheet": {"type": "membrane", "E": 1, "nu": 0.3, "thickness": 1,
                            "prestress": 1e-8}},
    "bodies": {"sheet": {"type": "membrane", "surface": "disc", "material": "sheet"}},
    "boundary_conditions": [
      {"type": "simply_supported", "body": "sheet", "edge": "u_min", "components": [0, 1, 2]},
      {"type": "simply_supported", "body": "sheet", "edge": "u_max", "components": [0, 1, 2]},
      {"type": "simply_supported", "body": "sheet", "edge": "v_min", "components": [0, 1, 2]},
      {"type": "simply_supported", "body": "sheet", "edge": "v_max", "components": [0, 1, 2]}],
    "solver": {"t_end": 1, "initial_step": 0.001, "max_iterations": 40},
    "output": {"vtk": "none", "monitors": [{"name": "centre", "at": [0.5, 0.5]}]}})");
  doc["geometry"]["disc"] = disc(16);
  doc["loads"] = Json::array();
  doc["loads"].push_back({{"type", "surface_load"}, {"body", "sheet"}, {"q", {0.0, 0.0, -q}}});
  Analysis a = Analysis::from_json(doc, "hencky.json");
  const AnalysisResult r = a.run();
  REQUIRE(r.solver.converged());
  const double w0 = -r.steps.back().displacements.at(0).z();
  const double hencky = c * std::cbrt(q / Et);
  INFO("w_0 " << w0 << ", Hencky " << hencky << " (" << r.steps.size() << " steps)");
  CHECK(std::abs(w0 / hencky - 1.0) < 5e-3);
}

TEST_CASE(
    "membrane model: a membrane pressed onto a rigid plane (STAS) sinks by q / eps_N and "
    "puts the whole load on the tool",
    "[iga][membrane][model][contact]") {
  // A unit square membrane, its lower face (thickness 0.1) on the plane z = 0, held in its
  // plane, pressed by q: the penalty law gives the pressure q at the gap -q / eps_N everywhere,
  // the membrane stays flat, and the tool carries q times the area.
  const double q = 2.0, eps_n = 1e4;
  Json doc = Json::parse(R"({
    "format": "iga-contact-model", "version": 1, "name": "pressed_membrane",
    "geometry": {
      "sheet": {"type": "construction", "shape": "plane", "origin": [0, 0, 0.05],
                "du": [1, 0, 0], "dv": [0, 1, 0], "refine": {"elevate": 1, "subdivide": 4}},
      "ground": {"type": "construction", "shape": "plane", "origin": [-1, -1, 0],
                 "du": [3, 0, 0], "dv": [0, 3, 0]}},
    "materials": {"sheet": {"type": "membrane", "E": 100, "nu": 0.3, "thickness": 0.1,
                            "prestress": 0.01}},
    "bodies": {"sheet": {"type": "membrane", "surface": "sheet", "material": "sheet"}},
    "boundary_conditions": [{"type": "fix", "body": "sheet", "points": "all",
                             "components": [0, 1]}],
    "contact": [{"type": "surface_to_rigid", "body": "sheet", "rigid": "ground", "eps_N": 1e4,
                 "face": "lower", "points_per_direction": 3}],
    "solver": {"t_end": 1, "initial_step": 0.5},
    "output": {"vtk": "none", "monitors": [{"name": "centre", "at": [0.5, 0.5]},
                                          {"name": "corner", "at": [0, 0]}]}})");
  doc["loads"] = Json::array();
  doc["loads"].push_back({{"type", "surface_load"}, {"body", "sheet"}, {"q", {0.0, 0.0, -q}}});
  Analysis a = Analysis::from_json(doc, "pressed_membrane.json");
  const AnalysisResult r = a.run();
  REQUIRE(r.solver.converged());
  const AnalysisStep& last = r.steps.back();
  for (const Vector3d& d : last.displacements) CHECK(d.z() == Approx(-q / eps_n).epsilon(1e-6));
  const Vector3d F = last.tool_loads.at(0).first;
  CHECK(F.z() == Approx(-q).epsilon(1e-8));  // q times the unit area, pushing the tool down
  CHECK(std::abs(F.x()) + std::abs(F.y()) < 1e-10);
  CHECK(last.contact.active == 16 * 9);  // every contact point of the 4 x 4 elements
}

TEST_CASE("membrane model: bad membrane input names the file, the JSON path and the value",
          "[iga][membrane][model]") {
  const Json base =
      balloon({{"type", "membrane"}, {"E", 1.0}, {"nu", 0.3}, {"thickness", 0.1}}, 0.1);
  using test::analysis_error;
  CHECK_THAT(analysis_error(base, [](Json& d) { d["materials"]["skin"]["nu"] = 0.7; }),
             Catch::Contains("m.json: /materials/skin/nu: must be in (-1, 0.5], got 0.7"));
  CHECK_THAT(analysis_error(base, [](Json& d) { d["materials"]["skin"]["mu"] = 1.0; }),
             Catch::Contains("/materials/skin/mu: belongs to \"law\": \"neo_hookean\""));
  CHECK_THAT(analysis_error(base,
                            [](Json& d) {
                              d["materials"]["skin"]["law"] = "neo_hookean";
                              d["materials"]["skin"].erase("nu");
                            }),
             Catch::Contains("/materials/skin: a neo-Hookean membrane"));
  CHECK_THAT(analysis_error(base, [](Json& d) { d["loads"][0]["type"] = "edge_load"; }),
             Catch::Contains("/loads/0/type: expected one of \"surface_load\", \"pressure\""));
  CHECK_THAT(analysis_error(base, [](Json& d) { d["boundary_conditions"][0]["type"] = "clamp"; }),
             Catch::Contains("/boundary_conditions/0/type: expected one of"));
  CHECK_THAT(
      analysis_error(base,
                     [](Json& d) {
                       d["materials"]["skin"] = {{"type", "rod"}, {"EA", 1}, {"EI", 1}};
                     }),
      Catch::Contains("/bodies/tube/material: names a material of type \"rod\"; a membrane needs "
                      "type \"membrane\""));
  CHECK_THAT(
      analysis_error(base, [](Json& d) { d["bodies"]["tube"]["type"] = "balloon"; }),
      Catch::Contains("/bodies/tube/type: expected one of \"membrane\", \"rod\", \"shell\""));
}

}  // namespace test_membrane_model
