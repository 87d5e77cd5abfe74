#!/usr/bin/env bash
# Configures and builds one flavour of the project.
#   scripts/build.sh [release|debug|asan]   (default release) -> build/<flavour>
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
flavour=${1:-release}
case "$flavour" in
  release) args=(-DCMAKE_BUILD_TYPE=Release) ;;
  debug)   args=(-DCMAKE_BUILD_TYPE=Debug) ;;
  asan)    args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DIGA_SANITIZE=ON -DIGA_BUILD_BENCH=OFF) ;;
  *) echo "build.sh: unknown flavour '$flavour' (release|debug|asan)" >&2; exit 2 ;;
esac
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
jobs=${IGA_JOBS:-$(nproc)}
cmake -S "$root" -B "$root/build/$flavour" "${generator[@]}" "${args[@]}" >/dev/null
cmake --build "$root/build/$flavour" --parallel "$jobs"
