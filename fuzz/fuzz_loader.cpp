// libFuzzer target: the model loader. Any byte string is parsed as a model file (JSON with the
// located-error SAX pass), then built into an Analysis (geometry, bodies, contact, solver and
// output sections). Every rejection must be a ModelError (file, JSON path, value); anything
// else (another exception, a crash, a hang, a leak) is a finding. Work caps (fuzz_caps.hpp): the
// integers that size a model (elements, refinement, quadrature and contact points) are clamped
// before the document is built, values beyond the library's limits left for it to reject.
// The rigid surfaces' projectors build a small subdivision tree (fuzz_caps.hpp, kTreeBudget).
// IGA_FUZZ_VERBOSE=1: each rejection's message on stderr (to check seeds: scripts/fuzz.sh).
// Build: scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined; off by default).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <string>

#include "fuzz/fuzz_caps.hpp"
#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"

namespace {
const bool verbose = std::getenv("IGA_FUZZ_VERBOSE") != nullptr;
}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  iga::fuzz::set_process_caps();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    iga::Json doc = iga::parse_json_text(text, "fuzz.json");
    iga::fuzz::clamp_work(doc);
    (void)iga::Analysis::from_json(doc, "fuzz.json");
    if (verbose) std::cerr << "fuzz_loader: loaded\n";
  } catch (const iga::ModelError& e) {
    if (std::string(e.what()).empty()) __builtin_trap();
    if (verbose) std::cerr << "fuzz_loader: " << e.what() << "\n";
  }
  return 0;
}
