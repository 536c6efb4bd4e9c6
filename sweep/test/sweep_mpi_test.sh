#!/usr/bin/env bash
# The sweep under MPI: `mpirun -np 2` gives results.csv rows identical to one process with one
# thread (apart from wall_s), and both ranks take runs.
#   bash sweep/test/sweep_mpi_test.sh NSBRIDGE MPIEXEC
set -uo pipefail
nsb=$1
mpiexec=$2
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# OpenMPI refuses root without --allow-run-as-root, and more ranks than cores without
# --oversubscribe (CI machines have 2 cores).
flags=(--oversubscribe)
[[ $(id -u) -eq 0 ]] && flags+=(--allow-run-as-root)
fig6=$root/scenes/sweeps/fig6.toml
fail=0
"$mpiexec" "${flags[@]}" -np 2 "$nsb" sweep "$fig6" --out "$tmp/mpi" --set solver.end_time=2 \
  > "$tmp/mpi.log" 2>&1 || { echo "FAILED: mpirun exited $?" >&2; cat "$tmp/mpi.log" >&2; fail=1; }
"$nsb" sweep "$fig6" --out "$tmp/one" --jobs 1 --set solver.end_time=2 > /dev/null || fail=1
# Both ranks ran some of the 36 runs.
grep -Eq 'on 2 processes .*; [1-9][0-9]* runs on ranks other than 0' "$tmp/mpi.log" ||
  { echo "FAILED: rank 1 ran nothing" >&2; cat "$tmp/mpi.log" >&2; fail=1; }
rows() { awk -F, '{ NF--; print }' OFS=, "$1"; }
if ! cmp -s <(rows "$tmp/mpi/results.csv") <(rows "$tmp/one/results.csv"); then
  echo "FAILED: mpirun -np 2 and --jobs 1 differ" >&2
  diff <(rows "$tmp/mpi/results.csv") <(rows "$tmp/one/results.csv") | head >&2
  fail=1
fi
[[ $fail -eq 0 ]] && echo "sweep_mpi_test: mpirun -np 2 equals --jobs 1 (36 rows)"
exit $fail
