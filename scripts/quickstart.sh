#!/usr/bin/env bash
# Quick start 1: install what is missing, build in Release, run the main job: the capstan app
# on its default model (data/capstan.json; results, plot and VTK files in out/capstan).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" release
"$root/build/release/apps/capstan" "$root/data/capstan.json" --out "$root/out/capstan" --max-error 0.005
