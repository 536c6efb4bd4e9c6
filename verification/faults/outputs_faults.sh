#!/bin/bash
# Fault injection on output folders (docs/cli.md, "Output folders" and "What each fault
# gets"): symbolic links, the current directory, a full disk (a file size limit: ulimit -f,
# with SIGXFSZ ignored, so that write(2) fails with EFBIG as it fails with ENOSPC on a full
# disk), read-only folders, and runs refused with exit 2. Each case checks the exit code, the
# message (option, file, reason) and that nothing was left behind: no partial file, no hidden
# staging folder, no empty output folder.
#   outputs_faults.sh NSBRIDGE SOURCE_DIR
set -u
nsb=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
root=$2
tmp=$(mktemp -d)
trap 'chmod -R u+w "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAILED: $*" >&2; }
check() {  # check DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then ok; else bad "$what"; fi
}
# expect CODE PATTERN -- ARGS...: nsbridge ARGS exits CODE and prints PATTERN (extended regex)
# on stdout or stderr, never "internal error".
expect() {
  local code=$1 pattern=$2
  shift 3
  out=$("$nsb" "$@" 2>&1)
  local rc=$?
  if [[ $rc -eq $code ]] && grep -Eq -- "$pattern" <<<"$out" && ! grep -q 'internal error' <<<"$out"; then
    ok
  else
    bad "nsbridge $* -> exit $rc (expected $code, /$pattern/): $(head -3 <<<"$out")"
  fi
}
# no_leftovers DIR: no hidden staging or temporary entry anywhere under DIR.
no_leftovers() { [[ -z $(find "$1" -name '.*tmp*' -o -name '.*old*' 2>/dev/null) ]]; }

ball="$root/scenes/bouncing-ball.toml"

# 1. --out LINK, a link to an earlier run's folder: the folder it points to gets the new set,
#    the link stays a link (it used to be replaced by a new folder, the target kept stale
#    results).
expect 0 'bouncing-ball' -- run "$ball" --out "$tmp/links/real" --set solver.end_time=0.5 --quiet
ln -s real "$tmp/links/link"
expect 0 'bouncing-ball' -- run "$ball" --out "$tmp/links/link" --set solver.end_time=1 --quiet
check "--out link: the link is still a link" test -L "$tmp/links/link"
check "--out link: the target holds the new set" grep -q '"end_time": 1,' "$tmp/links/real/summary.json"
check "--out link: nothing else beside it" test "$(ls -A "$tmp/links" | tr '\n' ' ')" = "link real "
# A dangling link is followed to the place it names, which is created.
ln -s made "$tmp/links/dangling"
expect 0 'bouncing-ball' -- run "$ball" --out "$tmp/links/dangling" --set solver.end_time=0.5 --quiet
check "--out dangling link: the named folder is made" test -f "$tmp/links/made/summary.json"
check "--out dangling link: the link stays" test -L "$tmp/links/dangling"

# 2. --out . in an empty folder: the folder is written into, never replaced (it used to be
#    renamed away, leaving the shell in a deleted directory).
mkdir -p "$tmp/here/sub"
cd "$tmp/here/sub" || exit 1
inode=$(stat -c %i .)
expect 0 'bouncing-ball' -- run "$ball" --out . --quiet
check "--out .: the current directory is the same one" test "$(stat -c %i "$tmp/here/sub")" = "$inode"
check "--out .: the shell's directory still exists" test -d "$(pwd -P)"
check "--out .: it holds the set and nothing else" \
  test "$(ls -A . | tr '\n' ' ')" = "events.csv history.csv summary.json "
expect 0 'bouncing-ball' -- run "$ball" --out . --quiet --set solver.end_time=1
check "--out . twice: the second set" grep -q '"end_time": 1,' summary.json
check "--out . twice: still the same directory" test "$(stat -c %i "$tmp/here/sub")" = "$inode"
# --out .. : the folder holding the current one is written into, and keeps it.
expect 0 'bouncing-ball' -- run "$ball" --out .. --quiet
check "--out ..: the set is in the parent" test -f "$tmp/here/summary.json"
check "--out ..: the current directory is still there" test "$(stat -c %i "$tmp/here/sub")" = "$inode"
check "--out . and ..: no staging left" no_leftovers "$tmp/here"
cd "$tmp" || exit 1

# 3. Exit 2 leaves nothing: inputs refused after the scene was read (an end time whose step
#    count overflows, a subnormal step) used to leave an empty out/.
expect 2 'end_time' -- run "$ball" --set solver.end_time=1e308 --out "$tmp/e2/a" --dump-lcp "$tmp/e2/d"
expect 2 'step' -- run "$ball" --set solver.step=4.9e-324 --out "$tmp/e2/b"
check "exit 2: no output folder at all" test ! -e "$tmp/e2"
mkdir -p "$tmp/e2-default" && cd "$tmp/e2-default" || exit 1
expect 2 'end_time' -- run "$ball" --set solver.end_time=1e308
check "exit 2, default --out: no out/" test ! -e "$tmp/e2-default/out"
cd "$tmp" || exit 1

# 4. A full disk while writing the outputs (a file size limit of 4 KiB: the ball's
#    history.csv is larger). Message and exit code of an unwritable --out; no partial file; the
#    previous set stays as it was.
expect 0 'bouncing-ball' -- run "$ball" --out "$tmp/full/ball" --quiet --set solver.end_time=0.5
cp -r "$tmp/full/ball" "$tmp/full-before"
out=$(ulimit -f 4; trap '' XFSZ; "$nsb" run "$ball" --out "$tmp/full/ball" --quiet 2>&1)
rc=$?
check "full disk, run: exit 2 (got $rc: $out)" test $rc -eq 2
check "full disk, run: the message names --out, the file and the reason" \
  grep -Eq "^nsbridge: --out $tmp/full/ball: cannot write '$tmp/full/ball/history.csv': File too large" <<<"$out"
check "full disk, run: the previous set is untouched" diff -r "$tmp/full-before" "$tmp/full/ball"
check "full disk, run: no staging left" no_leftovers "$tmp/full"
out=$(ulimit -f 4; trap '' XFSZ; "$nsb" run "$ball" --out "$tmp/full/new" --quiet 2>&1)
check "full disk, new folder: exit 2 and nothing made" \
  test $? -eq 2 -a ! -e "$tmp/full/new"

# 5. --dump-lcp on a full disk: it used to leave a 0-byte .dat. Excitation 7 to 4.2 s solves
#    52 contact problems (its first contacts close at 3.96 s); with no byte allowed, the first
#    problem's file fails.
exc7=("$root/scenes/bridge-exc7.toml" --set solver.end_time=4.2 --quiet)
out=$(ulimit -f 0; trap '' XFSZ; "$nsb" run "${exc7[@]}" --out "$tmp/dump/out" --dump-lcp "$tmp/dump/lcp" 2>&1)
rc=$?
check "full disk, --dump-lcp: exit 2 (got $rc: $out)" test $rc -eq 2
check "full disk, --dump-lcp: the message names --dump-lcp, the file and the reason" \
  grep -Eq "^nsbridge: --dump-lcp $tmp/dump/lcp: cannot write '$tmp/dump/lcp/lcp-000001.dat': File too large" <<<"$out"
check "full disk, --dump-lcp: no file and no folder left" test ! -e "$tmp/dump"

# 6. A sweep on a full disk: the runs whose files fit are written, the first that does not
#    stops the sweep with the message of an unwritable --out (it used to be "internal error",
#    exit 1); every file left is complete, and the same command resumes once there is space.
mkdir -p "$tmp/sw"
cat > "$tmp/sw/design.toml" <<TOML
scene = "$ball"
mode = "grid"
[[factor]]
key = "solver.end_time"
values = [0.1, 0.2, 4.0, 0.3]
TOML
"$nsb" sweep "$tmp/sw/design.toml" --out "$tmp/sw/clean" --jobs 1 >/dev/null 2>&1
out=$(ulimit -f 20; trap '' XFSZ; "$nsb" sweep "$tmp/sw/design.toml" --out "$tmp/sw/s" --jobs 1 2>&1)
rc=$?
check "full disk, sweep: exit 2 (got $rc: $out)" test $rc -eq 2
check "full disk, sweep: the message names --out, the file and the reason" \
  grep -Eq "^nsbridge: --out $tmp/sw/s: cannot write '$tmp/sw/s/runs/[^']+/history.csv': File too large" <<<"$out"
check "full disk, sweep: no staging or temporary left" no_leftovers "$tmp/sw/s"
check "full disk, sweep: no results.csv" test ! -e "$tmp/sw/s/results.csv"
check "full disk, sweep: the first two runs are complete" \
  test "$(find "$tmp/sw/s/runs" -name summary.json | wc -l)" -eq 2
out=$("$nsb" sweep "$tmp/sw/design.toml" --out "$tmp/sw/s" --jobs 1 2>&1)
rc=$?
check "full disk, sweep resumed: exit 0 (got $rc)" test $rc -eq 0
check "full disk, sweep resumed: 2 runs already done" grep -q '2 already done' <<<"$out"
# results.csv as the clean sweep's, but for the wall times.
strip() { /usr/bin/python3 -c 'import csv,sys
r=list(csv.DictReader(open(sys.argv[1])))
print([{k:v for k,v in x.items() if "wall" not in k} for x in r])' "$1"; }
check "full disk, sweep resumed: results.csv is the clean sweep's" \
  test "$(strip "$tmp/sw/s/results.csv")" = "$(strip "$tmp/sw/clean/results.csv")"

# 7. figures on a full disk: the first run's history does not fit; the message of an
#    unwritable --out, exit 2, no partial file.
out=$(ulimit -f 8; trap '' XFSZ; timeout 120 "$nsb" figures --quick --out "$tmp/fig" --workers 1 2>&1)
rc=$?
check "full disk, figures: exit 2 (got $rc: $(tail -2 <<<"$out"))" test $rc -eq 2
check "full disk, figures: the message names --out and the reason" \
  grep -Eq "^nsbridge: --out $tmp/fig: cannot write '$tmp/fig/[^']+': File too large" <<<"$out"
check "full disk, figures: no staging or temporary left" no_leftovers "$tmp/fig"

# 8. Read-only folders. root writes through a missing write permission, so as root these cases
#    run nsbridge as the unprivileged user nobody (setpriv), on copies of the binary, the two
#    scenes and their records that nobody can read, in a folder that nobody owns.
as_user=()
ball_ro=$ball
exc7_ro=$root/scenes/bridge-exc7.toml
design_ro=$tmp/sw/design.toml
nsb_ro=$nsb
if [[ $(id -u) -eq 0 ]]; then
  if ! command -v setpriv >/dev/null; then
    echo "SKIPPED: read-only folders: running as root without setpriv to drop the privilege"
    echo "outputs faults: $passed passed, $failed failed"
    [[ $failed -eq 0 ]]
    exit
  fi
  chmod 755 "$tmp"
  src=$tmp/ro-src
  mkdir -p "$src/scenes" "$src/data/ground-motions" "$tmp/ro"
  cp "$nsb" "$src/nsbridge"
  cp "$ball" "$root/scenes/bridge-exc7.toml" "$src/scenes/"
  cp "$root"/data/ground-motions/RSN988_NORTHR_CCN{090,360}.AT2 "$src/data/ground-motions/"
  sed "s#^scene = .*#scene = \"$src/scenes/bridge-exc7.toml\"#" "$tmp/sw/design.toml" >"$src/design.toml"
  chown -R 65534:65534 "$src" "$tmp/ro"
  as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  nsb_ro=$src/nsbridge
  ball_ro=$src/scenes/bouncing-ball.toml
  exc7_ro=$src/scenes/bridge-exc7.toml
  design_ro=$src/design.toml
  echo "read-only folders: as root, nsbridge runs as nobody (setpriv)"
fi
# expect_ro CODE PATTERN -- ARGS...: expect, for nsbridge run by the unprivileged user.
expect_ro() {
  local code=$1 pattern=$2
  shift 3
  out=$("${as_user[@]}" "$nsb_ro" "$@" 2>&1)
  local rc=$?
  if [[ $rc -eq $code ]] && grep -Eq -- "$pattern" <<<"$out" && ! grep -q 'internal error' <<<"$out"; then
    ok
  else
    bad "nsbridge $* -> exit $rc (expected $code, /$pattern/): $(head -3 <<<"$out")"
  fi
}
mkdir -p "$tmp/ro/parent/old"
[[ ${#as_user[@]} -gt 0 ]] && chown -R 65534:65534 "$tmp/ro"
expect_ro 0 'bouncing-ball' -- run "$ball_ro" --out "$tmp/ro/parent/old" --quiet --set solver.end_time=0.5
chmod a-w "$tmp/ro/parent"
expect_ro 2 "^nsbridge: --out $tmp/ro/parent/new: cannot create the directory '$tmp/ro/parent/new': Permission denied" \
  -- run "$ball_ro" --out "$tmp/ro/parent/new" --quiet
expect_ro 2 "^nsbridge: --out $tmp/ro/parent/old: cannot write beside '$tmp/ro/parent/old' in '$tmp/ro/parent': Permission denied" \
  -- run "$ball_ro" --out "$tmp/ro/parent/old" --quiet
expect_ro 2 "^nsbridge: --out $tmp/ro/parent/new: cannot create the directory" \
  -- sweep "$design_ro" --out "$tmp/ro/parent/new"
chmod u+w "$tmp/ro/parent"
chmod a-w "$tmp/ro/parent/old"
expect_ro 2 "^nsbridge: --out $tmp/ro/parent/old: cannot write into '$tmp/ro/parent/old': Permission denied" \
  -- run "$ball_ro" --out "$tmp/ro/parent/old" --quiet
chmod u+w "$tmp/ro/parent/old"
# The permission lost during the run: the parent made read-only while the bridge runs.
"${as_user[@]}" "$nsb_ro" run "$exc7_ro" --set solver.end_time=10 --set solver.step=5e-6 --out "$tmp/ro/parent/old" \
  --quiet >"$tmp/ro/log" 2>&1 &
pid=$!
sleep 0.3
chmod a-w "$tmp/ro/parent"
wait $pid
rc=$?
chmod u+w "$tmp/ro/parent"
check "permission lost during the run: exit 2 (got $rc: $(cat "$tmp/ro/log"))" test $rc -eq 2
check "permission lost during the run: the message of an unwritable --out" \
  grep -Eq "^nsbridge: --out $tmp/ro/parent/old: cannot .*Permission denied" "$tmp/ro/log"
check "permission lost during the run: the previous set stays" \
  grep -q '"end_time": 0.5,' "$tmp/ro/parent/old/summary.json"
check "permission lost during the run: nothing left beside it" \
  test "$(ls -A "$tmp/ro/parent" | tr '\n' ' ')" = "old "

echo "outputs faults: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
