#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang + ASan + UBSan in build/fuzz and runs each for
# a given time.
#   scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]
#   default: 60 s, fuzz_loader fuzz_pipeline fuzz_cad
# Seeds, small so that an execution takes milliseconds under the sanitizers (a large model costs
# tens of milliseconds to seconds per execution, and libFuzzer spends its time on it):
#   fuzz_loader, fuzz_pipeline  fuzz/seeds/models/: a coarse variant of every model of data/ and
#                               tests/data/models/ (few elements and steps, under 4 KB each; the
#                               same entity, body, material, condition, load, contact, motion,
#                               solver and output kinds), written by scripts/fuzz_seeds.py (run it
#                               after adding a model; this script warns when they are stale);
#                               fuzz_loader also the rejected files of tests/data/bad/
#   fuzz_cad                    the STEP and IGES files of data/cad and tests/data/cad up to
#                               CAD_MAX_KB = 17 KB (larger ones take 1 to 11 s per execution
#                               under the sanitizers), not the known findings fuzz_crash_*
# Caps on the work per input: the input size (-max_len: 4 KB for models, 17 KB for CAD files);
# in the model targets the integers that size a model (elements, refinement, quadrature and
# contact points, augmentations) are clamped before it is built (fuzz/fuzz_caps.hpp), and
# fuzz_pipeline runs at most 3 steps of at most 8 Newton iterations on at most 400 unknowns.
# The library's defaults and limits are unchanged. The targets run in build/fuzz (a "cad"
# entity's relative file name finds nothing there: its error path is fuzzed, the CAD reader
# itself by fuzz_cad).
# fuzz_cad runs with fuzz/lsan_occt.supp: leaks inside OpenCASCADE's libraries (it leaks while
# reading even valid files) are not findings: the tool reads CAD files in a forked child.
# The corpus grows in build/fuzz/corpus/<target> (inputs above -max_len, e.g. left by an older
# run, are truncated on loading); a crash, leak, timeout (10 s per input) or uncaught exception
# is written to build/fuzz/findings/<target>/ and makes the script exit 1.
# fuzz_cad runs in fork mode (-fork=IGA_JOBS, default nproc) past crashes and timeouts:
# OpenCASCADE's readers crash on many broken files, and the tool contains those crashes (reader
# child process). Each crash found is replayed and its sanitizer report's first frame outside
# the sanitizer runtime and libc names its owner: OpenCASCADE (libTK*: listed, reported
# upstream, not a failure) or ours (anything else: exit 1). Timeouts are listed (the tool's
# reader has a time limit, IGA_CAD_TIMEOUT).
# Reproduce a finding: build/fuzz/fuzz/<target> build/fuzz/findings/<target>/crash-...
# IGA_FUZZ_VERBOSE=1 build/fuzz/fuzz/fuzz_pipeline fuzz/seeds/models/*.json: what each seed does
# (loaded, rejected with which message, steps run).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(fuzz_loader fuzz_pipeline fuzz_cad)

"$root/scripts/install-deps.sh"
"$root/scripts/install-deps.sh" --fuzz
python3 "$root/scripts/fuzz_seeds.py" --check ||
  echo "fuzz: warning: fuzz/seeds/models is stale: run scripts/fuzz_seeds.py" >&2

build="$root/build/fuzz"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
CXX=clang++ cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DIGA_BUILD_FUZZ=ON -DIGA_BUILD_TESTS=OFF -DIGA_BUILD_BENCH=OFF >/dev/null
cmake --build "$build" --parallel "${IGA_JOBS:-$(nproc)}" --target "${targets[@]}"

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# One thread per execution: OpenMP's workers (element loops, projector trees) spin between
# loops and compete with the fuzzer on a small machine; the inputs are small anyway.
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
CAD_MAX_KB=17
status=0

# Replays each crash of fuzz_cad and names its owner by the first stack frame outside the
# sanitizer runtime and libc: "OpenCASCADE" (a libTK* library) or "ours" (exit status 1).
triage_cad() {  # findings dir, LSAN_OPTIONS
  local dir=$1 lsan=$2 ours=0 occt=0 f frame
  for f in "$dir"/crash-* "$dir"/leak-*; do
    [[ -e $f ]] || continue
    frame=$(cd "$build" && LSAN_OPTIONS=$lsan "$build/fuzz/fuzz_cad" "$f" 2>&1 |
      grep -E '^ *#[0-9]+ ' | grep -vE 'libasan|libubsan|libclang_rt|compiler-rt|/libc\.so|sanitizer_common|__sanitizer|libFuzzer|FuzzerLoop' | head -1)
    if [[ $frame == *libTK* ]]; then
      occt=$((occt + 1))
      echo "fuzz: OpenCASCADE: ${f##*/}: ${frame#"${frame%%[![:space:]]*}"}"
    else
      ours=$((ours + 1))
      echo "fuzz: ours: ${f##*/}: ${frame:-no stack frame (replay it: build/fuzz/fuzz/fuzz_cad $f)}" >&2
    fi
  done
  for f in "$dir"/timeout-* "$dir"/oom-*; do
    [[ -e $f ]] && echo "fuzz: slow or large: ${f##*/} (the tool's reader stops at IGA_CAD_TIMEOUT)"
  done
  echo "fuzz: fuzz_cad findings: $occt inside OpenCASCADE, $ours ours"
  ((ours == 0))
}
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t" findings="$build/findings/$t"
  mkdir -p "$corpus" "$findings"
  seeds=()
  case $t in
    fuzz_cad)
      max_len=$((CAD_MAX_KB * 1024))
      seeds=("$build/seeds/fuzz_cad")
      rm -rf "${seeds[0]}"
      mkdir -p "${seeds[0]}"
      find "$root/data/cad" "$root/tests/data/cad" \( -name '*.step' -o -name '*.stp' -o \
        -name '*.igs' -o -name '*.iges' \) -not -name 'fuzz_crash_*' -size -"$((CAD_MAX_KB + 1))"k \
        -exec cp -n {} "${seeds[0]}/" \;
      ;;
    fuzz_loader) max_len=4096 seeds=("$root/fuzz/seeds/models" "$root/tests/data/bad") ;;
    *) max_len=4096 seeds=("$root/fuzz/seeds/models") ;;
  esac
  lsan=${LSAN_OPTIONS:-}
  [[ $t == fuzz_cad ]] && lsan="suppressions=$root/fuzz/lsan_occt.supp:print_suppressions=0${lsan:+:$lsan}"
  mode=()
  [[ $t == fuzz_cad ]] && mode=(-fork="${IGA_JOBS:-$(nproc)}" -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  echo "fuzz: $t for $seconds s (corpus $(ls "$corpus" | wc -l) inputs, seeds ${seeds[*]#"$root/"})"
  # the corpus first: libFuzzer writes new inputs to the first folder only
  if ! (cd "$build" && LSAN_OPTIONS=$lsan "$build/fuzz/$t" "$corpus" "${seeds[@]}" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -max_len="$max_len" -print_final_stats=1 "${mode[@]}" \
      -artifact_prefix="$findings/" 2>"$build/$t.log") && [[ $t != fuzz_cad ]]; then
    status=1
    echo "fuzz: $t found a problem: $(ls "$findings")" >&2
  fi
  if [[ $t == fuzz_cad ]]; then
    # fork mode: executions summed over the jobs ("#N DONE ... exec/s: R" per merge line)
    grep -E "^#[0-9]+: cov" "$build/$t.log" | tail -1 || true
    triage_cad "$findings" "$lsan" || status=1
  else
    grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|^Done" "$build/$t.log" || true
  fi
done
exit $status
