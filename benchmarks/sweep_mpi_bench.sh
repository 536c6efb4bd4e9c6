#!/usr/bin/env bash
# Parallel efficiency of `nsbridge sweep` over MPI: the Fig. 6 design (36 runs) in one process
# with one worker, and under `mpirun -np RANKS` with one worker per rank. Medians of REPEATS
# give efficiency = T(1 process) / (RANKS * T(RANKS ranks)) (goal >= 0.8 at 2 ranks).
#   bash benchmarks/sweep_mpi_bench.sh [NSBRIDGE] [REPEATS = 3] [RANKS = 2] [CSV = out/sweep_mpi_bench.csv]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
nsb=${1:-$root/build/app/nsbridge}
repeats=${2:-3}
ranks=${3:-2}
csv=${4:-out/sweep_mpi_bench.csv}
mkdir -p "$(dirname "$csv")"
design=$root/scenes/sweeps/fig6.toml
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# As root OpenMPI needs --allow-run-as-root; --oversubscribe lets RANKS exceed the cores.
flags=(--oversubscribe)
[[ $(id -u) -eq 0 ]] && flags+=(--allow-run-as-root)
echo "sweep_mpi_bench: $design, 1 process against $ranks ranks, $repeats repeats (median)"
echo "revision $(git -C "$root" rev-parse --short HEAD), load average $(cut -d' ' -f1 /proc/loadavg)"
echo "mode,repeat,wall_s" > "$csv"
now() { date +%s.%N; }
for r in $(seq "$repeats"); do
  t0=$(now)
  "$nsb" sweep "$design" --out "$tmp/one" --jobs 1 --restart > /dev/null
  t1=$(now)
  mpirun "${flags[@]}" -np "$ranks" "$nsb" sweep "$design" --out "$tmp/mpi" --jobs 1 --restart > /dev/null
  t2=$(now)
  echo "one,$r,$(echo "$t1 - $t0" | bc -l)" >> "$csv"
  echo "mpi,$r,$(echo "$t2 - $t1" | bc -l)" >> "$csv"
done
awk -F, -v ranks="$ranks" 'NR > 1 { v[$1] = v[$1] " " $3 }
  function med(s,   a, n, i, j, t) { n = split(s, a, " "); for (i = 1; i <= n; ++i)
      for (j = i + 1; j <= n; ++j) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
      return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
  END { one = med(v["one"]); mpi = med(v["mpi"]);
        printf "1 process: median %.3f s; %d ranks: median %.3f s; efficiency %.3f (goal >= 0.8)\n",
               one, ranks, mpi, one / (ranks * mpi) }' "$csv"
echo "load average after $(cut -d' ' -f1 /proc/loadavg)"
