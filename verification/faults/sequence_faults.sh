#!/bin/bash
# Fault injection on earthquake sequences ([[model.excitation.sequence]], docs/scenes.md and
# docs/ground-motions.md, "Sequences"): an empty sequence, a negative rest (in the file and as
# an override), the single-record keys beside a sequence, a shared key in an entry and an entry
# without a record. Each case checks exit 2, the message (file, line and key path) and that
# nothing was written.
#   sequence_faults.sh NSBRIDGE SOURCE_DIR
set -u
nsb=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
root=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
passed=0
failed=0
ok() { passed=$((passed + 1)); }
bad() { failed=$((failed + 1)); echo "FAILED: $*" >&2; }
# expect SCENE PATTERN [ARGS...]: `nsbridge run SCENE --out out ARGS` exits 2, prints PATTERN
# (extended regex), never "internal error", and leaves no output folder.
expect() {
  local scene=$1 pattern=$2
  shift 2
  out=$("$nsb" run "$scene" --out "$tmp/out" --quiet "$@" 2>&1)
  local rc=$?
  if [[ $rc -eq 2 ]] && grep -Eq -- "$pattern" <<<"$out" && ! grep -q 'internal error' <<<"$out" &&
     [[ ! -e $tmp/out ]] && [[ -z $(find "$tmp" -name '.*' -newer "$tmp/mark" 2>/dev/null) ]]; then
    ok
  else
    bad "$scene $* -> exit $rc (expected 2, /$pattern/): $(head -3 <<<"$out")"
  fi
}
touch "$tmp/mark"
rec="$root/data/ground-motions/RSN988_NORTHR_CCN360.AT2"
bridge='[model]
kind = "bridge"
[[model.bents]]
position = -8.0
height = 2.0
[[model.bents]]
position = 8.0
height = 2.0
[model.excitation]'
entry="[[model.excitation.sequence]]
transverse_record = \"$rec\"
rest = 1.0"

printf '%s\nsequence = []\n' "$bridge" > empty.toml
expect empty.toml 'empty\.toml:10:[0-9]+: model\.excitation\.sequence: is empty'

printf '%s\n%s\n%s\n' "$bridge" "$entry" "${entry/rest = 1.0/rest = -1.0}" > negative.toml
expect negative.toml 'negative\.toml:15:[0-9]+: model\.excitation\.sequence\[1\]\.rest'
printf '%s\n%s\n%s\n' "$bridge" "$entry" "$entry" > good.toml
expect good.toml 'model\.excitation\.sequence\[0\]\.rest \(override\)' --set model.excitation.sequence.0.rest=-2

printf '%s\ntarget_pga = 0.5\n%s\n' "$bridge" "$entry" > mixed.toml
expect mixed.toml 'mixed\.toml:10:[0-9]+: model\.excitation\.target_pga: .*not both'

printf '%s\n%s\ntime_scale = 0.5\n' "$bridge" "$entry" > shared.toml
expect shared.toml 'shared\.toml:13:[0-9]+: model\.excitation\.sequence\[0\]\.time_scale: is shared'

printf '%s\n[[model.excitation.sequence]]\nrest = 1.0\n' "$bridge" > none.toml
expect none.toml 'none\.toml.*model\.excitation\.sequence\[0\].*names no record'

echo "sequence faults: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
