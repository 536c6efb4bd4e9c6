#!/usr/bin/env bash
# The example of limit-state fragility (scenes/sweeps/limit-states.toml, docs/workflow.md):
# runs its 30 runs, then recounts every stripe of fragility.json from the runs' own
# summary.json files (limit_fragility_check.py: status, limit_states, peaks, achieved Sa), and
# checks that the plots show the unseated runs (ida-unseated.csv, one row each; exceedance.csv
# with their count), and that a limit state no run watches stops the fragility (exit 2).
# The recount catches a break of the rules it checks: with the unseated runs dropped as
# failures (fragility_sweep.cpp's completed() on integrators::succeeded instead of is_result)
# all 6 limit states differ from the recount; with an unseated run compared by its response
# instead of reaching the limit state, 4 of them differ.
#   bash sweep/test/limit_fragility_test.sh NSBRIDGE
set -uo pipefail
nsb=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
design="$root/scenes/sweeps/limit-states.toml"
failed=0
fail() { echo "FAILED: $*" >&2; failed=$((failed + 1)); }

"$nsb" sweep "$design" --out "$tmp/o" --jobs 2 --plot --response peak_theta1 \
  --pga-key model.excitation.target_sa --limit 0.005 > "$tmp/log" 2>&1
rc=$?
if [[ $rc -ne 0 ]]; then
  cat "$tmp/log" >&2
  fail "nsbridge sweep exited $rc (unseated runs are results: exit 0 expected)"
fi
python3 "$root/sweep/test/limit_fragility_check.py" "$design" "$tmp/o" || fail "recount"
unseated=$(grep -c ',unseated,' "$tmp/o/results.csv")
[[ $(($(wc -l < "$tmp/o/plots/ida-unseated.csv") - 1)) -eq $unseated ]] ||
  fail "ida-unseated.csv: one row per unseated run ($unseated)"
[[ $(awk -F, 'NR > 1 { s += $5 } END { print s }' "$tmp/o/plots/exceedance.csv") -eq $unseated ]] ||
  fail "exceedance.csv: the unseated column sums to the unseated runs ($unseated)"
[[ -s "$tmp/o/fragility.png" ]] || fail "fragility.png"
# A limit state that no run watches (the one-deck bridge has no hinge): exit 2 after the runs,
# naming those watched.
cat > "$tmp/hinge.toml" <<TOML
scene = "$root/scenes/bridge-unseating.toml"
set = ["solver.end_time=5"]
fragility.im = "model.excitation.target_pga"
[[factor]]
key = "model.excitation.target_pga"
values = [0.3, 0.83]
[[fragility.limit_state]]
limit_state = "unseating_hinge_1"
TOML
out=$("$nsb" sweep "$tmp/hinge.toml" --out "$tmp/hinge" 2>&1)
rc=$?
[[ $rc -eq 2 ]] || fail "a limit state no run watches: exit $rc, 2 expected"
grep -q 'fragility.limit_state unseating_hinge_1: no run of the sweep watches "unseating_hinge_1" (results.csv has no column unseating_hinge_1_exceeded; watched: unseating_left, closure_left, unseating_right' <<<"$out" ||
  fail "a limit state no run watches: $out"
echo "limit_fragility_test: $failed failed"
[[ $failed -eq 0 ]]
