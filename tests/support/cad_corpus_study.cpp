// Study of CAD face import over a corpus (issue 34, item 4): imports every face of one STEP or
// IGES file, each face on its own (import_face), and compares its closest points with
// OpenCASCADE's projection (occt_projection_check.hpp). Not part of the test suite; run over a
// folder by scripts/cad_corpus_study.sh, one process per file (a file that crashes or hangs
// OCCT costs only itself).
//
// Usage: cad_corpus_study <file.step|.stp|.iges|.igs> [points per face, default 20]
// Output, one line each (tab-separated):
//   - FACE <k> <cad type> ok <entity type> cmp <points> <same> <closer> <none> <worst / h>
//     <bound_apart> <occt_outside> <occt_unconverged> <approx_apart> <approx_apart_worst / h>
//   - FACE <k> <cad type> ok <entity type> cmpfail <failure>
//   - FACE <k> <cad type> fail <message>
//   - FILE <path> faces <n> imported <m> cmpfail <c>   (last; "faces 0": no faces)
//   - FILE <path> unreadable <message>
#include <cstdlib>
#include <iostream>
#include <string>

#include <IGESControl_Reader.hxx>
#include <STEPControl_Reader.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include "cad/cad_face.hpp"
#include "tests/support/occt_projection_check.hpp"

namespace {

template <class Reader>
TopoDS_Shape read(const std::string& path) {
  Reader r;
  if (r.ReadFile(path.c_str()) != IFSelect_RetDone) throw std::runtime_error("OCCT cannot read it");
  r.TransferRoots();
  return r.OneShape();
}

std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\t') c = ' ';
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: cad_corpus_study <file> [points per face]\n";
    return 2;
  }
  const std::string path = argv[1];
  const int n = argc > 2 ? std::atoi(argv[2]) : 20;
  TopoDS_Shape shape;
  try {
    const std::string format = iga::cad_format(path);
    shape = format == "step" ? read<STEPControl_Reader>(path) : read<IGESControl_Reader>(path);
  } catch (const std::exception& e) {
    std::cout << "FILE\t" << path << "\tunreadable\t" << one_line(e.what()) << '\n';
    return 0;
  } catch (const Standard_Failure& e) {
    std::cout << "FILE\t" << path << "\tunreadable\t" << one_line(e.GetMessageString()) << '\n';
    return 0;
  }
  TopTools_IndexedMapOfShape map;
  if (!shape.IsNull()) TopExp::MapShapes(shape, TopAbs_FACE, map);
  int imported = 0, cmpfail = 0;
  for (int k = 0; k < map.Extent(); ++k) {
    const TopoDS_Face& face = TopoDS::Face(map(k + 1));
    std::cout << "FACE\t" << k << '\t' << std::flush;
    try {
      const auto [entity, d] = iga::import_face(face, k);
      ++imported;
      std::cout << d.cad_type << "\tok\t" << d.entity_type;
      if (!d.exact) std::cout << " (approximated within " << d.tolerance << ")";
      const iga::test::OcctComparison c =
          iga::test::compare_with_occt(face, entity, d.tolerance, n);
      if (!c.failure.empty()) {
        ++cmpfail;
        std::cout << "\tcmpfail\t" << one_line(c.failure) << '\n';
      } else {
        std::cout << "\tcmp\t" << c.points << '\t' << c.same << '\t' << c.ours_closer << '\t'
                  << c.occt_none << '\t' << c.worst << '\t' << c.bound_apart << '\t'
                  << c.occt_outside << '\t' << c.occt_unconverged << '\t' << c.approx_apart << '\t'
                  << c.approx_apart_worst << '\t' << c.ill_posed_apart << '\t' << c.ill_posed_reach
                  << '\n';
      }
    } catch (const std::exception& e) {
      std::cout << "?\tfail\t" << one_line(e.what()) << '\n';
    } catch (const Standard_Failure& e) {
      std::cout << "?\tfail\tOCCT: " << one_line(e.GetMessageString()) << '\n';
    }
  }
  std::cout << "FILE\t" << path << "\tfaces\t" << map.Extent() << "\timported\t" << imported
            << "\tcmpfail\t" << cmpfail << '\n';
  return 0;
}
