#!/usr/bin/env bash
# nsbridge plot and nsbridge run --plot end to end: one bridge with two contact families (the
# shear-key bridge: 4 abutment corners, 4 keys) under each method, shortened to its first
# impacts, drawn as PNG, SVG and PDF; the bents' hysteresis from a synthetic run folder.
# usage: plot_cli_test.sh NSBRIDGE
source "$(dirname "$0")/cli_lib.sh"
limit=60

png() { [[ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]]; }
pdf() { [[ "$(head -c 5 "$1")" == "%PDF-" ]]; }
svg() { grep -q '<svg' "$1" && grep -q '</svg>' "$1"; }
# The curves of an SVG: gnuplot writes one group <g id="gnuplot_plot_<k><panel letter>"> per
# curve drawn, titled or not.
curves() { grep -c '<g id="gnuplot_plot_' "$1"; }
nothing_left() { [[ -z "$(find "$1" -name '.*.tmp*' -o -name '*.gp' -o -name '*.log')" ]]; }

scene=$root/scenes/bridge-shear-keys.toml
# The first impacts come at 3.7 s (baseline events.csv of this scene); 5 s, no error estimate.
short=(--set solver.end_time=5 --set solver.error_estimate=false --quiet)
declare -A title=([moreau]="Moreau-Jean" [event_driven]="event-driven" [compliance]="compliance")
for m in moreau event_driven compliance; do
  run=$tmp/$m
  expect 0 "figure +$run/response.png" -- run "$scene" --out "$run" --method "$m" --plot "${short[@]}"
  check "$m: run --plot draws a PNG" png "$run/response.png"
  expect 0 "$run/r.svg" -- plot "$run" --out "$run/r.svg"
  check "$m: response SVG" svg "$run/r.svg"
  # x, y, theta; gN1-4 (abutments), gN5-8 (shear keys), each family's dashed g = 0: 13 curves.
  check "$m: response has 13 curves" test "$(curves "$run/r.svg")" -eq 13
  check "$m: the title names the method" grep -q "bridge-shear-keys: response, ${title[$m]}" "$run/r.svg"
  check "$m: abutments and shear keys are separate panels" \
    test "$(grep -cE '>(abutments|shear keys)<' "$run/r.svg")" -eq 2
  check "$m: contacts are named" grep -q 'gN5: shear_key_left_plus' "$run/r.svg"
  expect 0 "g.svg" -- plot "$run" --what gaps --out "$run/g.svg"
  # gN1-4 and gN5-8, each family's panel with its dashed line g = 0: 10 curves.
  check "$m: gaps has 10 curves" test "$(curves "$run/g.svg")" -eq 10
  expect 0 "e.svg" -- plot "$run" --what energy --out "$run/e.svg"
  check "$m: energy has energy_error" test "$(curves "$run/e.svg")" -eq 1
  expect 0 "v.svg" -- plot "$run" --what events --out "$run/v.svg"
  # One curve per kind of event the run has (events.csv's distinct kinds).
  kinds=$(tail -n +2 "$run/events.csv" | cut -d, -f3 | sort -u | wc -l)
  check "$m: events has one curve per kind ($kinds)" test "$(curves "$run/v.svg")" -eq "$kinds"
  check "$m: nothing left beside the figures" nothing_left "$run"
done
expect 0 "p.pdf" -- plot "$tmp/moreau" --what gaps --out "$tmp/moreau/p.pdf"
check "a PDF" pdf "$tmp/moreau/p.pdf"
expect 0 "gaps.png" -- plot "$tmp/moreau" --what gaps
check "the default picture is RUN_DIR/<what>.png" png "$tmp/moreau/gaps.png"

# Bents: a synthetic run folder of two bents, as [output] groups = ["bents"] adds them.
syn=$tmp/bents
mkdir -p "$syn"
{
  echo "t,x,y,theta,vx,vy,omega,gN1,lambdaN1,lambdaT1,bent1_ux,bent1_uy,bent1_fx,bent1_fy,bent2_ux,bent2_uy,bent2_fx,bent2_fy,energy_error"
  for i in $(seq 0 200); do
    awk -v i="$i" 'BEGIN { t = i * 0.01; u = 0.01 * sin(6.283 * t); printf "%g,0,0,0,0,0,0,0.01,0,0,%g,%g,%g,%g,%g,%g,%g,%g,0\n", t, u, -u, 2000 * u + 5 * (i % 7), -1000 * u, u / 2, u / 3, 900 * u, 800 * u }'
  done
} > "$syn/history.csv"
echo "t,contact,kind,note" > "$syn/events.csv"
echo '{"scene": "synthetic", "method": "compliance", "status": "completed", "end_time": 2}' > "$syn/summary.json"
expect 0 "b.svg" -- plot "$syn" --what bents --out "$syn/b.svg"
# Two bents x two directions: four loops, one panel each.
check "bents: four loops" test "$(curves "$syn/b.svg")" -eq 4
check "bents: panels per bent and direction" grep -q 'bent 2, transverse' "$syn/b.svg"
check "bents: force and deformation axes with units" grep -q 'force f_x \[kN\]' "$syn/b.svg"
expect 0 "b.png" -- plot "$syn" --what bents --out "$syn/b.png"
check "bents: PNG" png "$syn/b.png"
expect 0 "x.svg" -- plot "$syn" --what events --out "$syn/x.svg"
check "no events: the figure says so" grep -q 'no events' "$syn/x.svg"

echo "plot_cli_test: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
