#!/usr/bin/env bash
# The stability maps of every method (docs/benchmarks/stability.md): runs the six sweeps of
# this folder (or of ci/, the reduced grid of the CTest check) with `nsbridge sweep`, times
# each, then draws the maps and checks the trust warnings against them (maps.py).
#   benchmarks/stability/run.sh NSBRIDGE OUT [JOBS] [ci]
# A sweep exits 1 when some of its runs did not complete; those runs are points of the map.
# Exits 1 when a map and the runs' warnings disagree, 2 when a sweep cannot run.
set -u
nsbridge=$(realpath "$1"); out=$2; jobs=${3:-2}; grid=${4:-}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$out"
echo "map,runs,wall_s" > "$out/times.csv"
for design in "$here/$grid"/*.toml; do
  name=$(basename "$design" .toml)
  start=$(date +%s.%N)
  "$nsbridge" sweep "$design" --out "$out/$name" --jobs "$jobs" --restart > "$out/$name.log" 2>&1
  code=$?
  if [ "$code" -gt 1 ]; then cat "$out/$name.log"; exit 2; fi
  end=$(date +%s.%N)
  runs=$(($(wc -l < "$out/$name/results.csv") - 1))
  printf '%s,%s,%.1f\n' "$name" "$runs" "$(echo "$end - $start" | bc)" >> "$out/times.csv"
  tail -1 "$out/times.csv"
done
if [ -z "$grid" ]; then python3 "$here/maps.py" plot "$out" || exit 2; fi
python3 "$here/maps.py" check "$out"
