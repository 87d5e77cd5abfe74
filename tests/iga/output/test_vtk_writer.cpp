// The VTK writers produce files ParaView reads: structure and values checked by parsing back.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "iga/output/vtk_writer.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_vtk_writer {

using namespace iga;
namespace fs = std::filesystem;

namespace {
using iga::test::slurp;
}  // namespace

TEST_CASE("write_vtk_polydata: polyline with scalar and vector point data", "[iga][output]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_vtk_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::vector<Eigen::Vector3d> pts = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}};
  VtkPointData d;
  d.scalars.push_back({"tension", {1.5, 2.5, 3.5}});
  d.vectors.push_back({"force", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});
  write_vtk_polydata((dir / "rope.vtk").string(), pts, true, d);
  const std::string s = slurp(dir / "rope.vtk");
  CHECK_THAT(s, Catch::StartsWith("# vtk DataFile Version 3.0"));
  CHECK_THAT(s, Catch::Contains("POINTS 3 double\n0 0 0\n1 0 0\n1 2 0\n"));
  CHECK_THAT(s, Catch::Contains("LINES 1 4\n3 0 1 2\n"));
  CHECK_THAT(s, Catch::Contains("SCALARS tension double 1\nLOOKUP_TABLE default\n1.5\n2.5\n3.5\n"));
  CHECK_THAT(s, Catch::Contains("VECTORS force double\n1 0 0\n0 1 0\n0 0 1\n"));
  write_vtk_polydata((dir / "cloud.vtk").string(), pts, false);
  CHECK_THAT(slurp(dir / "cloud.vtk"), Catch::Contains("VERTICES 3 6\n1 0\n1 1\n1 2\n"));
  d.scalars.push_back({"bad", {1.0}});
  CHECK_THROWS_WITH(write_vtk_polydata((dir / "x.vtk").string(), pts, true, d),
                    Catch::Contains("field 'bad' has 1 values for 3 points"));
  CHECK_THROWS(write_vtk_polydata("/nonexistent/dir/x.vtk", pts, true));
  VtkCollection pvd((dir / "run.pvd").string());
  pvd.add(0.5, "rope_0001.vtk");
  pvd.add(1.0, "rope_0002.vtk");
  const std::string c = slurp(dir / "run.pvd");
  CHECK_THAT(c, Catch::Contains("<DataSet timestep=\"0.5\" part=\"0\" file=\"rope_0001.vtk\"/>"));
  CHECK_THAT(c, Catch::Contains("<DataSet timestep=\"1\" part=\"0\" file=\"rope_0002.vtk\"/>"));
  fs::remove_all(dir);
}

TEST_CASE("write_vtk_grid: quadrilaterals of a structured grid", "[iga][output]") {
  const fs::path dir = fs::temp_directory_path() / ("iga_vtk_grid_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::vector<Eigen::Vector3d> pts;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i) pts.emplace_back(i, j, 0.0);
  VtkPointData d;
  d.scalars.push_back({"z", std::vector<double>(6, 0.5)});
  write_vtk_grid((dir / "grid.vtk").string(), pts, 3, 2, d);
  const std::string s = slurp(dir / "grid.vtk");
  CHECK_THAT(s, Catch::Contains("POINTS 6 double\n"));
  CHECK_THAT(s, Catch::Contains("POLYGONS 2 10\n4 0 1 4 3\n4 1 2 5 4\n"));
  CHECK_THAT(s, Catch::Contains("POINT_DATA 6\nSCALARS z double 1\n"));
  CHECK_THROWS_WITH(write_vtk_grid((dir / "bad.vtk").string(), pts, 2, 2),
                    Catch::Contains("a grid of 2 x 2 needs that many points, got 6"));
  fs::remove_all(dir);
}

TEST_CASE("write_vtk_polydata: non-finite values are written as 0 with the flag non_finite",
          "[iga][output]") {
  const std::string path =
      (fs::temp_directory_path() / ("iga_vtk_non_finite_" + std::to_string(::getpid()) + ".vtk"))
          .string();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector3d> pts = {{0, 0, 0}, {1, inf, 0}, {2, 0, 0}};
  VtkPointData d;
  d.scalars = {{"s", {1.0, 2.0, std::nan("")}}};
  d.vectors = {
      {"v", {Eigen::Vector3d(0, 0, -inf), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}}};
  write_vtk_polydata(path, pts, true, d);
  const std::string text = iga::test::slurp(path);
  for (const char* w : {"nan", "inf", "NaN", "Inf"}) CHECK(text.find(w) == std::string::npos);
  CHECK(text.find("1 0 0\n") != std::string::npos);  // the point with y = inf
  CHECK(text.find("SCALARS non_finite double 1\nLOOKUP_TABLE default\n1\n1\n1\n") !=
        std::string::npos);
  // Finite data: no flag field.
  write_vtk_polydata(path, {{0, 0, 0}, {1, 0, 0}}, true, {});
  CHECK(iga::test::slurp(path).find("non_finite") == std::string::npos);
  std::filesystem::remove(path);
}

}  // namespace test_vtk_writer
