#!/usr/bin/env bash
# The suite must pass on any x86-64 processor. Results differ between processors in the last
# bits because (1) glibc's libm picks FMA/AVX2 code paths for exp, log, sin, pow, ... by
# processor, and (2) a compiler may fuse a*b+c into one rounding (-ffp-contract). This script
# runs the whole suite under each variation this machine can produce:
#   libm      the release build, run with glibc's FMA and AVX2 code paths masked
#             (GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-FMA4): the libm of an older processor,
#             and with the round-off probe (below) in the same run, so that CI's time does not
#             grow
#   fast-fma  a build with -ffp-contract=fast -mfma (needs a processor with FMA; skipped without).
#             CI does not run it: its sanitizer build is built this way (scripts/build.sh asan)
#   off       a build with -ffp-contract=off (not in `all`: on x86-64 without -mfma there is no
#             FMA instruction to contract into, and the release build is the same machine code)
#   probe     the release build, run with the round-off probe IGA_ROUNDOFF_PROBE=<seed> (seed
#             $IGA_PROBE_SEED, default 1; iga/solvers/roundoff_probe.hpp): Newton corrections
#             perturbed by 1e-10 and converged steps refused now and then, as another
#             processor's rounding may (alone; `libm` runs it too). Tests of the step control
#             itself turn it off for their scope (docs/portability.md).
#   scripts/portability.sh [libm|fast-fma|off|probe|all]...     default: all
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
modes=("$@")
((${#modes[@]})) || modes=(all)
[[ " ${modes[*]} " == *" all "* ]] && modes=(libm fast-fma)

"$root/scripts/install-deps.sh"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
jobs=${IGA_JOBS:-$(nproc)}

run_suite() {  # build dir, label, env...
  local dir=$1 label=$2
  shift 2
  echo "portability: $label"
  env "$@" ctest --test-dir "$dir" --output-on-failure --parallel "$(nproc)" --timeout 600
}

for mode in "${modes[@]}"; do
  case "$mode" in
    libm)
      "$root/scripts/build.sh" release
      run_suite "$root/build/release" \
        "libm without FMA/AVX2 code paths, with the round-off probe (seed ${IGA_PROBE_SEED:-1})" \
        GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-FMA4 IGA_ROUNDOFF_PROBE="${IGA_PROBE_SEED:-1}"
      ;;
    probe)
      "$root/scripts/build.sh" release
      run_suite "$root/build/release" "the round-off probe (seed ${IGA_PROBE_SEED:-1})" \
        IGA_ROUNDOFF_PROBE="${IGA_PROBE_SEED:-1}"
      ;;
    fast-fma | off)
      if [[ "$mode" == fast-fma ]] && ! grep -qw fma /proc/cpuinfo; then
        echo "portability: fast-fma skipped: this processor has no FMA instructions"
        continue
      fi
      dir="$root/build/fp-$mode"
      cmake -S "$root" -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
        -DIGA_FP_CONTRACT="$mode" -DIGA_BUILD_BENCH=OFF >/dev/null
      cmake --build "$dir" --parallel "$jobs"
      run_suite "$dir" "built with IGA_FP_CONTRACT=$mode"
      ;;
    *) echo "portability.sh: unknown mode '$mode' (libm|fast-fma|off|probe|all)" >&2; exit 2 ;;
  esac
done
