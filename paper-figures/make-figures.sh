#!/usr/bin/env bash
# Regenerates the figures of Shi & Dimitrakopoulos (2017) from nsbridge runs of the benchmark
# bridge (scenes/bridge-exc*.toml) and plots them with gnuplot into OUTDIR:
#   fig3-response.png    Fig. 3: x, y, theta and the gaps gN1..gN4 under excitation 5
#   fig4-omega.png       Fig. 4: the angular velocity omega under excitation 5
#   fig6-peak-rotation.png  Fig. 6: peak |theta| against the target transverse PGA, with and
#                        without deck-abutment pounding, over the 7 excitations
#   fig7-compliance.png  Fig. 7: theta(t) of the nonsmooth and the compliance approaches for
#                        contact stiffness 1e-4 k ... 1e2 k under excitation 5
#   fig8-first-pounding.png  Fig. 8: the gap at the first pounding and the force-penetration
#                        loops of the gap element, for several stiffnesses
# The measured records of the shake-table test are not public, so the figures show nsbridge's
# results only (docs/paper-figures.md).
#   bash paper-figures/make-figures.sh [NSBRIDGE] [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
nsb=${1:-$root/build/app/nsbridge}
out=${2:-$root/out/paper-figures}
mkdir -p "$out"
runs=$out/runs
mkdir -p "$runs"

run() {  # run NAME SCENE [nsbridge run options...]
  local name=$1 scene=$2
  shift 2
  "$nsb" run "$root/scenes/$scene.toml" --out "$runs/$name" "$@" >/dev/null
}

# Largest |value| of a history.csv column.
peak() {  # peak FILE COLUMN
  awk -F, -v c="$2" 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == c) k = i; next }
                     { v = $k < 0 ? -$k : $k; if (v > m) m = v } END { printf "%.9g\n", m }' "$1"
}

# Figs. 3, 4: excitation 5, nonsmooth (Moreau–Jean, h = 1e-4) with the event-driven scheme
# as the reference.
run exc5-moreau bridge-exc5 --method moreau
run exc5-event bridge-exc5 --method event_driven

# Fig. 6: peak rotation against PGA, with pounding and without it (gaps of 1 m never close).
pga=(0.1 0.2 0.35 0.5 0.65 0.8 1.0)
: > "$out/fig6.dat"
echo "# pga_g peak_theta_pounding peak_theta_no_pounding [rad]" >> "$out/fig6.dat"
for i in 1 2 3 4 5 6 7; do
  run "exc$i" "bridge-exc$i" --method moreau
  run "exc$i-free" "bridge-exc$i" --method moreau --set model.gaps.left=1.0 \
    --set model.gaps.right=1.0
  echo "${pga[$((i - 1))]} $(peak "$runs/exc$i/history.csv" theta)" \
       "$(peak "$runs/exc$i-free/history.csv" theta)" >> "$out/fig6.dat"
done

# Fig. 7: the compliance approach over the paper's stiffness range.
factors=(1e-4 1e-2 1e0 1e2)
for f in "${factors[@]}"; do
  run "exc5-k$f" bridge-exc5 --method compliance --set "solver.stiffness_factor=$f"
done

# Fig. 8: the first pounding of the nonsmooth run, resolved at every step of the compliance
# runs in a window around it.
first=$(awk -F, 'NR > 1 && $3 == "impact" { print $1, $2; exit }' "$runs/exc5-moreau/events.csv")
t_first=${first% *}
contact=${first#* }
t_end=$(awk -v t="$t_first" 'BEGIN { printf "%.6f", t + 0.15 }')
for f in "${factors[@]}"; do
  run "exc5-k$f-first" bridge-exc5 --method compliance --set "solver.stiffness_factor=$f" \
    --set "solver.end_time=$t_end" --set output.sample_dt=0
done

gnuplot -e "runs='$runs'; out='$out'; contact=$contact; t_first=$t_first" "$here/figures.gp"
echo "paper-figures: $out (first pounding at contact $contact, t = $t_first s)"
