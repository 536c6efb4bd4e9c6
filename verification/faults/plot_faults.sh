#!/usr/bin/env bash
# Fault class: bad run folders given to `nsbridge plot`. Each case asserts exit 2, a message
# naming the file (and line) or the option, and that no picture and no temporary is left.
# usage: plot_faults.sh NSBRIDGE
set -u
nsb=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

# A small valid run folder: one deck, one contact.
good() {
  mkdir -p "$1"
  printf 't,x,y,theta,vx,vy,omega,gN1,lambdaN1,lambdaT1,energy_error\n0,0,0,0,0,0,0,0.01,0,0,0\n0.1,0.001,0,0,0,0,0,0.009,0,0,1e-9\n' > "$1/history.csv"
  printf 't,contact,kind,note\n0.05,1,impact,\n' > "$1/events.csv"
  printf '{"scene": "tiny", "method": "moreau", "status": "completed", "contacts": [{"contact": 1, "family": "abutment", "name": "left +W/2"}]}\n' > "$1/summary.json"
}

# case_ NAME PATTERN RUN_DIR [ARGS...]: nsbridge plot RUN_DIR ARGS (with --out $tmp/out/fig.svg
# unless ARGS name one) exits 2 with PATTERN in its message and leaves $tmp/out empty.
case_() {
  local name=$1 pattern=$2 dir=$3
  shift 3
  rm -rf "$tmp/out"; mkdir -p "$tmp/out"
  local out rc
  local args=("$@")
  [[ " $* " == *" --out "* ]] || args+=(--out "$tmp/out/fig.svg")
  out=$(timeout -s KILL 30 "$nsb" plot "$dir" "${args[@]}" 2>&1)
  rc=$?
  if [[ $rc -eq 2 ]] && grep -Eq -- "$pattern" <<<"$out" && [[ -z "$(ls -A "$tmp/out")" ]] &&
     ! grep -q 'internal error' <<<"$out"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAILED: $name: exit $rc, left: $(ls -A "$tmp/out"), output: $out" >&2
  fi
}

case_ "missing folder" "$tmp/absent: no such run folder" "$tmp/absent"
mkdir -p "$tmp/empty"
case_ "no history.csv" "empty/history.csv: not found" "$tmp/empty"
good "$tmp/rows"; printf '0.2,1,2\n' >> "$tmp/rows/history.csv"
case_ "a short row" "rows/history.csv:4: 3 fields, expected 11" "$tmp/rows"
good "$tmp/text"; sed -i '3s/0.001/abc/' "$tmp/text/history.csv"
case_ "a field that is no number" "text/history.csv:3: column x: 'abc' is not a number" "$tmp/text"
good "$tmp/header"; sed -i '1s/^t,/time,/' "$tmp/header/history.csv"
case_ "a header without t" "header/history.csv:1: expected a header starting with t" "$tmp/header"
good "$tmp/nosamples"; sed -i '2,$d' "$tmp/nosamples/history.csv"
case_ "no samples" "nosamples/history.csv: no samples" "$tmp/nosamples"
good "$tmp/binary"; head -c 300 /dev/urandom > "$tmp/binary/history.csv"
case_ "binary history" "binary/history.csv:" "$tmp/binary"
good "$tmp/json"; printf '{"scene": "tiny", "method": ' > "$tmp/json/summary.json"
case_ "a cut summary.json" "json/summary.json: not a summary.json .*: unexpected end" "$tmp/json"
good "$tmp/nosummary"; rm "$tmp/nosummary/summary.json"
case_ "no summary.json" "nosummary/summary.json: not found" "$tmp/nosummary"
good "$tmp/nomethod"; printf '{"scene": "tiny"}\n' > "$tmp/nomethod/summary.json"
case_ "no method" "nomethod/summary.json: method: missing" "$tmp/nomethod"
good "$tmp/ok"
case_ "an unknown --what" "--what: .*not in" "$tmp/ok" --what hysteresis
case_ "an unsupported extension" "--out .*fig.jpg: unsupported extension '.jpg'" "$tmp/ok" --out "$tmp/out/fig.jpg"
case_ "no bent columns" 'ok/history.csv: no bent columns .*groups = \["bents"\]' "$tmp/ok" --what bents
good "$tmp/noevents"; rm "$tmp/noevents/events.csv"
case_ "no events.csv" "noevents/events.csv: not found" "$tmp/noevents" --what events
good "$tmp/badevents"; printf '0.1,one,impact,\n' >> "$tmp/badevents/events.csv"
case_ "a garbled events.csv" "badevents/events.csv:3: contact: not a contact number" "$tmp/badevents" --what events
case_ "an --out folder that does not exist" "--out .*nowhere/fig.svg: no such folder" "$tmp/ok" --out "$tmp/out/nowhere/fig.svg"
# The run folder itself is untouched by every case.
check_clean() { [[ -z "$(find "$tmp" -name '.*tmp*' -o -name '*.gp' -o -name '*.log' -o -name '*.svg')" ]]; }
if check_clean; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAILED: files left" >&2; fi

echo "plot_faults: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
