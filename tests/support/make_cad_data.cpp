// Writes the CAD files of data/cad with OpenCASCADE's modelling API and writers (issue 15):
//   make_cad_data DIR      (scripts/make_cad_data.sh runs it on data/cad)
// cylinder.step / .igs   the capstan's drum: R = 1, height 3, axis e_z from z = -1.5, seam at -e_y
//                        (data/capstan.json, "cylinder_step")
// torus.step             R = 3, r = 1 about e_z
// bspline_face.step      a rational bicubic-by-quadratic face with a double knot
// plate_with_hole.step   a square plate of side 4 with a hole of radius 1 (trimmed)
// sheave_v30.step        a sheave with a V-groove of half-angle 30 degrees (root radius 1)
// die_fillet.step        a die 4 x 4 x 1, top at z = 0, its top edges filleted (r = 0.5)
//                        (data/plate_on_die.json)
// die_fillet_split.step  the same die split by the planes x = 0.37 and y = -0.61: the same
//                        geometry in more faces (seams across the top and the fillets)
// Lengths in mm (STEP's unit here); a model reads them with "unit" as it needs.
#include <filesystem>
#include <iostream>
#include <numbers>

#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>

#include "cad/cad_import.hpp"
#include "tests/support/cad_samples.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_cad_data DIR\n";
    return 2;
  }
  try {
    using iga::test::frame;
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    BRepPrimAPI_MakeCylinder cyl =
        BRepPrimAPI_MakeCylinder(frame({0, 0, -1.5}, {0, 0, 1}, {0, -1, 0}), 1.0, 3.0);
    iga::test::write_step(cyl.Shape(), (dir / "cylinder.step").string());
    iga::test::write_iges(cyl.Shape(), (dir / "cylinder.igs").string());
    iga::test::write_step(
        BRepPrimAPI_MakeTorus(frame({0, 0, 0}, {0, 0, 1}, {1, 0, 0}), 3.0, 1.0).Shape(),
        (dir / "torus.step").string());
    iga::test::write_step(iga::test::bspline_face(), (dir / "bspline_face.step").string());
    iga::test::write_step(iga::test::plate_with_hole(4.0, 1.0),
                          (dir / "plate_with_hole.step").string());
    iga::test::write_step(iga::test::sheave(1.6, 0.6, 1.0, std::numbers::pi / 6),
                          (dir / "sheave_v30.step").string());
    iga::test::write_step(iga::test::filleted_die(4.0, 1.0, 0.5),
                          (dir / "die_fillet.step").string());
    iga::test::write_step(iga::test::split_xy(iga::test::filleted_die(4.0, 1.0, 0.5), 0.37, -0.61),
                          (dir / "die_fillet_split.step").string());
    for (const auto& f : std::filesystem::directory_iterator(dir)) {
      std::cout << f.path().filename().string() << ":\n";
      for (const iga::CadFace& face : iga::list_cad_faces(f.path().string()))
        std::cout << "  face " << face.index << ": " << face.cad_type
                  << (face.trimmed ? ", trimmed" : "") << ", area " << face.area << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "make_cad_data: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
