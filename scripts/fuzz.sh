#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang + ASan + UBSan in build/fuzz and runs each for
# a given time, seeded with every model of data/ and tests/data/ (fuzz_cad: with the STEP and
# IGES files of data/cad and tests/data/cad, up to 128 KB each).
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
#   default: 60 s, fuzz_loader fuzz_pipeline fuzz_cad
# The corpus grows in build/fuzz/corpus/<target>; a crash, leak, timeout or uncaught exception
# is written to build/fuzz/findings/<target>/ and makes the script exit 1. The timeout is 60 s
# per input: the largest models the loader accepts take a few seconds to set up natively and
# ten times that under the sanitizers.
# Reproduce a finding: build/fuzz/fuzz/<target> build/fuzz/findings/<target>/crash-...
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(fuzz_loader fuzz_pipeline fuzz_cad)

"$root/scripts/install-deps.sh"
"$root/scripts/install-deps.sh" --fuzz

build="$root/build/fuzz"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
CXX=clang++ cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DIGA_BUILD_FUZZ=ON -DIGA_BUILD_TESTS=OFF -DIGA_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --parallel "${IGA_JOBS:-$(nproc)}" --target "${targets[@]}"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
status=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t" findings="$build/findings/$t"
  mkdir -p "$corpus" "$findings"
  max_len=65536
  if [[ $t == fuzz_cad ]]; then
    max_len=131072
    find "$root/data/cad" "$root/tests/data/cad" \( -name '*.step' -o -name '*.stp' -o \
      -name '*.igs' -o -name '*.iges' \) -size -128k -exec cp -n {} "$corpus/" \;
  else
    find "$root/data" "$root/tests/data" -name '*.json' -exec cp -n {} "$corpus/" \;
  fi
  echo "fuzz: $t for $seconds s (corpus $(ls "$corpus" | wc -l) inputs)"
  if ! "$build/fuzz/$t" "$corpus" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 \
      -max_len="$max_len" -print_final_stats=1 -artifact_prefix="$findings/" 2>"$build/$t.log"; then
    status=1
    echo "fuzz: $t found a problem: $(ls "$findings")" >&2
  fi
  grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|^Done" "$build/$t.log" || true
done
exit $status
