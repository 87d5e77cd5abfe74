// The error message of a model with one edit, shared by the analysis loader's tests.
#pragma once

#include <string>

#include "iga/model/analysis.hpp"

namespace iga::test {

/// The ModelError message of Analysis::from_json on `base` after `edit(doc)`, the document
/// named "m.json"; "no error" if it loads.
template <class Edit>
std::string analysis_error(const Json& base, Edit&& edit) {
  Json doc = base;
  edit(doc);
  try {
    (void)Analysis::from_json(doc, "m.json");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "no error";
}

/// data/capstan.json turned back into the model of make_capstan's defaults
/// (tests/support/capstan.hpp), which tests use as a fixture: a cubic rope whose wrapped shape is
/// stress-free, EI = 1e-2, 3 contact points per element, penalty enforcement.
inline Json cubic_penalty_capstan(Json doc) {
  doc["geometry"]["rope"].erase("degree");
  doc["bodies"]["rope"].erase("stress_free");
  doc["materials"]["rope"]["EI"] = 1e-2;
  Json& c = doc["contact"][0];
  c["points_per_element"] = 3;
  c.erase("enforcement");
  c.erase("penetration_tol");
  c.erase("max_augmentations");
  c.erase("slip_tol");
  return doc;
}

}  // namespace iga::test
