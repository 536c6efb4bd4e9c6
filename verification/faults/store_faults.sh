#!/usr/bin/env bash
# Fault injection for `nsbridge sweep --hdf5` (docs/outputs.md, "sweep.h5"; docs/cli.md, "What
# each fault gets"), each case with its exit code, the file and key its message names, and what
# it leaves:
#   1. DIR/sweep.h5 cannot be created (a folder has its name): exit 2 naming it, no run made;
#   2. DIR/sweep.h5 holds another design's runs: exit 2 naming it, no run made, the file kept;
#   3. output.hdf5_history neither "all", "none" nor a list of names: exit 2 at its line, no
#      folder made;
#   4. output.hdf5_history names a column the runs' history lacks: exit 2 naming the design,
#      the key and the column; sweep.h5 opens, with no group for the run.
# Usage: store_faults.sh NSBRIDGE SOURCE_DIR
set -u
nsb=$(realpath "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

# expect CODE PATTERN ARGS...: nsbridge ARGS exits with CODE and prints PATTERN (ERE).
expect() {
  local code=$1 pattern=$2
  shift 2
  out=$("$nsb" "$@" 2>&1)
  local rc=$?
  [[ $rc -eq $code ]] || fail "nsbridge $* -> exit $rc, expected $code: $out"
  grep -Eq -- "$pattern" <<<"$out" || fail "nsbridge $* -> no /$pattern/ in: $out"
}
rows_in() { find "$1" -name row.csv 2>/dev/null | wc -l; }

# Two runs of the bouncing ball, a fraction of a second each.
design() {  # design FILE HEIGHTS [EXTRA]
  printf 'scene = "%s/scenes/bouncing-ball.toml"\nset = ["solver.end_time=0.5"]\n[[factor]]\nkey = "model.height"\nvalues = %s\n%s\n' \
    "$src" "$2" "${3:-}" > "$1"
}
design a.toml "[1.0, 2.0]"
design b.toml "[1.5, 2.5]"

# 1. A folder where sweep.h5 goes.
mkdir -p d1/sweep.h5
expect 2 "d1/sweep.h5: cannot create the HDF5 file" sweep a.toml --out d1 --hdf5
[[ $(rows_in d1) -eq 0 ]] || fail "case 1: runs were made"

# 2. Another design's sweep.h5 in a folder of this design.
expect 0 "store .*d2/sweep.h5" sweep a.toml --out d2 --hdf5
mkdir d3 && cp d2/sweep.h5 d3/
sum=$(md5sum < d3/sweep.h5)
expect 2 "d3/sweep.h5: holds the runs of a different design.*--restart" sweep b.toml --out d3 --hdf5
[[ $(rows_in d3) -eq 0 ]] || fail "case 2: runs were made"
[[ $(md5sum < d3/sweep.h5) == "$sum" ]] || fail "case 2: the other design's sweep.h5 changed"
expect 0 "store .*d3/sweep.h5" sweep b.toml --out d3 --hdf5 --restart

# 3. A value hdf5_history does not take.
design c.toml "[1.0, 2.0]" $'[output]\nhdf5_history = 3'
expect 2 "c.toml:7:16: output.hdf5_history: must be \"all\", \"none\" or an array" \
  sweep c.toml --out d4 --hdf5
[[ ! -e d4 ]] || fail "case 3: the folder was made"
design c.toml "[1.0, 2.0]" $'[output]\nhdf5_history = "some"'
expect 2 "c.toml:7:16: output.hdf5_history" sweep c.toml --out d4 --hdf5
[[ ! -e d4 ]] || fail "case 3: the folder was made"

# 4. A column no history has.
design c.toml "[1.0, 2.0]" $'[output]\nhdf5_history = ["y", "theta"]'
expect 2 "c.toml:7: output.hdf5_history: run 000[01]'s history.csv has no column \"theta\"" \
  sweep c.toml --out d5 --hdf5 --jobs 1
/usr/bin/python3 -c "
import h5py, sys
with h5py.File(sys.argv[1], 'r') as f:
    assert len(f['runs']) == 0, list(f['runs'])
" d5/sweep.h5 || fail "case 4: sweep.h5 does not open, or holds a group"
echo "store faults: 4 classes ok"
