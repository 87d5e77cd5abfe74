// CAD files for the tests of issue 15, made with OpenCASCADE's own modelling API and written
// with its STEP and IGES writers (no file is written by hand): solids of revolution, a
// B-spline face, a plate with a hole, a sheave with a V-groove. tests/support/make_cad_data.cpp
// writes the ones in data/cad (scripts/make_cad_data.sh).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>

namespace iga::test {

gp_Ax2 frame(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis,
             const Eigen::Vector3d& x_dir);

/// Writes the shape (lengths in mm, OCCT's unit); throws std::runtime_error on failure.
void write_step(const TopoDS_Shape& shape, const std::string& path);
/// IGES in B-rep mode (faces with their trimming), lengths in mm.
void write_iges(const TopoDS_Shape& shape, const std::string& path);

/// A rational B-spline face of degrees (3, 2), 6 x 5 poles (a wavy rectangle 4 x 3), with
/// a double inner knot in u; `periodic` makes it periodic in u instead (a closed tube).
TopoDS_Face bspline_face(bool periodic = false);
/// A square plate of side `a` in the plane z = 0 (centred at the origin) with a round hole of
/// radius `r` at its centre: one planar face with two wires.
TopoDS_Face plate_with_hole(double a, double r);
/// A sheave: a disc of outer radius R_out about the z axis, width 2 w, with a V-groove of
/// half-angle `alpha` (radians) whose flanks meet at radius R_root (or a flat bottom of half
/// width `flat` there), revolved from its profile.
TopoDS_Shape sheave(double R_out, double w, double R_root, double alpha, double flat = 0.0);
/// A die: the box [-a/2, a/2]^2 x [-height, 0] with the four edges of its top face filleted
/// (radius r, OCCT's BRepFilletAPI_MakeFillet): a flat top, four cylindrical fillets mitred at
/// the corners, the sides.
TopoDS_Shape filleted_die(double a, double height, double r);
/// The shape's shells split by the planes x = x_s and y = y_s (OCCT's BRepAlgoAPI_Splitter):
/// the same surface in more faces, with seams where the planes cut it.
TopoDS_Shape split_xy(const TopoDS_Shape& shape, double x_s, double y_s);

}  // namespace iga::test
