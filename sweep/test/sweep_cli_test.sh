#!/usr/bin/env bash
# End-to-end tests of `nsbridge sweep`: design errors (exit 2, nothing written), a failing run
# inside a sweep (exit 1, a row with its status), resume, refusal of a changed design, the
# equality of --jobs 1 and --jobs 2, the Fig. 6 design and the plots, --gnuplot, and the
# warnings of a sweep's run against `nsbridge run` with the same overrides, and the fragility
# of a sweep (fragility.json against the rows counted by hand, errors of [fragility]).
#   bash sweep/test/sweep_cli_test.sh NSBRIDGE
set -uo pipefail
nsb=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

check() {  # check DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAILED: $what" >&2; fi
}
# run CODE PATTERN ARGS...: nsbridge ARGS must exit with CODE and print PATTERN (ERE).
run() {
  local code=$1 pattern=$2
  shift 2
  local out rc
  out=$("$nsb" "$@" 2>&1)
  rc=$?
  if [[ $rc -eq $code ]] && grep -Eq -- "$pattern" <<<"$out"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED: nsbridge $* -> exit $rc (expected $code, /$pattern/):" >&2
    echo "$out" | head -5 >&2
  fi
}
# The rows of a results.csv without wall_s, the last column.
rows() { awk -F, '{ NF--; print }' OFS=, "$1"; }

design() {  # design FILE SCENE BODY: a design file with the base scene by absolute path
  printf 'scene = "%s/scenes/%s.toml"\n%s\n' "$root" "$2" "$3" > "$1"
}

# --- Design errors: exit 2 before any run, nothing written ------------------------------
design "$tmp/unknown.toml" bouncing-ball $'[[factor]]\nkey = "model.colour"\nvalues = [1]'
run 2 'unknown.toml:2: factor model.colour = 1: .*model.colour' sweep "$tmp/unknown.toml" --out "$tmp/o1"
check "no output after a design error" test ! -e "$tmp/o1"
design "$tmp/value.toml" bouncing-ball $'[[factor]]\nkey = "model.restitution"\nvalues = [0.5, 2]'
run 2 'factor model.restitution = 2: .*must be in \[0, 1\]' sweep "$tmp/value.toml" --out "$tmp/o1"
design "$tmp/empty.toml" bouncing-ball $'[[factor]]\nkey = "model.restitution"\nvalues = []'
run 2 'empty.toml:4:10: factor\[0\].values: must not be empty' sweep "$tmp/empty.toml" --out "$tmp/o1"
run 2 "fig6.toml: scene: .*solver.end_time \\(override\\)" sweep "$root/scenes/sweeps/fig6.toml" --out "$tmp/o1" --set solver.end_time=-1
check "no output after design errors" test ! -e "$tmp/o1"

# --- A run that fails numerically is a row; the sweep goes on -----------------------------
# Event-driven with g = 1e40: the adaptive step underflows at t = 0 (status "stalled").
design "$tmp/ball.toml" bouncing-ball \
  $'set = ["solver.method=event_driven"]\n[[factor]]\nkey = "model.gravity"\nvalues = [9.81, 1e40, 4.905]'
run 1 'failed +1 of 3 runs' sweep "$tmp/ball.toml" --out "$tmp/ball"
check "stalled row" grep -q '^0001,1e+40,stalled,' "$tmp/ball/results.csv"
check "completed rows" test "$(grep -c ',completed,' "$tmp/ball/results.csv")" -eq 2
check "outputs of the failed run" test -s "$tmp/ball/runs/0001/summary.json"

# --- Resume and a changed design ------------------------------------------------------------
rm "$tmp/ball/runs/0002/row.csv"
run 1 '2 already done \(skipped\), 1 run now' sweep "$tmp/ball.toml" --out "$tmp/ball"
design "$tmp/ball.toml" bouncing-ball \
  $'set = ["solver.method=event_driven"]\n[[factor]]\nkey = "model.gravity"\nvalues = [9.81, 3.0]'
run 2 'different design.*--restart' sweep "$tmp/ball.toml" --out "$tmp/ball"
check "refused: old rows kept" grep -q '^0002,4.905,' "$tmp/ball/results.csv"
run 0 '0 already done \(skipped\), 2 run now' sweep "$tmp/ball.toml" --out "$tmp/ball" --restart
check "restarted: old runs removed" test ! -e "$tmp/ball/runs/0002"

# --- Fig. 6 (short records) with 1 and 2 workers: the same rows --------------------------------
fig6=$root/scenes/sweeps/fig6.toml
run 0 '36 in the design' sweep "$fig6" --out "$tmp/f1" --jobs 1 --set solver.end_time=2
run 0 '2 threads' sweep "$fig6" --out "$tmp/f2" --jobs 2 --set solver.end_time=2 --plot
check "fig6: 36 rows" test "$(wc -l < "$tmp/f1/results.csv")" -eq 37
check "fig6: --jobs 1 and 2 give the same rows" cmp -s <(rows "$tmp/f1/results.csv") <(rows "$tmp/f2/results.csv")
for f in ida.csv ida.png ida.svg exceedance.csv exceedance.png exceedance.svg; do
  check "plot $f" test -s "$tmp/f2/plots/$f"
done

# --- One factor at a time on the bridge: the tornado chart --------------------------------------
design "$tmp/oat.toml" bridge-exc7 $'mode = "oat"\nset = ["solver.end_time=3"]
[[factor]]\nkey = "model.seats.friction"\nvalues = [0.2, 0.8]
[[factor]]\nkey = "model.gaps.left"\nvalues = [0.005, 0.05]'
run 0 '5 in the design' sweep "$tmp/oat.toml" --out "$tmp/oat" --plot --limit 0.001
for f in tornado.csv tornado.png tornado.svg; do check "plot $f" test -s "$tmp/oat/plots/$f"; done
check "tornado rows" test "$(wc -l < "$tmp/oat/plots/tornado.csv")" -eq 3

# --- The plots are drawn by the gnuplot that --gnuplot names ------------------------------------
printf '#!/bin/sh\nexit 3\n' > "$tmp/no-gnuplot"
chmod +x "$tmp/no-gnuplot"
run 1 'gnuplot failed' sweep "$tmp/oat.toml" --out "$tmp/oat" --plot-only --limit 0.001 \
  --gnuplot "$tmp/no-gnuplot"

# --- A run of a sweep is `nsbridge run`: the same summary, warnings included ---------------------
# Excitation 7 with a coarse step: 6 warnings (step period, accuracy, penetration of each
# contact; its energy balance error, 0.75 %, is within the method's 1 %, and the step equals the
# record's sampling interval of 0.02 s, which is not longer than it).
design "$tmp/coarse.toml" bridge-exc7 $'[[factor]]\nkey = "solver.step"\nvalues = [0.02]'
run 0 '1 in the design' sweep "$tmp/coarse.toml" --out "$tmp/coarse"
run 0 'warnings   6' run "$root/scenes/bridge-exc7.toml" --set solver.step=0.02 --quiet \
  --out "$tmp/coarse-run"
warnings() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["warnings"])' "$1"; }
check "a sweep run has warnings" test "$(warnings "$tmp/coarse/runs/0000/summary.json")" != "[]"
check "the warnings of a sweep run and of nsbridge run are the same" \
  test "$(warnings "$tmp/coarse/runs/0000/summary.json")" = "$(warnings "$tmp/coarse-run/summary.json")"
check "the summaries are the same but for the wall time and CPU seconds" \
  cmp -s <(grep -v -e wall_time -e cpu_seconds "$tmp/coarse/runs/0000/summary.json") \
         <(grep -v -e wall_time -e cpu_seconds "$tmp/coarse-run/summary.json")
check "the histories are the same" \
  cmp -s "$tmp/coarse/runs/0000/history.csv" "$tmp/coarse-run/history.csv"

# --- Fragility: 3 stripes x 3 records on the bridge, counted by hand from results.csv ----------
design "$tmp/frag.toml" bridge-exc5 $'set = ["solver.end_time=4", "model.excitation.longitudinal_pga=0"]
[[factor]]\nkey = "model.excitation.target_pga"\nvalues = [0.2, 0.6, 1.2]
[[factor]]\nkey = "record"
[[factor.records]]\nname = "sylmar"\ntransverse = "'"$root"$'/data/ground-motions/RSN1084_NORTHR_SCS142.AT2"
[[factor.records]]\nname = "elcentro"\ntransverse = "'"$root"$'/data/ground-motions/RSN6_IMPVALL.I_I-ELC180.AT2"
[[factor.records]]\nname = "friuli"
transverse = "'"$root"$'/data/ground-motions/asce7-suite/RSN125_FRIULI.A_A-TMZ000.AT2"
[fragility]\nim = "model.excitation.target_pga"
[[fragility.limit_state]]\nname = "theta_5e-4"\nresponse = "peak_theta"\nthreshold = 5e-4
[[fragility.limit_state]]\nname = "never"\nresponse = "peak_theta"\nthreshold = 1'
run 0 'fragility  .*fragility.png' sweep "$tmp/frag.toml" --out "$tmp/frag" --jobs 2 --plot
check "fragility.png" test -s "$tmp/frag/fragility.png"
# "im n exceeded" per stripe: from results.csv by awk, and from fragility.json.
by_hand() {
  awk -F, -v t="$2" 'NR > 1 { n[$2]++; if ($9 >= t) k[$2]++ }
    END { for (im in n) print im, n[im], k[im] + 0 }' "$1" | sort -g
}
from_json() {
  python3 -c 'import json, sys
for s in json.load(open(sys.argv[1]))["limit_states"][sys.argv[2]]["stripes"]:
    print(s["im"], s["n"], s["exceeded"])' "$1" "$2"
}
check "results.csv column 9 is peak_theta (after peak_x, peak_x_error, peak_y, peak_y_error)" test "$(head -1 "$tmp/frag/results.csv" | cut -d, -f9)" = peak_theta
check "fragility stripes = the rows counted by hand" \
  cmp -s <(by_hand "$tmp/frag/results.csv" 5e-4) <(from_json "$tmp/frag/fragility.json" theta_5e-4)
check "the stripes hold 0, 1 and 3 of 3 runs over 5e-4" \
  test "$(from_json "$tmp/frag/fragility.json" theta_5e-4)" = $'0.2 3 0\n0.6 3 1\n1.2 3 3'
check "3 stripes of 3 runs" test "$(from_json "$tmp/frag/fragility.json" never)" = $'0.2 3 0\n0.6 3 0\n1.2 3 0'
check "no exceedance: null and the status" python3 -c 'import json, sys
ls = json.load(open(sys.argv[1]))["limit_states"]["never"]
assert ls["status"] == "no_exceedances" and ls["theta"] is None and ls["ci95_beta"] is None
assert ls["moments"]["status"] == "censored"' "$tmp/frag/fragility.json"
check "no NaN in fragility.json" test "$(grep -ci nan "$tmp/frag/fragility.json")" -eq 0
# A changed [fragility] changes no run: the rerun resumes and refits; --plot-only refits too.
sed -i 's/threshold = 1$/threshold = 2e-4/' "$tmp/frag.toml"
run 0 '9 already done \(skipped\), 0 run now' sweep "$tmp/frag.toml" --out "$tmp/frag"
check "refitted after the threshold changed" \
  cmp -s <(by_hand "$tmp/frag/results.csv" 2e-4) <(from_json "$tmp/frag/fragility.json" never)
rm "$tmp/frag/fragility.json"
run 0 'fragility  .*fragility.json' sweep "$tmp/frag.toml" --out "$tmp/frag" --plot-only
check "--plot-only writes fragility.json" test -s "$tmp/frag/fragility.json"

# --- Bad [fragility] input: exit 2 naming the key, nothing written ------------------------------
fragdesign() {  # fragdesign FILE FRAGILITY-BODY: a bouncing-ball grid with a [fragility] section
  design "$1" bouncing-ball $'[[factor]]\nkey = "model.restitution"\nvalues = [0.5, 0.9]\n'"$2"
}
fragdesign "$tmp/f1.toml" $'[fragility]\nim = "model.gravity"\n[[fragility.limit_state]]\nname = "a"\nresponse = "peak_y"\nthreshold = 1'
run 2 'f1.toml:6:6: fragility.im: "model.gravity" is not a factor' sweep "$tmp/f1.toml" --out "$tmp/o2"
fragdesign "$tmp/f2.toml" $'[fragility]\nim = "model.restitution"\n[[fragility.limit_state]]\nname = "a"\nresponse = "peak_theta"\nthreshold = 1'
run 2 'f2.toml:9:12: fragility.limit_state\[0\].response: "peak_theta" is not a results.csv column' \
  sweep "$tmp/f2.toml" --out "$tmp/o2"
fragdesign "$tmp/f3.toml" $'[fragility]\nim = "model.restitution"\n[[fragility.limit_state]]\nname = "a"\nresponse = "peak_y"\nthreshold = inf'
run 2 'f3.toml:10:13: fragility.limit_state\[0\].threshold: required: a finite number' \
  sweep "$tmp/f3.toml" --out "$tmp/o2"
fragdesign "$tmp/f4.toml" $'[fragility]\nim = "model.restitution"\nlimit = 1'
run 2 'f4.toml:7:9: fragility.limit: unknown key' sweep "$tmp/f4.toml" --out "$tmp/o2"
check "no output after [fragility] errors" test ! -e "$tmp/o2"

echo "sweep_cli_test: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
