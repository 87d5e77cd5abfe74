// libFuzzer target: the STEP and IGES readers (issue 34). The input is a CAD file: written to a
// temporary file (OpenCASCADE reads files) named .step if it starts as a STEP file does
// ("ISO-10303-21"), else .igs, then read, transferred and every face described and converted
// (list_cad_in_process, the listing of `iga info`), and imported whole
// (import_cad_in_process). Rejections must be CadErrors with a message; the listing's numbers
// must be finite. Anything else is a finding: another exception, a crash, a hang, a leak.
//
// In process, not through the guarded entry points (list_cad, import_cad): those run OpenCASCADE
// in a child process and turn its crashes into CadErrors, which would hide every crash from the
// fuzzer (and cost a fork per input). Here a crash inside OpenCASCADE is a finding with the
// sanitizer's report of where it happened: a crash the guard contains for the tool's users
// (report it upstream), a crash in cad/ is ours to fix.
// Build: scripts/fuzz.sh (clang, -fsanitize=fuzzer,address,undefined; off by default). With
// -DIGA_FUZZ_CAD_MAIN the file is a plain program running the inputs named on its command line
// (to check it with g++, or to replay a finding without libFuzzer).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include <unistd.h>

#include "cad/cad_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const bool step = text.rfind("ISO-10303-21", 0) == 0;
  const std::string path =
      "/tmp/fuzz_cad_" + std::to_string(::getpid()) + (step ? ".step" : ".igs");
  std::ofstream(path, std::ios::binary) << text;
  try {
    const iga::CadListing l = iga::list_cad_in_process(path);
    for (const iga::CadFace& f : l.faces)
      if (!std::isfinite(f.area) || !f.box_lo.allFinite() || !f.box_hi.allFinite() ||
          !std::isfinite(f.tolerance) || (f.entity_type.empty() && f.message.empty()))
        __builtin_trap();
    if (!std::isfinite(l.units.factor) || !(l.units.factor > 0.0)) __builtin_trap();
    (void)iga::import_cad_in_process(path, "fuzz");
  } catch (const iga::CadError& e) {
    if (std::string(e.what()).empty()) __builtin_trap();
  }
  std::remove(path.c_str());
  return 0;
}

#ifdef IGA_FUZZ_CAD_MAIN
#include <iostream>
#include <iterator>
int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    std::cout << argv[i] << ": ran\n";
  }
  return 0;
}
#endif
