#!/usr/bin/env bash
# End-to-end tests of the nsbridge command line: exit codes (0 success, 1 not solved or
# stopped early, 2 bad input), error messages that name the file, line or key, and output
# files that are complete or absent.
#   bash app/test/cli_test.sh NSBRIDGE
set -uo pipefail
nsb=$1
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

# expect CODE PATTERN -- ARGS...: runs nsbridge ARGS, checks the exit code and that stdout or
# stderr matches the extended regular expression PATTERN.
expect() {
  local code=$1 pattern=$2
  shift 3
  local out rc
  out=$("$nsb" "$@" 2>&1)
  rc=$?
  if [[ $rc -eq $code ]] && grep -Eq -- "$pattern" <<<"$out"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED: nsbridge $* -> exit $rc (expected $code), output:" >&2
    echo "$out" | head -5 >&2
  fi
}

check() {  # check DESCRIPTION COMMAND...: a plain assertion
  local what=$1
  shift
  if "$@"; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAILED: $what" >&2; fi
}

# --- nsbridge lcp -------------------------------------------------------------------------
lcp=$root/data/siconos-lcp
expect 0 'status: +solved' -- lcp "$lcp/lcp_trivial.dat"
for s in lemke pgs nfb enum; do
  expect 0 'status: +solved' -- lcp "$lcp/lcp_deudeu.dat" --solver "$s"
done
expect 0 '"status": *"solved"' -- lcp "$lcp/lcp_trivial.dat" --json
# Lemke is known to end on a secondary ray for CPS_3 (Siconos's own expected failure).
expect 1 'ray' -- lcp "$lcp/lcp_CPS_3.dat" --solver lemke
expect 2 'no such|not found|cannot open|does not exist' -- lcp "$tmp/missing.dat"
: > "$tmp/empty.dat"
expect 2 'empty\.dat' -- lcp "$tmp/empty.dat"
printf '2\n0\n2\n2\n2 2\n1 0\n0 1\n-1 nan\n' > "$tmp/nan.dat"
expect 2 'nan\.dat:8' -- lcp "$tmp/nan.dat"
printf '2\n0\n2\n2\n2 2\n1 0\n0 1\n' > "$tmp/short.dat"
expect 2 'short\.dat' -- lcp "$tmp/short.dat"
expect 2 'solver' -- lcp "$lcp/lcp_trivial.dat" --solver simplex

# --- nsbridge criterion -------------------------------------------------------------------
# Straight deck, W/L = 2.44/33.35, mu = 0.5: eta = +-mu L/W = +-6.834 (docs/criterion.md).
expect 0 'eta\+ = .*6\.83' -- criterion --skew 0 --width 2.44 --length 33.35 --friction 0.5
expect 0 '"rotation"' -- criterion --skew 30 --width 10 --length 30 --friction 0 --json
expect 2 'width' -- criterion --skew 0 --width -1 --length 30 --friction 0.5
expect 2 'friction' -- criterion --skew 0 --width 10 --length 30 --friction -0.1

# --- nsbridge run -------------------------------------------------------------------------
expect 0 'bouncing-ball' -- run "$root/scenes/bouncing-ball.toml" --out "$tmp/ball"
check "run writes history.csv, events.csv and summary.json" \
  test -s "$tmp/ball/history.csv" -a -s "$tmp/ball/events.csv" -a -s "$tmp/ball/summary.json"
check "no temporary file is left behind" test -z "$(ls -A "$tmp/ball" | grep -v -E '^(history|events)\.csv$|^summary\.json$')"
for m in moreau event_driven compliance; do
  expect 0 "method +$m" -- run "$root/scenes/rigid-deck-skew.toml" --out "$tmp/deck-$m" --method "$m"
done
expect 0 'bouncing-ball' -- run "$root/scenes/bouncing-ball.toml" --out "$tmp/ball2" \
  --set solver.step=1e-3 --set solver.end_time=0.5
expect 2 'solver\.nope|nope' -- run "$root/scenes/bouncing-ball.toml" --out "$tmp/x" --set solver.nope=1
expect 2 'method' -- run "$root/scenes/bouncing-ball.toml" --out "$tmp/x" --method rk4
sed 's/^mass = .*/mass = -1.0/' "$root/scenes/bouncing-ball.toml" > "$tmp/neg-mass.toml"
expect 2 'neg-mass\.toml:[0-9]+.*mass' -- run "$tmp/neg-mass.toml" --out "$tmp/neg"
check "a rejected scene writes no output" test ! -e "$tmp/neg"
printf '[model]\nkind = "bouncing_ball"\nmass = 1.0\nmas = 2.0\n' > "$tmp/typo.toml"
expect 2 'typo\.toml:4.*mas' -- run "$tmp/typo.toml" --out "$tmp/typo"
expect 2 'missing\.toml' -- run "$tmp/missing.toml"

echo "cli: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
