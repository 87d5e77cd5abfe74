#!/bin/bash
# Builds G+Smo's linear Kirchhoff-Love shell driver kl_linear (bench/gismo/kl_linear.cpp), which
# bench/bench_linear_shell runs beside our linear path when IGA_GISMO_KL names it (README.md).
#
# usage: bench/gismo/build.sh [GISMO_REPO] [KLSHELL_REPO] [WORKDIR]
#   GISMO_REPO    default https://github.com/gismo/gismo.git (or a local mirror)
#   KLSHELL_REPO  default https://github.com/gismo/gsKLShell.git
#   WORKDIR       default build/gismo under the project root (sources and build)
# env: GISMO_REV, KLSHELL_REV (pinned commits, README.md), JOBS (default 1: the driver is one
# translation unit of ~6 GB at compile time)
#
# Result: $WORKDIR/build/kl_linear
#
# G+Smo is used header-only (GISMO_BUILD_LIB=OFF): only the few non-template G+Smo sources
# (object libraries gsCore, gsIO, gsParallel, gzstream) are compiled; the driver is a single
# translation unit with all templates. About 6-7 minutes on 2 cores.
set -euo pipefail

SCRIPT_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
GISMO_MIRROR=${1:-https://github.com/gismo/gismo.git}
KLSHELL_MIRROR=${2:-https://github.com/gismo/gsKLShell.git}
WORK=${3:-$SCRIPT_DIR/../../build/gismo}
# G+Smo: HEAD (branch stable) of the mirror, 2024-10-16
GISMO_REV=${GISMO_REV:-c405448b6c676a2ed1c0f316e23a63c20d25f658}
# gsKLShell: last commit before the move to <gsExpressions/...> includes
# (which needs a newer G+Smo than the mirror has), 2025-04-09
KLSHELL_REV=${KLSHELL_REV:-6ba4ca84c72622e8a29d94e59aebcd0ff3bf4692}
JOBS=${JOBS:-1}

mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)
SRC=$WORK/gismo
BLD=$WORK/build
START=$(date +%s)

# Check out commit $3 of mirror $1 into $2, leaving out files whose blobs are
# missing from the (partial) mirror (e.g. filedata/surfaces/car.xml).
checkout() {
    local mirror=$1 dir=$2 rev=$3
    if [ ! -d "$dir/.git" ]; then
        git clone -q --no-checkout "$mirror" "$dir"
    fi
    local missing
    missing=$(git -C "$dir" ls-tree -r --format='%(objectname) %(path)' "$rev" \
        | awk '{print $1}' | git -C "$dir" cat-file --batch-check \
        | awk '$2=="missing"{print $1}' || true)
    if [ -n "$missing" ]; then
        local pats=('/*')
        for sha in $missing; do
            local p
            p=$(git -C "$dir" ls-tree -r --format='%(objectname) %(path)' "$rev" | awk -v s="$sha" '$1==s{print $2}')
            echo "note: blob of $p missing in $mirror, left out of the checkout"
            pats+=("!/$p")
        done
        git -C "$dir" sparse-checkout set --no-cone "${pats[@]}"
    fi
    git -C "$dir" -c advice.detachedHead=false checkout -q -f "$rev"
}

checkout "$GISMO_MIRROR" "$SRC" "$GISMO_REV"
checkout "$KLSHELL_MIRROR" "$SRC/optional/gsKLShell" "$KLSHELL_REV"

# Configure: Release (-O3 -DNDEBUG, no -march), header-only, module gsKLShell.
# (gsOpennurbs is always added by G+Smo's submodules.txt; it is not built below.)
cmake -S "$SRC" -B "$BLD" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O3 -DNDEBUG" \
    -DTARGET_ARCHITECTURE=none \
    -DGISMO_BUILD_LIB=OFF -DGISMO_OPTIONAL="gsKLShell" \
    -DGISMO_BUILD_EXAMPLES=OFF -DGISMO_BUILD_UNITTESTS=OFF > "$WORK/configure.log" 2>&1 \
    || { cat "$WORK/configure.log"; exit 1; }

# Non-template G+Smo sources (gsMesh2 is not needed and does not compile in
# header-only mode at this G+Smo commit).
make -C "$BLD" -j"$JOBS" gsCore gsIO gsParallel gzstream

rm -f "$BLD/lib/libgismo_nolib_objs.a"
mkdir -p "$BLD/lib"
find "$BLD/src/CMakeFiles/gsCore.dir" "$BLD/src/CMakeFiles/gsIO.dir" \
     "$BLD/src/CMakeFiles/gsParallel.dir" "$BLD/external/gzstream/CMakeFiles/gzstream.dir" \
     -name '*.o' | sort | xargs ar rcs "$BLD/lib/libgismo_nolib_objs.a"

# The driver: one translation unit, templates of G+Smo and gsKLShell included.
CXXFLAGS="-O3 -DNDEBUG -std=c++14 -Wall -Wno-long-long -Wno-unknown-pragmas -UGISMO_BUILD_LIB"
INCS="-I$SRC/src -I$SRC/external -I$BLD -I$SRC/optional"
c++ $CXXFLAGS $INCS -c "$SCRIPT_DIR/kl_linear.cpp" -o "$BLD/kl_linear.o"
c++ -O3 "$BLD/kl_linear.o" -o "$BLD/kl_linear" "$BLD/lib/libgismo_nolib_objs.a" -ldl -lz

echo "built $BLD/kl_linear in $(( $(date +%s) - START )) s"
