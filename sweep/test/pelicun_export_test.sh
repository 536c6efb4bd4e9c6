#!/usr/bin/env bash
# nsbridge export pelicun end to end: a 6-run sweep of the benchmark bridge (2 records of the
# PEER fixture suite x 3 PGA levels, 0.3 s each, with a [fragility] section) exported, and the
# files checked by pelicun_export_check.py (pandas) against pelicun's documented formats and
# against results.csv and fragility.json; then the same results.csv with bent columns added
# (peak_bent<i>_ux, _uy) gives drifts |u| / H_i with the heights of bridge-exc5.toml; and a
# missing results.csv is refused with exit 2 and nothing written.
# Usage: pelicun_export_test.sh NSBRIDGE SOURCE_DIR
set -u
nsb=$(realpath "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

"$nsb" records import "$src/sweep/test/data/records-import/peer" --out suite >/dev/null ||
  fail "import"
mkdir -p data && ln -s "$src/data/ground-motions" data/ground-motions
cp "$src/scenes/bridge-exc5.toml" base.toml
cat > d.toml <<'EOT'
scene = "base.toml"
set = ["solver.end_time=0.3", "output.sample_dt=0.05"]
[[factor]]
key = "record"
suite = "suite/records.csv"
[[factor]]
key = "model.excitation.target_pga"
values = [0.3, 0.6, 0.9]
[fragility]
im = "model.excitation.target_pga"
[[fragility.limit_state]]
name = "theta_1.6e-4"
response = "peak_theta"
threshold = 1.6e-4
[[fragility.limit_state]]
name = "theta_3e-4"
response = "peak_theta"
threshold = 3e-4
[[fragility.limit_state]]
name = "theta_1"
response = "peak_theta"
threshold = 1
EOT
"$nsb" sweep d.toml --out s >/dev/null 2>&1 || fail "sweep exited $?"
[ -f s/fragility.json ] || fail "no fragility.json"
# Two limit states with an estimate (mixed stripes), one without (never reached).
[ "$(grep -c '"status": "fitted"' s/fragility.json)" -ge 2 ] || fail "fragility.json: $(cat s/fragility.json)"
out=$("$nsb" export pelicun s 2>&1) || fail "export exited $?: $out"
echo "$out" | grep -q "6 of 6 runs as demand samples" || fail "$out"
/usr/bin/python3 "$src/sweep/test/pelicun_export_check.py" s/pelicun s || fail "format check"

# Bent drifts: results.csv with bent columns (as a scene that records bent displacements
# writes them), fragility.json left out (the refit reads the design's own columns only).
mkdir b && cp s/manifest.toml b/ && cp -r s/runs b/
/usr/bin/python3 - s/results.csv b/results.csv <<'EOT'
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head = rows[0]
at = head.index("residual_theta") + 1
extra = ["peak_bent1_ux", "peak_bent1_uy", "peak_bent2_ux", "peak_bent2_uy", "peak_bent3_ux", "peak_bent3_uy"]
out = [head[:at] + extra + head[at:]]
for k, r in enumerate(rows[1:]):
    out.append(r[:at] + ["%r" % (0.001 * (k + 1) * (j + 1) * (-1) ** j) for j in range(6)] + r[at:])
csv.writer(open(sys.argv[2], "w", newline=""), lineterminator="\n").writerows(out)
EOT
out=$("$nsb" export pelicun b --design d.toml --out b/p 2>&1) || fail "bents: export exited $?: $out"
/usr/bin/python3 "$src/sweep/test/pelicun_export_check.py" b/p b 1.83,2.44,1.52 || fail "bent drifts"

msg=$("$nsb" export pelicun nowhere --out x/p 2>&1); rc=$?
[ $rc = 2 ] || fail "missing results.csv: exit $rc: $msg"
echo "$msg" | grep -q "nowhere/results.csv" || fail "missing results.csv: $msg"
[ ! -e x ] && [ ! -e nowhere ] || fail "missing results.csv: something was written"
echo "pelicun export: formats and values checked"
