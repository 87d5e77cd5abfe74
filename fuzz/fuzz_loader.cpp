// libFuzzer target: the model loader. Any byte string is parsed as a model file (JSON with the
// located-error SAX pass), then built into an Analysis (geometry, bodies, contact, solver and
// output sections). Every rejection must be a ModelError (file, JSON path, value); anything
// else (another exception, a crash, a hang, a leak) is a finding.
// Build: scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined; off by default).
#include <cstddef>
#include <cstdint>
#include <string>

#include "geometry/json_reader.hpp"
#include "iga/model/analysis.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const iga::Json doc = iga::parse_json_text(text, "fuzz.json");
    (void)iga::Analysis::from_json(doc, "fuzz.json");
  } catch (const iga::ModelError& e) {
    if (std::string(e.what()).empty()) __builtin_trap();
  }
  return 0;
}
