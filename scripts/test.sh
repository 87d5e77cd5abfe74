#!/usr/bin/env bash
# Quick start 2: install what is missing, build, and run the whole test suite through CTest.
#   scripts/test.sh            Release build in build/release
#   scripts/test.sh --sanitize ASan + UBSan build in build/asan, with -ffp-contract=fast -mfma
#                              where the processor has FMA (scripts/build.sh)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
flavour=release
[[ "${1:-}" == "--sanitize" ]] && flavour=asan
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" "$flavour"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# OpenCASCADE's process-wide objects, never freed (scripts/lsan_occt.supp)
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$root/scripts/lsan_occt.supp:print_suppressions=0}
ctest --test-dir "$root/build/$flavour" --output-on-failure --parallel "$(nproc)" --timeout 600
