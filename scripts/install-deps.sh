#!/usr/bin/env bash
# Installs the Debian 12 packages this project builds with, only those that are missing.
# Runs apt-get only when something is missing (as root, or through sudo).
#   scripts/install-deps.sh          what the build, the tests and the apps need
#   scripts/install-deps.sh --fuzz   clang and its libFuzzer runtime (scripts/fuzz.sh)
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config
  libeigen3-dev libcgal-dev libsuitesparse-dev nlohmann-json3-dev
  catch2 libcli11-dev libbenchmark-dev
  libocct-data-exchange-dev libtbb-dev  # OCCT: its CMake package names libtbb.so, which only libtbb-dev holds
  libopenblas0-serial  # the BLAS of CHOLMOD's supernodal factorization (Debian's alternatives)
  python3 python3-matplotlib clang-format clang-tidy
  python3-dev python3-numpy python3-pytest pybind11-dev  # the Python module (python/)
  libpetsc-real3.18-dev libmumps-dev openmpi-bin  # distributed runs: PETSc with MUMPS (also called directly) and hypre, OpenMPI's mpirun
)
[[ "${1:-}" == "--fuzz" ]] && packages=(clang libclang-rt-dev)

# CHOLMOD and UMFPACK call libblas.so.3, which Debian's alternatives point at the installed BLAS of
# highest priority; a threaded OpenBLAS (-pthread, -openmp) wins over the serial one and is slower
# here (its threads compete with the element loops'). Said, not changed.
blas_note() {
  local blas
  blas=$(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3 2>/dev/null || true)
  [[ "$blas" == *openblas-serial* ]] ||
    echo "install-deps: note: libblas.so.3 is ${blas:-missing}, not OpenBLAS serial: the sparse" \
      "factorizations are slower (update-alternatives --config libblas.so.3-x86_64-linux-gnu)"
}

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  [[ "${1:-}" == "--fuzz" ]] || blas_note
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install ${missing[*]}" >&2; exit 1; }
  SUDO=sudo
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
[[ "${1:-}" == "--fuzz" ]] || blas_note
