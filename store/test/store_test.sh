#!/usr/bin/env bash
# `nsbridge sweep --hdf5` end to end: DIR/sweep.h5 holds the numbers of the sweep's CSV files
# bit for bit (store_check.py, with Debian's h5py and numpy); a sweep killed with SIGKILL part
# way leaves a sweep.h5 that h5py opens, whose finished groups equal their runs' files, and a
# resume completes it, equal to an uninterrupted sweep but for the wall times; a design that
# keeps some history columns keeps exactly those.
#   bash store/test/store_test.sh NSBRIDGE
set -uo pipefail
nsb=$1
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

check() {  # check DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAILED: $what" >&2; fi
}

# Eight short runs of the benchmark bridge (1 s of record 5, with pounding): four seat
# frictions x two PGAs, so that the runs differ in their impacts.
design() {  # design FILE [OUTPUT_SECTION]
  cat > "$1" <<EOF
scene = "$root/scenes/bridge-exc5.toml"
set = ["solver.end_time=1"]
[[factor]]
key = "model.seats.friction"
values = [0.3, 0.4, 0.5, 0.7]
[[factor]]
key = "model.excitation.target_pga"
values = [0.5, 1.0]
${2:-}
EOF
}
design "$tmp/d.toml"

# (1) Every number of sweep.h5 equals its CSV file's.
out=$("$nsb" sweep "$tmp/d.toml" --out "$tmp/a" --jobs 2 --hdf5 2>&1)
check "sweep --hdf5 exits 0 and names the file" grep -q "store .*a/sweep.h5" <<<"$out"
check "sweep.h5 equals the CSV files bit for bit" "$py" "$here/store_check.py" equal "$tmp/a"

# (2) SIGKILL part way, once two runs are finished (--jobs 1: one run at a time).
"$nsb" sweep "$tmp/d.toml" --out "$tmp/b" --jobs 1 --hdf5 >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  n=$(ls "$tmp"/b/runs/*/row.csv 2>/dev/null | wc -l)
  [[ $n -ge 2 ]] && break
  sleep 0.05
done
kill -KILL "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
n=$(ls "$tmp"/b/runs/*/row.csv 2>/dev/null | wc -l)
check "the kill came part way ($n of 8 runs finished)" test "$n" -ge 2 -a "$n" -lt 8
check "after SIGKILL sweep.h5 opens and its finished groups equal their files" \
  "$py" "$here/store_check.py" partial "$tmp/b"
out=$("$nsb" sweep "$tmp/d.toml" --out "$tmp/b" --jobs 1 --hdf5 2>&1)
check "the resume skips the finished runs" grep -Eq "[1-9] already done" <<<"$out"
check "the resumed sweep.h5 equals its CSV files" "$py" "$here/store_check.py" equal "$tmp/b"
check "the resumed sweep.h5 equals the uninterrupted one but for wall times" \
  "$py" "$here/store_check.py" same "$tmp/a" "$tmp/b"

# (3) A design that keeps two history columns: exactly t and those, the rest as before; the
# file is made again from the run folders when the selection changes.
design "$tmp/d.toml" $'[output]\nhdf5_history = ["theta", "gN1"]'
out=$("$nsb" sweep "$tmp/d.toml" --out "$tmp/a" --jobs 2 --hdf5 2>&1)
check "a changed selection keeps the runs" grep -q "8 already done" <<<"$out"
check "a changed selection makes sweep.h5 again" grep -q "made again from the run folders" <<<"$out"
check "the selected columns equal history.csv's" "$py" "$here/store_check.py" equal "$tmp/a"

echo "store_test: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
