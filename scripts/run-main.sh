#!/usr/bin/env bash
# The main job: set up, build nsbridge, run the benchmark bridge under the strongest
# excitation (scenes/bridge-exc7.toml, transverse PGA 1.0 g) with Moreau–Jean, and draw its
# response (displacements, rotation, contact forces by family; `nsbridge run --plot`,
# docs/plots.md) to out/bridge-exc7/response.png.
#   bash scripts/run-main.sh [SCENE.toml] [-- extra nsbridge run options, e.g. --set solver.step=1e-5]
# NSB_BUILD_DIR selects the build directory (default: build).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

scene=scenes/bridge-exc7.toml
if [[ $# -gt 0 && "$1" != "--" ]]; then scene=$1; shift; fi
if [[ "${1:-}" == "--" ]]; then shift; fi
name=$(basename "$scene" .toml)
out=out/$name

bash scripts/install-deps.sh
build=${NSB_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DNSB_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build "$build" --target nsbridge -j "$jobs"

status=0
"$build/app/nsbridge" run "$scene" --out "$out" --method moreau --plot "$@" || status=$?
if [[ $status -eq 2 || ! -f "$out/history.csv" ]]; then
  echo "run-main: the run failed (exit $status)" >&2
  exit "$status"
fi
echo "run-main: $out/response.png"
exit "$status"
