#!/usr/bin/env bash
# Quick start 1: install what is missing, build in Release, run the main job.
# The main job is the demo of the geometry kernel on the models in data/ (the capstan app
# takes its place once it exists).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" release
iga="$root/build/release/apps/iga"
out="$root/out/demo"
mkdir -p "$out"
for model in "$root"/data/*.json; do
  echo "== $(basename "$model")"
  "$iga" info "$model"
  "$iga" eval "$model" --center
done
echo "== sample table: $out/torus_grid.csv"
"$iga" eval "$root/data/torus_patch.json" --grid 8 --out "$out/torus_grid.csv"
