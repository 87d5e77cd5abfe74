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
# The slowest tests of this run (CTest's cost data: seconds per test), to keep CI within its time.
cost="$root/build/$flavour/Testing/Temporary/CTestCostData.txt"
if [[ -f "$cost" ]]; then
  echo "test.sh: the 12 slowest tests ($flavour), seconds:"
  awk '/^---/ {exit} NF >= 3 {printf "%8.1f  %s\n", $NF, substr($0, 1, length($0) - length($(NF-1)) - length($NF) - 2)}' \
    "$cost" | sort -rn | head -12 || true
fi
