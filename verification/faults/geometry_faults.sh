#!/bin/bash
# Fault injection on the deck's plan (docs/bridge.md, "Faces with their own angles", "Curved
# decks"): a radius that cannot hold the deck (no more than half its width, an arc of 180
# degrees or more, an arc R phi too short for its bents), subtending almost nothing,
# angle_deg without radius or beside length, a curved deck with a skew, with an abutment's
# own angle or with a connector, and an end angle out of range. Each case
# checks exit 2, the message (file, line and key path) and that nothing was written.
#   geometry_faults.sh NSBRIDGE
set -u
nsb=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
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
  rm -rf "$tmp/out"  # a case that wrongly ran must not fail the next ones
}
touch "$tmp/mark"
bridge() {  # bridge DECK_LINES [MORE]: a curved or straight one-deck bridge on two bents
  printf '[model]\nkind = "bridge"\n[model.deck]\nmass = 140.5\nwidth = 2.44\n%s\n' "$1"
  printf '[[model.bents]]\nposition = -5.0\nheight = 2.0\n[[model.bents]]\nposition = 5.0\nheight = 2.0\n'
  printf '[solver]\nend_time = 0.01\n%s\n' "${2:-}"
}

bridge $'radius = 1.0\nangle_deg = 30.0' > narrow.toml
expect narrow.toml 'narrow\.toml:[0-9]+:[0-9]+: model\.deck\.radius: must exceed half the width'
bridge $'radius = 10.0\nlength = 40.0\ninertia = 13090.0' > wide.toml
expect wide.toml 'wide\.toml:[0-9]+:[0-9]+: model\.deck\.radius: R = 10 m cannot hold an arc of L = 40 m: it would subtend 229\.183 deg, 180 or more \(L / R >= pi\); R > L / pi = 12\.7324 m'
# R = 2 m at 30 degrees: an arc of 1.0472 m, whose ends at -+0.5236 m do not reach the bents
# at -+5 m: the radius is named, with the radius that holds them, 2 * 5 / (pi / 6) = 19.0986 m.
bridge $'radius = 2.0\nangle_deg = 30.0' > short.toml
expect short.toml 'short\.toml:[0-9]+:[0-9]+: model\.deck\.radius: R = 2 m subtending angle_deg = 30 gives an arc of 1\.0472 m, its ends at -\+0\.523599 m from its middle: it cannot hold \[\[model\.bents\]\] 0 at position = -5 m, which needs R >= 2 \|position\| / phi = 19\.0986 m'
bridge $'radius = 1.0e6\nlength = 33.5\ninertia = 13090.0' > flat.toml
expect flat.toml 'flat\.toml:[0-9]+:[0-9]+: model\.deck\.radius: gives a subtended angle'
bridge $'angle_deg = 30.0\nlength = 33.5' > noradius.toml
expect noradius.toml 'noradius\.toml:[0-9]+:[0-9]+: model\.deck\.angle_deg: needs radius'
bridge $'radius = 64.0\nangle_deg = 30.0\nlength = 33.5' > both.toml
expect both.toml 'both\.toml:[0-9]+:[0-9]+: model\.deck\.angle_deg: give either length'
bridge $'radius = 64.0\nangle_deg = 30.0\nskew_deg = 10.0' > skewed.toml
expect skewed.toml 'skewed\.toml:[0-9]+:[0-9]+: model\.deck\.skew_deg: must be 0'
bridge $'radius = 64.0\nangle_deg = 30.0' $'[model.abutments]\nskew_left_deg = 10.0' > abut.toml
expect abut.toml 'abut\.toml:[0-9]+:[0-9]+: model\.abutments\.skew_left_deg: a curved deck'
bridge $'radius = 64.0\nangle_deg = 30.0' $'[[model.bearings]]\nposition = 0.0\nstiffness = 1000.0' > bearing.toml
expect bearing.toml 'bearing\.toml:[0-9]+:[0-9]+: model\.deck\.radius: a curved deck takes bents and seats only'
bridge $'length = 33.5\ninertia = 13090.0' $'[model.abutments]\nskew_right_deg = 85.0' > steep.toml
expect steep.toml 'steep\.toml:[0-9]+:[0-9]+: model\.abutments\.skew_right_deg'

echo "geometry faults: $passed passed, $failed failed"
[[ $failed -eq 0 && $passed -eq 10 ]]
