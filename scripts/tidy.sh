#!/usr/bin/env bash
# clang-tidy (the committed .clang-tidy: bugprone, performance, cognitive complexity at most 40)
# on the library's sources (geometry/, cad/, contact/, iga/), the programs' (apps/) and the Python
# module's (python/), with the compile commands of build/release (built first if missing). Fails
# on any warning.
#   scripts/tidy.sh [-j N]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
[[ "${1:-}" == "-j" ]] && jobs=$2
command -v clang-tidy >/dev/null || bash scripts/install-deps.sh
[[ -f build/release/compile_commands.json ]] || bash scripts/build.sh release
log=$(mktemp)
trap 'rm -f "$log"' EXIT
mapfile -t files < <(git ls-files 'geometry/*.cpp' 'cad/*.cpp' 'contact/*.cpp' 'iga/*.cpp' 'apps/*.cpp' 'python/*.cpp')
printf '%s\n' "${files[@]}" |
  xargs -P "$jobs" -n 1 clang-tidy -p build/release --quiet 2>/dev/null >"$log" || true
root="$(pwd)/"
mapfile -t warnings < <(grep -E ': (warning|error): ' "$log" | sed "s#^$root##" | sort -u)
if ((${#warnings[@]} > 0)); then
  echo "tidy: ${#warnings[@]} warning(s):" >&2
  printf '  %s\n' "${warnings[@]}" >&2
  exit 1
fi
echo "tidy: clean (${#files[@]} files)"
