// One OpenCASCADE face converted as import_cad converts each face of a file (issue 34, item 4):
// for tests and studies that read the file themselves (tests/support/cad_corpus_study.cpp).
// Needs OCCT's headers (TopoDS_Face); the rest of the project uses cad_import.hpp only.
#pragma once

#include <string>
#include <utility>

#include <TopoDS_Face.hxx>

#include "cad/cad_import.hpp"

namespace iga {

/// The face (`index`: its number, for the description) as the project's surface, trimmed
/// when its boundary is not its parameter rectangle, and its description. Throws CadError
/// naming what is wrong with the face (not the file: the caller knows it).
std::pair<GeometryEntity, CadFace> import_face(const TopoDS_Face& face, int index);

}  // namespace iga
