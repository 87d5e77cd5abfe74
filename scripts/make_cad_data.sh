#!/usr/bin/env bash
# Writes data/cad/*.step, *.igs with OpenCASCADE's modelling API (tests/support/make_cad_data.cpp):
# the CAD files of the example models, made by the program, never by hand.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" release
cmake --build "$root/build/release" --target make_cad_data
"$root/build/release/tests/make_cad_data" "$root/data/cad"
