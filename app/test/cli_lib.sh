# The command-line tests' shared part, sourced by each test script with the nsbridge
# executable as its first argument: nsb, root (the source tree), tmp (removed on exit), the
# counters, expect and check.
nsb=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

# expect CODE PATTERN -- ARGS...: runs nsbridge ARGS, checks the exit code and that stdout or
# stderr matches the extended regular expression PATTERN. No command may hang (each is
# stopped after $limit s, exit 124) or print "internal error", which is kept for real bugs.
limit=20
expect() {
  local code=$1 pattern=$2
  shift 3
  local out rc
  out=$(timeout -s KILL "$limit" "$nsb" "$@" 2>&1)
  rc=$?
  if [[ $rc -eq $code ]] && grep -Eq -- "$pattern" <<<"$out" &&
     ! grep -q 'internal error' <<<"$out"; then
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
