#!/usr/bin/env bash
# Draws every shipped scene (scenes/*.toml) under every method: runs each into
# OUT/<scene>-<method>/ (unless that folder already holds a run) and draws its response, gaps,
# events and energy there as PNG with `nsbridge plot` (docs/plots.md).
#   bash scripts/plot-scenes.sh [OUT]     (default out/plots; NSB_BUILD_DIR selects the build)
# A run that ends early (exit 1: unseated, stalled) is drawn as far as it went.
set -uo pipefail
cd "$(dirname "$0")/.."
nsb=${NSB_BUILD_DIR:-build}/app/nsbridge
out=${1:-out/plots}
mkdir -p "$out"
failures=0
for scene in scenes/*.toml; do
  name=$(basename "$scene" .toml)
  for method in moreau event_driven compliance; do
    dir=$out/$name-$method
    if [[ ! -f $dir/summary.json ]]; then
      "$nsb" run "$scene" --method "$method" --out "$dir" --quiet > "$dir.log" 2>&1
    fi
    if [[ ! -f $dir/summary.json ]]; then
      echo "plot-scenes: $name $method: the run wrote nothing (see $dir.log)" >&2
      failures=$((failures + 1))
      continue
    fi
    for what in response gaps events energy; do
      if ! "$nsb" plot "$dir" --what "$what" > /dev/null; then
        echo "plot-scenes: $name $method: plot --what $what failed" >&2
        failures=$((failures + 1))
      fi
    done
  done
done
echo "plot-scenes: figures in $out/<scene>-<method>/{response,gaps,events,energy}.png, $failures failures"
[[ $failures -eq 0 ]]
