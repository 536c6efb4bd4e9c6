#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in build-fuzz/ and runs each for
# SECONDS (default 60), two at a time. Fails on any crash, leak, timeout (hang), out-of-memory
# or sanitizer report; the input that found it is left in build-fuzz/artifacts/<target>/.
#   bash fuzz/run.sh [SECONDS] [TARGET...]
#   bash fuzz/run.sh --configure      only configure build-fuzz/ (scripts/run-tests.sh builds
#                                     the unit tests there too and runs them under the sanitizers)
# Seeds: scenes/ and data/ (docs/fuzzing.md); the growing corpus stays in build-fuzz/corpus/.
set -euo pipefail
cd "$(dirname "$0")/.."
configure_only=0
if [[ "${1:-}" == "--configure" ]]; then configure_only=1; shift; fi
seconds=${1:-60}
shift || true
targets=("$@")
[[ ${#targets[@]} -eq 0 ]] && targets=(fuzz_scene fuzz_records fuzz_lcp_dat fuzz_cli_numbers)
build=${NSB_FUZZ_BUILD:-build-fuzz}
jobs=$(nproc 2>/dev/null || echo 2)

# -O0 with line tables: the quickest sanitizer build to compile, with readable reports (the CI
# budget is compile time; 60 s of fuzzing at -O0 still runs 1e4-1e5 inputs per target).
CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Fuzz \
  -DCMAKE_CXX_FLAGS_FUZZ="-O0 -gline-tables-only" -DNSB_FUZZ=ON \
  -DNSB_BUILD_BENCHMARKS=OFF -DNSB_WITH_SICONOS=OFF -DNSB_WITH_MPI=OFF >/dev/null
[[ $configure_only -eq 1 ]] && exit 0
cmake --build "$build" -j "$jobs" --target "${targets[@]}" >/dev/null

# Seed corpora: every file a parser is meant to read, in the target's input layout.
seed() {  # seed TARGET: fills $build/corpus/TARGET (kept between runs)
  local t=$1 dir=$build/corpus/$1 f i=0
  mkdir -p "$dir"
  case $t in
    fuzz_scene)
      for f in scenes/*.toml; do { echo; cat "$f"; } > "$dir/seed-$(basename "$f")"; done
      { echo "solver.step=1e-3"; cat scenes/bouncing-ball.toml; } > "$dir/seed-override" ;;
    fuzz_records)
      for f in data/ground-motions/*; do
        [[ -f $f ]] || continue  # a folder (a record suite) is not itself a record
        case ${f,,} in
          *.at2) { printf '\x00'; head -c 4096 "$f"; } > "$dir/seed-$i" ;;
          *.csv) { printf '\x01'; head -c 4096 "$f"; } > "$dir/seed-$i" ;;
          *) { printf '\x02'; head -c 4096 "$f"; } > "$dir/seed-$i" ;;
        esac
        i=$((i + 1))
      done ;;
    fuzz_lcp_dat)
      for f in data/siconos-lcp/*.dat; do
        [[ $(stat -c %s "$f") -le 65536 ]] && cp "$f" "$dir/seed-$(basename "$f")"
      done ;;
    fuzz_cli_numbers)
      printf '\x00%s\n%s\n%s\n%s' 30 10 30 0.5 > "$dir/seed-criterion"
      printf '\x02%s\n%s\n%s\n%s' -45 2.44 33.35 0 > "$dir/seed-criterion-json"
      printf '\x01%s\n%s' 1e-12 0 > "$dir/seed-lcp"
      printf '\x03%s\n%s' 1e-8 100 > "$dir/seed-lcp-json" ;;
  esac
  # The inputs that once found bugs are seeds too.
  [[ -d fuzz/regressions/$t ]] && cp fuzz/regressions/"$t"/* "$dir"/ 2>/dev/null || true
}

run() {  # run TARGET: libFuzzer for $seconds; its log in $build/logs/TARGET.log
  local t=$1
  mkdir -p "$build/artifacts/$t" "$build/logs"
  seed "$t"
  if "$build/fuzz/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
      -print_final_stats=1 -artifact_prefix="$build/artifacts/$t/" "$build/corpus/$t" \
      >"$build/logs/$t.log" 2>&1; then
    echo "fuzz: $t: $(grep -E '^stat::number_of_executed_units' "$build/logs/$t.log" | awk '{print $2}') executions," \
         "$(grep -Eo 'cov: [0-9]+' "$build/logs/$t.log" | tail -1) edges, no failure"
  else
    echo "fuzz: $t FAILED (log: $build/logs/$t.log, input: $build/artifacts/$t/)" >&2
    tail -30 "$build/logs/$t.log" >&2
    return 1
  fi
}

status=0
pids=()
names=()
for t in "${targets[@]}"; do
  run "$t" & pids+=($!); names+=("$t")
  if [[ ${#pids[@]} -ge $jobs ]]; then
    wait "${pids[0]}" || status=1
    pids=("${pids[@]:1}")
  fi
done
for p in "${pids[@]}"; do wait "$p" || status=1; done
exit $status
