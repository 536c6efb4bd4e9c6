#!/usr/bin/env bash
# Fault injection for sweeps (docs/sweep.md, "Resume"; docs/cli.md, "What each fault gets"):
#   1. an input whose content changed after some runs were made (a record, the base scene):
#      the resume is refused (exit 2) with a message naming the file, and nothing in the
#      sweep's folder changes; the file restored, the resume goes on;
#   2. a sweep stopped by SIGINT and SIGKILL at random moments, several times, then resumed:
#      results.csv equals a clean run's byte for byte apart from wall_s, so do every run's
#      history.csv and events.csv, and no temporary file is left behind;
#   3. --jobs 1 and --jobs 2 give the same results.csv (apart from wall_s) and run files.
# Usage: sweep_faults.sh NSBRIDGE SOURCE_DIR [SEED]
set -u
nsb=$(realpath "$1")
src=$(cd "$2" && pwd)
seed=${3:-$(( $(date +%s) % 32768 ))}
RANDOM=$seed
echo "seed $seed (rerun with it as the third argument to repeat the kill times)"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

# A small sweep of the benchmark bridge, 2 records x 4 friction coefficients, 8 s each. The
# base scene is a copy (so that the test can change it); its own records are found in
# ./data/ (the scene's lookup: docs/scenes.md), the factor's beside the design.
mkdir -p data
ln -s "$src/data/ground-motions" data/ground-motions
cp "$src/scenes/bridge-exc5.toml" base.toml
cp "$src/data/ground-motions/RSN6_IMPVALL.I_I-ELC180.AT2" a.AT2
cp "$src/data/ground-motions/RSN1084_NORTHR_SCS142.AT2" b.AT2
cat > d.toml <<'EOF'
scene = "base.toml"
set = ["solver.end_time=8", "output.sample_dt=0.02"]
[[factor]]
key = "record"
records = [ { name = "a", transverse = "a.AT2" }, { name = "b", transverse = "b.AT2" } ]
[[factor]]
key = "model.seats.friction"
values = [0.2, 0.4, 0.6, 0.8]
EOF

# results.csv without its last column (wall_s).
strip() { awk -F, '{NF--; print}' OFS=, "$1"; }
# Every entry of a folder with its modification time, and every file's checksum.
snapshot() { (cd "$1" && find . -printf '%y %p %T@\n' | sort && find . -type f -print0 | sort -z |
              xargs -0 sha256sum); }
# Same results (apart from wall_s) and the same history.csv and events.csv in every run.
same_sweep() {
  cmp -s <(strip "$1/results.csv") <(strip "$2/results.csv") ||
    fail "$3: results.csv differs from the clean run's: $(diff <(strip "$1/results.csv") \
      <(strip "$2/results.csv") | head -4)"
  for run in "$1"/runs/*/; do
    id=$(basename "$run")
    for f in history.csv events.csv limit_states.csv; do  # row.csv holds wall_s
      [ -f "$run/$f" ] || fail "$3: runs/$id/$f missing in the clean run"
      cmp -s "$run/$f" "$2/runs/$id/$f" || fail "$3: runs/$id/$f differs from the clean run's"
    done
  done
  [ "$(ls "$1/runs" | wc -l)" = "$(ls "$2/runs" | wc -l)" ] || fail "$3: not the same runs"
  leftover=$(find "$2" -name '.*.tmp*' -o -name '.*.old-*')
  [ -z "$leftover" ] || fail "$3: temporary files left behind: $leftover"
}

# The clean run every other one is compared with; its wall time [ms] sets the kill times.
start=$(date +%s%N)
"$nsb" sweep d.toml --out clean --jobs 2 > clean.log 2>&1 || fail "clean run: exit $?"
clean_ms=$(( ($(date +%s%N) - start) / 1000000 ))
[ "$(wc -l < clean/results.csv)" = 9 ] || fail "clean run: not 8 rows"
echo "clean run: $clean_ms ms"

# --- 1. an input changed between a run and its resume -----------------------------------
refused() {  # $1: the file changed, named in the message
  before=$(snapshot clean)
  "$nsb" sweep d.toml --out clean --jobs 2 > refused.log 2>&1
  rc=$?
  [ $rc = 2 ] || fail "changed $1: exit $rc, expected 2: $(cat refused.log)"
  grep -q "$1: changed since the runs in clean were made" refused.log ||
    fail "changed $1: the message does not name the file: $(cat refused.log)"
  [ "$before" = "$(snapshot clean)" ] || fail "changed $1: the refused resume wrote into clean/"
}
cp a.AT2 a.orig
sed -i '2s/$/ (edited)/' a.AT2       # the title line: the same accelerations, another content
refused a.AT2
mv a.orig a.AT2                      # restored: the old rows are valid again
"$nsb" sweep d.toml --out clean --jobs 2 > resumed.log 2>&1 || fail "restored: exit $?"
grep -q "8 already done" resumed.log || fail "restored: the resume did not skip the 8 runs"
cp base.toml base.orig
echo "# a comment: the same scene, another content" >> base.toml
refused base.toml
mv base.orig base.toml
"$nsb" sweep d.toml --out clean --jobs 2 > resumed.log 2>&1 || fail "restored scene: exit $?"
echo "ok: a changed record or base scene is refused with its name, nothing written"

# --- 2. SIGINT and SIGKILL at random moments, then resume ---------------------------------
stopped=0
round=0
# Job control: a background command of a script otherwise starts with SIGINT ignored.
set -m
# Rounds until the sweep was stopped 6 times (SIGINT and SIGKILL in turn), or it got to its end.
while [ $stopped -lt 6 ] && [ $round -lt 12 ]; do
  done_runs=$(find killed/runs -name row.csv 2> /dev/null | wc -l)
  [ "$done_runs" -lt 8 ] || break
  round=$((round + 1))
  sig=$([ $((round % 2)) = 1 ] && echo INT || echo KILL)
  "$nsb" sweep d.toml --out killed --jobs 2 > killed.log 2>&1 &
  pid=$!
  # A random moment within 70 % of the time the runs still to do take, from the start (reading
  # the design) to a run's last write.
  ms=$(( clean_ms * (8 - done_runs) / 8 * (RANDOM % 700) / 1000 ))
  sleep "$(printf '%d.%03d' $((ms / 1000)) $((ms % 1000)))"
  kill -s $sig $pid 2> /dev/null
  wait $pid
  rc=$?
  [ $rc = 0 ] || stopped=$((stopped + 1))
  echo "round $round: SIG$sig after $ms ms, exit $rc," \
       "$(find killed/runs -name row.csv 2> /dev/null | wc -l) runs done"
done
set +m
[ $stopped -ge 4 ] || fail "only $stopped rounds were stopped before the end: no test"
# What a SIGKILL during a write leaves (io::write_file_atomically's ".<name>.tmp<pid>",
# io::write_file_set's ".<id>.tmp-<pid>-<n>"), in the sweep's folder, in runs/ and in a run
# that has no row.csv yet.
mkdir -p killed
echo partial > killed/.results.csv.tmp4242
if [ -d killed/runs ]; then
  mkdir killed/runs/.0001.tmp-4242-0
  echo partial > killed/runs/.0001.tmp-4242-0/history.csv
fi
for run in $([ -d killed/runs ] && ls -d killed/runs/*/); do
  [ -f "$run/row.csv" ] || { echo partial > "$run/.history.csv.tmp4242"; break; }
done
"$nsb" sweep d.toml --out killed --jobs 2 > killed.log 2>&1 || fail "resume after kills: exit $?"
same_sweep clean killed "resumed after SIGINT and SIGKILL"
echo "ok: stopped $stopped times and resumed: the clean run's results"

# --- 3. --jobs 1 and --jobs 2 -------------------------------------------------------------
"$nsb" sweep d.toml --out one --jobs 1 > one.log 2>&1 || fail "--jobs 1: exit $?"
same_sweep clean one "--jobs 1 against --jobs 2"
echo "ok: --jobs 1 equals --jobs 2"
