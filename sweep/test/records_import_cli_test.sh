#!/usr/bin/env bash
# nsbridge records import end to end: the PEER search fixture and the COSMOS V2 fixture
# (test/data/records-import) imported into suites, then a short sweep of the benchmark bridge
# over each suite runs every record, its factor's levels named as the suite names them.
# Usage: records_import_cli_test.sh NSBRIDGE SOURCE_DIR
set -u
nsb=$(realpath "$1")
src=$(cd "$2" && pwd)
data=$src/sweep/test/data/records-import
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

for kind in peer cosmos; do
  out=$("$nsb" records import "$data/$kind" --out "suite-$kind" 2>&1) ||
    fail "$kind: import exited $?: $out"
  echo "$out" | grep -q "records import: 2 records" || fail "$kind: $out"
  [ -f "suite-$kind/records.csv" ] || fail "$kind: no records.csv"
  # The bridge scene, 0.3 s: its records found under ./data (docs/scenes.md).
  mkdir -p data && ln -sfn "$src/data/ground-motions" data/ground-motions
  cp "$src/scenes/bridge-exc5.toml" base.toml
  cat > "d-$kind.toml" <<EOT
scene = "base.toml"
set = ["solver.end_time=0.3", "output.sample_dt=0.05"]
[[factor]]
key = "record"
suite = "suite-$kind/records.csv"
EOT
  out=$("$nsb" sweep "d-$kind.toml" --out "sweep-$kind" 2>&1) || fail "$kind: sweep exited $?: $out"
  rows=$(tail -n +2 "sweep-$kind/results.csv" | wc -l)
  [ "$rows" = 2 ] || fail "$kind: $rows rows in results.csv"
  grep -c ',completed,' "sweep-$kind/results.csv" | grep -qx 2 ||
    fail "$kind: not every run completed: $(cat "sweep-$kind/results.csv")"
done
grep -q '^0000,RSN101,' sweep-peer/results.csv || fail "peer: level names: $(cat sweep-peer/results.csv)"
grep -q '^0001,NP00125_19990921T1747,' sweep-cosmos/results.csv ||
  fail "cosmos: level names: $(cat sweep-cosmos/results.csv)"
echo "records import: PEER and COSMOS suites imported and swept"
