// The error message of a model with one edit, shared by the analysis loader's tests.
#pragma once

#include <string>

#include "iga/analysis.hpp"

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

}  // namespace iga::test
