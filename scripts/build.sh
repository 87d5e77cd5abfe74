#!/usr/bin/env bash
# Configures and builds one flavour of the project.
#   scripts/build.sh [release|debug|asan]   (default release) -> build/<flavour>
# asan: AddressSanitizer + UndefinedBehaviorSanitizer at -O2 with line tables (-g1: stack traces
# name file and line), and, on a processor with FMA, -ffp-contract=fast -mfma: the one build
# that also checks that no result depends on fused multiply-adds (docs/portability.md), and the
# build without PETSc and MPI (-DIGA_WITH_PETSC=OFF: the serial fallback of iga/parallel, and no
# MPI runtime under the sanitizers).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
flavour=${1:-release}
case "$flavour" in
  release) args=(-DCMAKE_BUILD_TYPE=Release) ;;
  debug)   args=(-DCMAKE_BUILD_TYPE=Debug) ;;
  asan)
    args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG"
          -DIGA_SANITIZE=ON -DIGA_BUILD_BENCH=OFF -DIGA_WITH_PETSC=OFF)
    if grep -qw fma /proc/cpuinfo; then
      args+=(-DIGA_FP_CONTRACT=fast-fma)
    else
      echo "build.sh: asan without -ffp-contract=fast -mfma: this processor has no FMA" >&2
      args+=(-DIGA_FP_CONTRACT=)
    fi
    ;;
  *) echo "build.sh: unknown flavour '$flavour' (release|debug|asan)" >&2; exit 2 ;;
esac
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
jobs=${IGA_JOBS:-$(nproc)}
cmake -S "$root" -B "$root/build/$flavour" "${generator[@]}" "${args[@]}" >/dev/null
cmake --build "$root/build/$flavour" --parallel "$jobs"
