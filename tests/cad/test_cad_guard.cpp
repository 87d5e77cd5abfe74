// Issue 34: a CAD file never kills the program (broken files are CadErrors naming the file, a
// crash inside OpenCASCADE included), listing is not conversion (every face listed, a face that
// does not convert has its message), units are shown and bad ones refused, numbers beyond the
// model bounds are refused, and what OpenCASCADE skipped is a warning (an error when strict).
// The broken files are made here from data/cad and tests/data/cad/occt/screw.step (a public
// OCCT test file, see its README).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Pln.hxx>

#include "cad/cad_import.hpp"
#include "tests/support/cad_samples.hpp"
#include "tests/support/files.hpp"

// The file's names, apart from its neighbours in the unity build (tests/CMakeLists.txt).
namespace test_cad_guard {

using namespace iga;
using Catch::Matchers::Contains;

namespace {

const std::string kCylinder = std::string(IGA_SOURCE_DIR) + "/data/cad/cylinder.step";
const std::string kCylinderIges = std::string(IGA_SOURCE_DIR) + "/data/cad/cylinder.igs";
const std::string kScrew = std::string(IGA_SOURCE_DIR) + "/tests/data/cad/occt/screw.step";

std::string out_dir(const std::string& name) {
  const std::string d = test::fresh_out_dir("cad_guard", name);
  std::filesystem::create_directories(d);
  return d;
}

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}
std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& l : lines) s += l + "\n";
  return s;
}

/// The text without its n-th (from 1) one-line entity that contains `what` (e.g. a
/// CARTESIAN_POINT): the entities referring to it then refer to nothing.
std::string without_entity(const std::string& text, const std::string& what, int n = 1) {
  std::vector<std::string> lines = lines_of(text);
  int seen = 0;
  const auto it = std::find_if(lines.begin(), lines.end(), [&](const std::string& l) {
    return l.rfind('#', 0) == 0 && l.find(what) != std::string::npos &&
           l.find(");") != std::string::npos && ++seen == n;
  });
  REQUIRE(it != lines.end());
  lines.erase(it);
  return joined(lines);
}

/// The text with its one `from` replaced by `to`.
std::string with_replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  REQUIRE(text.find(from, at + 1) == std::string::npos);
  return text.replace(at, from.size(), to);
}

/// The text cut after `fraction` of its bytes, optionally closed as a STEP file ends.
std::string truncated(const std::string& text, double fraction, bool closed) {
  std::string s = text.substr(0, static_cast<std::size_t>(fraction * text.size()));
  if (closed) s += "\nENDSEC;\nEND-ISO-10303-21;\n";
  return s;
}

/// data/cad/cylinder.step (lengths in mm) with its length unit declared as `factor` mm, a
/// conversion based unit named `name`.
std::string with_unit(const std::string& text, const std::string& name, const std::string& factor) {
  const std::string si = "LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );";
  std::vector<std::string> lines = lines_of(text);
  const auto it = std::find_if(lines.begin(), lines.end(), [&](const std::string& l) {
    return l.find(si) != std::string::npos;
  });
  REQUIRE(it != lines.end());
  const std::string label = it->substr(0, it->find(' '));
  *it = label + " = ( CONVERSION_BASED_UNIT('" + name +
        "',#9001) LENGTH_UNIT() NAMED_UNIT(#9002) );\n" +
        "#9001 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(" + factor + "),#9003);\n" +
        "#9002 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n" + "#9003 = ( " + si;
  return joined(lines);
}

/// Bytes that are no CAD file: a JPEG header and noise.
std::string binary_noise() {
  std::string s = "\xFF\xD8\xFF\xE0";
  s += std::string("\x00\x10JFIF\x00", 7);
  std::mt19937 rng(34);
  for (int i = 0; i < 4096; ++i) s += static_cast<char>(rng() & 0xFF);
  return s;
}

}  // namespace

TEST_CASE("cad guard: broken files are CadErrors naming the file, never a crash", "[cad]") {
  const std::string dir = out_dir("broken");
  const std::string cylinder = test::slurp(kCylinder), screw = test::slurp(kScrew);
  std::vector<std::string> files;
  auto make = [&](const std::string& name, const std::string& text) {
    write(dir + "/" + name, text);
    files.push_back(dir + "/" + name);
  };
  make("cylinder_truncated.step", truncated(cylinder, 0.5, false));
  make("cylinder_truncated_closed.step", truncated(cylinder, 0.5, true));
  make("screw_truncated.step", truncated(screw, 0.45, false));
  make("screw_truncated_closed.step", truncated(screw, 0.45, true));
  make("cylinder_missing_point.step", without_entity(cylinder, "CARTESIAN_POINT"));
  make("cylinder_missing_center.step", without_entity(cylinder, "CARTESIAN_POINT", 3));
  make("cylinder_wrong_type_first.step", with_replaced(cylinder, "#26 = AXIS2_PLACEMENT_3D('',#27,",
                                                       "#26 = AXIS2_PLACEMENT_3D('',#28,"));
  make("screw_missing_point.step", without_entity(screw, "CARTESIAN_POINT"));
  make("photo.step", binary_noise());
  make("photo.igs", binary_noise());
  make("empty.step", "");
  make("cylinder_truncated.igs", truncated(test::slurp(kCylinderIges), 0.5, false));
  for (const std::string& f : files) {
    INFO(f);
    // The listing and the import, each read in its own child process.
    CHECK_THROWS_WITH(list_cad(f), Contains(f));
    CHECK_THROWS_WITH(import_cad(f, "x"), Contains(f));
  }
  // The top circle's placement (#26) given a direction (#28) for its location: OpenCASCADE
  // 7.6 reads the file, skips the wrong reference and crashes in the transfer (StepToGeom);
  // reported with its signal (or, where a sanitizer reports the crash itself, with the reader
  // process's exit status), and this process goes on.
  const std::string crash = dir + "/cylinder_wrong_type.step";
  write(crash, with_replaced(cylinder, "#26 = AXIS2_PLACEMENT_3D('',#27,",
                             "#26 = AXIS2_PLACEMENT_3D('',#28,"));
  for (int pass = 0; pass < 2; ++pass) {
    std::string what = "no error";
    try {
      if (pass == 0) (void)import_cad(crash, "x");
      if (pass == 1) (void)list_cad(crash);
    } catch (const CadError& e) {
      what = e.what();
    }
    INFO(what);
    CHECK((what == "OpenCASCADE crashed (signal 11, SIGSEGV) while reading " + crash ||
           what.find("OpenCASCADE failed (its reader process ended with status") == 0));
  }
  // Findings of fuzz/fuzz_cad.cpp: a stack overflow inside OpenCASCADE, and a null handle it
  // dereferences (a 2D line's point of an unknown entity type, StepToGeom::MakeLine2d).
  for (const char* name : {"fuzz_crash_oriented_edge.step", "fuzz_crash_pcurve_point.step"}) {
    const std::string found = std::string(IGA_SOURCE_DIR) + "/tests/data/cad/" + name;
    for (int pass = 0; pass < 2; ++pass) {
      std::string what = "no error";
      try {
        if (pass == 0) (void)import_cad(found, "x");
        if (pass == 1) (void)list_cad(found);
      } catch (const CadError& e) {
        what = e.what();
      }
      INFO(what);
      CHECK((what == "OpenCASCADE crashed (signal 11, SIGSEGV) while reading " + found ||
             what.find("OpenCASCADE failed (its reader process ended with status") == 0 ||
             (what != "no error" && what.find(found) != std::string::npos)));
    }
  }
  CHECK_THROWS_WITH(list_cad(dir + "/empty.step"), Contains("empty"));
  // A folder named like a CAD file.
  std::filesystem::create_directories(dir + "/folder.step");
  CHECK_THROWS_WITH(list_cad(dir + "/folder.step"), Contains("is a directory"));
  CHECK_THROWS_WITH(import_cad(dir + "/folder.step", "x"), Contains("is a directory"));
  // The good files still read after all this.
  CHECK(import_cad(kCylinder, "x").entities.size() == 3);
}

TEST_CASE("cad guard: the listing lists every face, a face that does not convert with its reason",
          "[cad]") {
  SECTION("screw.step (OCCT's test data): every face with its type and a result or a reason") {
    const CadListing l = list_cad(kScrew);
    CHECK(l.format == "step");
    REQUIRE(l.faces.size() == 10);
    for (std::size_t k = 0; k < l.faces.size(); ++k) {
      const CadFace& f = l.faces[k];
      INFO("face " << k << ": " << f.cad_type << " -> " << f.entity_type << " / " << f.message);
      CHECK(f.index == static_cast<int>(k));
      CHECK(!f.cad_type.empty());
      CHECK(f.entity_type.empty() != f.message.empty());  // one of them
      CHECK(f.wires >= 1);
    }
    CHECK(l.warnings.empty());
  }
  SECTION("a face beyond the model bounds has its message, the other face converts") {
    // Two unit squares, at z = 0 and z = 5.5, written by OpenCASCADE; then the second moved to
    // z = 1e120 in the text (|x| <= 1e100 in a model; OpenCASCADE's writer drops such a face).
    const std::string dir = out_dir("bounds");
    TopoDS_Compound c;
    BRep_Builder b;
    b.MakeCompound(c);
    for (const double z : {0.0, 5.5})
      b.Add(c,
            BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, z), gp_Dir(0, 0, 1)), 0, 1, 0, 1).Face());
    const std::string near = dir + "/near.step", path = dir + "/far.step";
    test::write_step(c, near);
    std::string text = test::slurp(near);
    int moved = 0;
    for (std::size_t at; (at = text.find(",5.5)")) != std::string::npos; ++moved)
      text.replace(at, 5, ",1.E+120)");
    REQUIRE(moved >= 4);  // its corners at least
    write(path, text);
    const CadListing l = list_cad(path);
    REQUIRE(l.faces.size() == 2);
    CHECK(l.faces[0].entity_type == "plane");
    CHECK(l.faces[0].message.empty());
    CHECK(l.faces[1].cad_type == "plane");
    CHECK(l.faces[1].entity_type.empty());
    CHECK_THAT(l.faces[1].message, Contains("beyond the model bounds"));
    // The import of that face is an error naming file and face; of the other face, fine.
    CHECK_THROWS_WITH(import_cad(path, "x"),
                      Contains(path) && Contains("face 1") && Contains("beyond the model bounds"));
    CadOptions first;
    first.faces = {0};
    CHECK(import_cad(path, "x", first).entities.size() == 1);
  }
}

TEST_CASE("cad guard: the file's length unit is shown, and refused unless a length", "[cad]") {
  const std::string dir = out_dir("units");
  const std::string cylinder = test::slurp(kCylinder);
  const CadListing mm = list_cad(kCylinder);
  CHECK(mm.units.file_unit_mm == Approx(1.0).epsilon(1e-15));
  CHECK(mm.units.factor == Approx(1.0).epsilon(1e-15));
  REQUIRE(!mm.units.names.empty());
  CHECK(mm.units.names.front() == "millimetre");
  CHECK(list_cad(kCylinder, "m").units.factor == Approx(1e-3).epsilon(1e-15));

  // The same numbers declared in inches: 25.4 times the lengths in mm, the same in "in".
  const std::string inch = dir + "/cylinder_inch.step";
  write(inch, with_unit(cylinder, "INCH", "25.4"));
  const CadListing in = list_cad(inch);
  CHECK(in.units.names.front() == "INCH");
  CHECK(in.units.file_unit_mm == Approx(25.4).epsilon(1e-15));
  CHECK(in.units.factor == Approx(25.4).epsilon(1e-15));
  const CadListing in_in = list_cad(inch, "in");
  CHECK(in_in.units.factor == Approx(1.0).epsilon(1e-15));
  REQUIRE(in.faces.size() == mm.faces.size());
  for (std::size_t k = 0; k < mm.faces.size(); ++k) {
    const Eigen::Vector3d size_mm = mm.faces[k].box_hi - mm.faces[k].box_lo;
    const Eigen::Vector3d size_in = in.faces[k].box_hi - in.faces[k].box_lo;
    const Eigen::Vector3d size_in_in = in_in.faces[k].box_hi - in_in.faces[k].box_lo;
    // (boxes are OCCT's optimal boxes: to 1e-6 of the size)
    CHECK((size_in - 25.4 * size_mm).norm() <= 1e-6 * size_in.norm());
    CHECK((size_in_in - size_mm).norm() <= 1e-6 * size_mm.norm());
    CHECK(in.faces[k].area == Approx(25.4 * 25.4 * mm.faces[k].area).epsilon(1e-6));
  }
  // Not a length: refused by the listing and the import, naming the file and the value.
  for (const char* factor : {"1.E300", "0.", "-25.4", "1.E-9"}) {
    const std::string bad = dir + "/cylinder_unit_" + factor + ".step";
    write(bad, with_unit(cylinder, "FURLONG", factor));
    INFO(bad);
    CHECK_THROWS_WITH(list_cad(bad),
                      Contains(bad) && Contains("length unit \"FURLONG\"") && Contains("refused"));
    CHECK_THROWS_WITH(import_cad(bad, "x"), Contains(bad) && Contains("refused"));
  }
  // 1e6 mm = 1 km: a length, accepted.
  const std::string km = dir + "/cylinder_km.step";
  write(km, with_unit(cylinder, "KILOMETRE", "1.E6"));
  CHECK(list_cad(km).units.factor == Approx(1e6).epsilon(1e-15));
  // IGES: the global section's unit (flag 2, "MM"; edited to flag 1, "INCH", in its columns).
  const std::string igs = test::slurp(kCylinderIges);
  const CadListing iges = list_cad(kCylinderIges);
  REQUIRE(!iges.units.names.empty());
  CHECK(iges.units.names.front() == "MM");
  CHECK(iges.units.file_unit_mm == Approx(1.0).epsilon(1e-15));
  const std::size_t at = igs.find(",1.,2,2HMM,");
  REQUIRE(at != std::string::npos);
  const std::size_t pad = igs.find("  G0000003", at);
  REQUIRE(pad != std::string::npos);
  std::string igs_inch = igs;
  igs_inch.erase(pad, 2);  // the line keeps its 72 columns
  igs_inch.replace(at, 11, ",1.,1,4HINCH,");
  write(dir + "/cylinder_inch.igs", igs_inch);
  const CadListing iges_in = list_cad(dir + "/cylinder_inch.igs");
  CHECK(iges_in.units.names.front() == "INCH");
  CHECK(iges_in.units.factor == Approx(25.4).epsilon(1e-15));
  REQUIRE(iges_in.faces.size() == iges.faces.size());
  CHECK(iges_in.faces[0].area == Approx(25.4 * 25.4 * iges.faces[0].area).epsilon(1e-6));
}

TEST_CASE("cad guard: skipped entities are a warning, an error when strict", "[cad]") {
  const std::string dir = out_dir("skipped");
  const std::string die_file = std::string(IGA_SOURCE_DIR) + "/data/cad/die_fillet.step";
  // The second ADVANCED_FACE renamed to a type STEP does not have: its shell loses it.
  std::vector<std::string> lines = lines_of(test::slurp(die_file));
  int seen = 0;
  for (std::string& l : lines)
    if (l.find("= ADVANCED_FACE(") != std::string::npos && ++seen == 2)
      l.replace(l.find("ADVANCED_FACE("), 13, "ADVANCED_FACEX");
  REQUIRE(seen >= 2);
  const std::string damaged = dir + "/die_damaged.step";
  write(damaged, joined(lines));

  const CadImport whole = import_cad(die_file, "d");
  CHECK(whole.entities.size() == 10);
  CHECK(whole.warnings.empty());
  CadOptions strict;
  strict.strict = true;
  CHECK(import_cad(die_file, "d", strict).entities.size() == 10);

  const CadImport part = import_cad(damaged, "d");
  CHECK(part.entities.size() == 9);
  REQUIRE(part.warnings.size() == 1);
  CHECK_THAT(part.warnings[0], Contains(damaged) && Contains("skipped"));
  const CadListing listed = list_cad(damaged);
  CHECK(listed.faces.size() == 9);
  CHECK(listed.warnings == part.warnings);
  CHECK_THROWS_WITH(import_cad(damaged, "d", strict), Contains(damaged) && Contains("strict"));
  // OCCT's screw: complete, no warning.
  CHECK(list_cad(kScrew).warnings.empty());
}

TEST_CASE("cad guard: a face number out of range names its place in the list", "[cad]") {
  CadOptions o;
  o.faces = {0, 99};
  try {
    (void)import_cad(kCylinder, "x", o);
    FAIL("no error");
  } catch (const CadError& e) {
    CHECK(e.face_option == 1);
    CHECK_THAT(e.what(), Contains("face 99 does not exist"));
  }
}

TEST_CASE("cad guard: the in-process path gives what the guarded path gives", "[cad]") {
  const CadImport a = import_cad(kCylinder, "c");
  const CadImport b = import_cad_in_process(kCylinder, "c");
  REQUIRE(a.entities.size() == b.entities.size());
  for (std::size_t i = 0; i < a.entities.size(); ++i) {
    CHECK(a.entities[i].first == b.entities[i].first);
    CHECK(a.entities[i].second == b.entities[i].second);  // exact: JSON round trip
    CHECK(a.faces[i].entity_type == b.faces[i].entity_type);
  }
  CHECK(list_cad_in_process(kScrew).faces.size() == list_cad(kScrew).faces.size());
}

TEST_CASE("cad guard: a reader that takes longer than IGA_CAD_TIMEOUT is stopped, with the file",
          "[cad]") {
  // Restores the variable whatever the test's outcome.
  struct EnvGuard {
    ~EnvGuard() { ::unsetenv("IGA_CAD_TIMEOUT"); }
  } guard;
  // 0.1 ms: less than starting the reader process takes, let alone reading the 10 faces.
  ::setenv("IGA_CAD_TIMEOUT", "1e-4", 1);
  for (const bool listing : {false, true}) {
    try {
      if (listing)
        (void)list_cad(kScrew);
      else
        (void)import_cad(kScrew, "s");
      FAIL("no error");
    } catch (const CadError& e) {
      CHECK_THAT(e.what(), Contains("did not finish reading " + kScrew + " within 0.0001 s") &&
                               Contains("IGA_CAD_TIMEOUT"));
    }
  }
  for (const char* bad : {"abc", "-5", "0", "nan"}) {
    ::setenv("IGA_CAD_TIMEOUT", bad, 1);
    CHECK_THROWS_WITH(import_cad(kCylinder, "c"),
                      Contains("IGA_CAD_TIMEOUT = \"" + std::string(bad) + "\""));
  }
  // A limit that leaves time: the same file imports.
  ::setenv("IGA_CAD_TIMEOUT", "600", 1);
  CHECK(import_cad(kScrew, "s").entities.size() == 10);
}

TEST_CASE(
    "cad guard: a face that crashes the reader is listed with the crash, the others as "
    "without it",
    "[cad]") {
  struct EnvGuard {
    ~EnvGuard() { ::unsetenv("IGA_CAD_TEST_CRASH_FACE"); }
  } guard;
  const CadListing plain = list_cad(kScrew);
  REQUIRE(plain.faces.size() == 10);
  for (const int crash : {0, 3, 9}) {
    INFO("face " << crash << " crashes");
    ::setenv("IGA_CAD_TEST_CRASH_FACE", std::to_string(crash).c_str(), 1);
    const CadListing l = list_cad(kScrew);
    REQUIRE(l.faces.size() == 10);
    CHECK(l.units.factor == plain.units.factor);
    for (std::size_t k = 0; k < 10; ++k) {
      CHECK(l.faces[k].index == static_cast<int>(k));
      CHECK(l.faces[k].cad_type == plain.faces[k].cad_type);
      if (static_cast<int>(k) == crash) {
        CHECK(l.faces[k].entity_type.empty());
        CHECK_FALSE(l.faces[k].described);
        CHECK_THAT(l.faces[k].message, Contains("OpenCASCADE crashed (") &&
                                           Contains("describing or converting this face"));
      } else {
        CHECK(l.faces[k].entity_type == plain.faces[k].entity_type);
        CHECK(l.faces[k].message == plain.faces[k].message);
        CHECK(l.faces[k].area == Approx(plain.faces[k].area).epsilon(1e-12));
      }
    }
  }
  // The hook is the reader child's only: in this process nothing crashes.
  CHECK(list_cad_in_process(kScrew).faces.size() == 10);
}

}  // namespace test_cad_guard
