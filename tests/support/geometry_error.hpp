// Shared helper of the geometry tests: the ModelError of a geometry section given as text.
#pragma once

#include <catch2/catch.hpp>

#include <string>

#include "geometry/geometry_io.hpp"
#include "geometry/json_reader.hpp"

namespace iga::test {

/// The ModelError of parsing `text` as the geometry section of g.json; a test failure if the
/// section is read without one.
inline ModelError geometry_error(const std::string& text) {
  try {
    parse_geometry(parse_json_text(text, "g.json"), "g.json", JsonPointer("/geometry"));
  } catch (const ModelError& e) {
    return e;
  }
  FAIL("no ModelError for " << text);
  return ModelError("", "", "");
}

}  // namespace iga::test
