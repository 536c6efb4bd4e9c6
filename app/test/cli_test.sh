#!/usr/bin/env bash
# End-to-end tests of the nsbridge command line: exit codes (0 success, 1 not solved or
# stopped early, 2 bad input), error messages that name the file, line or key, and output
# files that are complete or absent.
#   bash app/test/cli_test.sh NSBRIDGE
set -uo pipefail
source "$(dirname "$0")/cli_lib.sh" "$1"

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
# eta of each end (docs/criterion.md, "Unequal end angles and curved decks"), by hand.
# Straight deck W = 2, L = 10, left face at 0, right face at 45 deg, mu = 0.5: the centroid
# lies at (W^2 (tan^2 45 - 0) / (24 L), W^2 (tan 45 - 0) / (12 L)) = (1/60, 1/30) from the axis's
# midpoint. Right end: corners (6, 1) and (4, -1) from the midpoint, so M = (5 - 1/60, -1/30),
# h = (1, 1), n = (-1, 1)/sqrt2, t = (-1, -1)/sqrt2, h x d = h x n = sqrt2 and
# eta(k) = (M x (n + k t)) / sqrt2 = (297 - 301 k) / 120: eta+ = eta(-0.5) = 447.5/120 = 3.72917,
# eta- = eta(0.5) = 146.5/120 = 1.22083. Left end: corners (-5, -+1), M = (-5 - 1/60, -1/30),
# h = (0, 1), n = (1, 0), t = (0, 1), h x d = -1, eta(k) = (301 k - 2) / 60:
# eta+ = -152.5/60 = -2.54167, eta- = 148.5/60 = 2.475.
expect 0 'left end \(face at 0 deg\): eta\+ = -2\.54167, eta- = 2\.475, rotation predicted \(max \|eta\+-\| > 1\): yes' \
  -- criterion --width 2 --length 10 --friction 0.5 --skew-left 0 --skew-right 45
expect 0 'right end \(face at 45 deg\): eta\+ = 3\.72917, eta- = 1\.22083' \
  -- criterion --width 2 --length 10 --friction 0.5 --skew-left 0 --skew-right 45
# Curved deck R = 40 m, W = 8 m, phi = 60 deg (L = R phi = 41.8879 m), mu = 0.3: the sector's
# centroid radius rbar = 4 sin 30 (44^3 - 36^3) / (3 (pi/3) (44^2 - 36^2)) = 120.4/pi
# = 38.32451 m; at the right end (psi = 30 deg) M x n = R - rbar cos psi, M x t = -rbar sin psi,
# h x n = W/2, so eta(k) = (R - rbar cos psi - k rbar sin psi) / (W/2):
# eta+ = (40 - 33.18999 + 0.3 * 19.16226) / 4 = 3.13967, eta- = 0.265331; the left end mirrors
# it (eta+ and eta- exchanged).
expect 0 '"ends": \[\{"end": "left", "angle_deg": -30(\.0*[0-9])?, "eta_plus": 0\.26533[0-9]*, "eta_minus": 3\.13966[0-9]*, "rotation": true\}, \{"end": "right", "angle_deg": 30(\.0*[0-9])?, "eta_plus": 3\.13966[0-9]*, "eta_minus": 0\.26533[0-9]*, "rotation": true\}\]' \
  -- criterion --width 8 --length 41.88790204786391 --radius 40 --friction 0.3 --json
# The shipped curved scene, subtending 30 deg (radial ends at -+15 deg), at its seats' mu = 0.5:
# eta+- = 9.07, -4.35 at the right end (docs/curved.md's sweep at 30 deg).
expect 0 'right end \(face at 15 deg\): eta\+ = 9\.0705, eta- = -4\.35395' -- criterion --scene "$root/scenes/bridge-curved-three-span.toml"
expect 2 'criterion: --radius: must exceed half the width' -- criterion --width 8 --length 10 --radius 3 --friction 0
expect 2 'criterion: --skew with --scene' -- criterion --scene "$root/scenes/bridge-curved-three-span.toml" --skew 10
expect 2 'bridge-two-frame\.toml.*no deck of one body' -- criterion --scene "$root/scenes/bridge-two-frame.toml"
expect 2 'criterion: --skew is required' -- criterion --width 10 --length 30 --friction 0.5

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

# --- robustness: no input hangs, crashes or fools the command line -----------------------
# The lcp reader refuses what is not a regular file (it used to read a FIFO or /dev/urandom
# forever) ...
mkfifo "$tmp/fifo"
expect 2 'fifo: not a regular file' -- lcp "$tmp/fifo"
expect 2 '/dev/urandom: not a regular file' -- lcp /dev/urandom
# ... and allocates nothing before the header's n is known to fit in the file (it used to
# end in "internal error: std::bad_alloc").
printf '1000000000 0 1000000000 1000000000 1000000000 1000000000\n' > "$tmp/big.dat"
expect 2 'big\.dat:1: n = 1000000000; expected a size <= 32768' -- lcp "$tmp/big.dat"
printf '30000 0 30000 30000 30000 30000\n1 2 3\n' > "$tmp/short-n.dat"
expect 2 'short-n\.dat:1: n = 30000 needs at least 1800060000 bytes for M and q, but the file has 38' \
  -- lcp "$tmp/short-n.dat"
# Subnormal numbers are numbers (they used to give "internal error: stod", with half a JSON
# object already printed); numbers beyond the range of a double are refused by name.
printf '2\n0\n2\n2\n2 2\n1 1e-310\n0 1\n-1 -4.9e-324\n' > "$tmp/subnormal.dat"
expect 0 'status: +solved' -- lcp "$tmp/subnormal.dat"
expect 0 '^\{"file": .*"w": \[0, 9\.9999999999995e-311\]\}$' -- lcp "$tmp/subnormal.dat" --json
expect 0 'status: +solved' -- lcp "$lcp/lcp_trivial.dat" --tol 4.9e-324
printf '2\n0\n2\n2\n2 2\n1 0\n0 1\n-1 1e400\n' > "$tmp/overflow.dat"
expect 2 "overflow\.dat:8: q\(2\) is '1e400'; expected a finite number" -- lcp "$tmp/overflow.dat" --json
check "a refused .dat file prints nothing on standard output" \
  test -z "$("$nsb" lcp "$tmp/overflow.dat" --json 2>/dev/null)"
expect 2 'tol' -- lcp "$lcp/lcp_trivial.dat" --tol abc
expect 2 'max-iter' -- lcp "$lcp/lcp_trivial.dat" --max-iter 1e99
# An override index too large for any integer is out of range like any other (it used to give
# "internal error: stoul").
expect 2 'bridge-exc7\.toml: override "model\.bents\.99999999999999999999\.height=1": model\.bents\.99999999999999999999: index out of range; model\.bents has 3 elements' \
  -- run "$root/scenes/bridge-exc7.toml" --out "$tmp/x" --set 'model.bents.99999999999999999999.height=1'
expect 2 'model\.bents\.3: index out of range; model\.bents has 3 elements' \
  -- run "$root/scenes/bridge-exc7.toml" --out "$tmp/x" --set 'model.bents.3.height=1'
# Criterion results that are not finite are refused (they used to print -nan and inf, exit 0).
expect 2 'criterion: --width 1e-300 and --length 1e\+300 \(W/L = 0, mu = 0\.5\) make eta non-finite' \
  -- criterion --skew 0 --width 1e-300 --length 1e300 --friction 0.5 --json
expect 2 'criterion: --width 5e-324 and --length 1 .*make eta non-finite' \
  -- criterion --skew 0 --width 4.9e-324 --length 1 --friction 0.5 --json
check "a refused criterion prints nothing on standard output" \
  test -z "$("$nsb" criterion --skew 0 --width 1e-300 --length 1e300 --friction 0.5 --json 2>/dev/null)"
expect 0 '"friction": 5e-324' -- criterion --skew 0 --width 2.44 --length 33.35 --friction 4.9e-324 --json
expect 2 'skew' -- criterion --skew nan --width 1 --length 1 --friction 0
expect 2 'width' -- criterion --skew 0 --width 1e400 --length 1 --friction 0
# --out "" is bad input, and an --out that cannot be created is found before the run: the
# 22 s bridge at 1e-5 s steps takes longer than the limit, so only a check made before the
# integration can answer in time (it used to integrate first).
pushd "$tmp" >/dev/null
expect 2 '^nsbridge: --out: empty path; expected a directory' -- \
  run "$root/scenes/bouncing-ball.toml" --out ""
popd >/dev/null
check "--out \"\" writes nothing" test ! -e "$tmp/out"
: > "$tmp/a-file"
limit=5
expect 2 "^nsbridge: --out $tmp/a-file/sub: cannot create the directory '$tmp/a-file/sub': Not a directory" \
  -- run "$root/scenes/bridge-exc7.toml" --set solver.step=1e-5 --out "$tmp/a-file/sub"
# --dump-lcp: a folder that cannot be made is refused before the run, as --out is; "" too.
expect 2 "^nsbridge: --dump-lcp $tmp/a-file/sub: cannot create the directory '$tmp/a-file/sub': Not a directory" \
  -- run "$root/scenes/bridge-exc7.toml" --set solver.step=1e-5 --out "$tmp/d" --dump-lcp "$tmp/a-file/sub"
expect 2 '^nsbridge: --dump-lcp: empty path' -- run "$root/scenes/bouncing-ball.toml" --out "$tmp/d" --dump-lcp ""
# One .dat file per contact problem, listed in manifest.csv; `nsbridge lcp` reads each.
expect 0 'impact-oscillator' -- run "$root/scenes/impact-oscillator.toml" --out "$tmp/io" \
  --method event_driven --dump-lcp "$tmp/io-lcp"
check "the manifest lists the 4 impacts" test "$(grep -c ',impact,' "$tmp/io-lcp/manifest.csv")" = 4
expect 0 'status: +solved' -- lcp "$tmp/io-lcp/lcp-000001.dat"
limit=20
# Outputs are replaced as a set: a directory that held an older set holds the new one, and
# nothing else is left beside it; a directory with the user's own files keeps them.
expect 0 'bouncing-ball' -- run "$root/scenes/bouncing-ball.toml" --out "$tmp/set/ball" --set solver.end_time=0.5
expect 0 'bouncing-ball' -- run "$root/scenes/bouncing-ball.toml" --out "$tmp/set/ball" --set solver.end_time=1
check "the second run's set replaced the first" grep -q '"end_time": 1,' "$tmp/set/ball/summary.json"
check "no temporary directory is left beside the outputs" test "$(ls -A "$tmp/set")" = ball
echo mine > "$tmp/set/ball/notes.txt"
expect 0 'bouncing-ball' -- run "$root/scenes/bouncing-ball.toml" --out "$tmp/set/ball" --set solver.end_time=0.5
check "the user's own file is kept" grep -q mine "$tmp/set/ball/notes.txt"
check "and the set is the new one" grep -q '"end_time": 0.5,' "$tmp/set/ball/summary.json"
# A run interrupted by SIGKILL leaves the previous set as it was.
cp -r "$tmp/set/ball" "$tmp/before"
(timeout -s KILL 0.3 "$nsb" run "$root/scenes/bridge-exc7.toml" --set solver.step=1e-5 \
  --out "$tmp/set/ball" >/dev/null 2>&1) 2>/dev/null
check "a killed run leaves the previous set untouched" diff -r "$tmp/before" "$tmp/set/ball"
# Runs that must not be trusted say so (it used to print "0 warnings" and exit 0 for an
# energy error of 38 % and 4.7 cm of penetration), in summary.json too; --strict exits 1.
# These cases were found on excitation 7 with the Sylmar record and the 33.35 m deck; they run
# on that input set (the Sylmar scene with the earlier deck length and bent positions) so that
# the figures below stay those of the report.
sylmar7=("$root/scenes/bridge-exc7-sylmar.toml" --set model.deck.length=33.35
         --set model.bents.0.position=-8.34 --set model.bents.2.position=8.34)
exc7=("${sylmar7[@]}" --set solver.step=0.1 --out "$tmp/exc7")
expect 0 'warnings   8 ' -- run "${exc7[@]}"
# (The run that was reported had an energy error of 38 % and 4.7 cm of penetration; with the
# seat velocity taken at t_k+1 the same run has 11 % and 1.9 cm, still far outside the bounds.)
expect 0 'warning: energy_balance: error [1-9][0-9.]* % of the largest energy term; the method is trusted up to 1 %' -- run "${exc7[@]}"
expect 0 'warning: penetration: contact [1-4] penetrates 0\.0[1-9][0-9]* m at t = ' -- run "${exc7[@]}"
expect 0 'warning: step_record: solver\.step = 0\.1 s is longer than the record.s sampling interval 0\.0025 s' -- run "${exc7[@]}"
expect 0 'warning: step_period: solver\.step = 0\.1 s resolves the shortest natural period' -- run "${exc7[@]}"
expect 0 'warning: accuracy: the peak \|theta\| 0\.00283 has an estimated error of ' -- run "${exc7[@]}"
for w in accuracy energy_balance penetration step_period step_record; do
  check "summary.json records the $w warning" grep -q "\"$w: " "$tmp/exc7/summary.json"
done
expect 1 'strict: 8 warning\(s\): the run is not to be trusted' -- run "${exc7[@]}" --strict
# The record's sampling interval is its AT2 DT = 0.005 s times time_scale = 0.5.
expect 0 'step_record: .* 0\.0025 s' -- run "${sylmar7[@]}" --set solver.step=0.003 \
  --set solver.end_time=0.3 --out "$tmp/x"
expect 0 'warnings   0$' -- run "${sylmar7[@]}" --set solver.step=0.002 \
  --set solver.end_time=0.3 --out "$tmp/x"
# A step equal to the interval (0.005 s at time_scale 1; the record's times i DT carry round-off
# below DT) is not longer than it.
check "a step equal to the record's sampling interval does not warn step_record" \
  bash -c '! "$0" run "$@" 2>&1 | grep -q step_record' "$nsb" \
  "$root/scenes/bridge-exc7-sylmar.toml" --set solver.step=0.005 --set solver.end_time=0.3 \
  --set model.excitation.time_scale=1.0 --out "$tmp/x"
# Outcomes of the integration (docs/run-api.md): a run whose contact problems were all solved,
# some by the fallback chain, succeeds (exit 0); a run that cannot go on is exit 1 with its
# status and time, and nothing prints "nan". The wedged deck (both gaps closed) left 651 of
# 80000 problems unsolved by Lemke alone; in 2 s the chain is needed 3 times.
expect 0 'status     completed_with_fallbacks' -- run "$root/scenes/bridge-exc7.toml" \
  --set model.gaps.left=0 --set model.gaps.right=0 --set solver.end_time=2 --out "$tmp/x"
expect 1 'status     stalled at t = 0 s' -- run "$root/scenes/bouncing-ball.toml" \
  --set model.gravity=1e40 --method event_driven --out "$tmp/x"
expect 1 'status     stalled at t = 0 s' -- run "$root/scenes/bouncing-ball.toml" \
  --set model.gravity=1e100 --method compliance --out "$tmp/x"
check "a stalled run prints no nan" bash -c \
  "! '$nsb' run '$root/scenes/bouncing-ball.toml' --set model.gravity=1e100 --method compliance --out '$tmp/x' 2>&1 | grep -qi nan"
# g = 1e308 is no scene value: a number is at most 1e100 in magnitude (docs/scenes.md).
expect 2 'bouncing-ball\.toml: model\.gravity \(override\): must be at most 1e\+100 in magnitude' \
  -- run "$root/scenes/bouncing-ball.toml" --set model.gravity=1e308 --out "$tmp/x"
# Shortest period of the impact oscillator (m = 1 t, k = 1 kN/m): T = 2 pi sqrt(m/k) = 6.28 s,
# so 20 steps per period need h <= 0.314 s.
expect 0 'step_period: solver\.step = 0\.5 s resolves the shortest natural period 6\.28 s with 12\.6 steps; the method needs >= 20 \(solver\.step <= 0\.314 s\)' \
  -- run "$root/scenes/impact-oscillator.toml" --set solver.step=0.5 --out "$tmp/x"
check "h = 0.3 s resolves T = 6.28 s by 20.9 steps: no step_period warning" bash -c \
  "! '$nsb' run '$root/scenes/impact-oscillator.toml' --set solver.step=0.3 --out '$tmp/x' 2>&1 | grep -q step_period"
# --cross-check (docs/error-estimates.md, "Cross-checks"): the compliance method at 1e-4 of its
# contact stiffness lets excitation 7's deck rotate 27 % more than Moreau-Jean in the first
# 4.5 s; the warning names both peaks, exit 0, and 1 under --strict. An unknown method: exit 2.
soft=("$root/scenes/bridge-exc7.toml" --method compliance --set solver.end_time=4.5
      --set solver.stiffness_factor=1e-4 --cross-check moreau --out "$tmp/cross")
expect 0 'warning: cross_check: the peak \|theta\| is 0\.00171 under compliance and 0\.00134 under moreau' \
  -- run "${soft[@]}"
check "summary.json records the cross-check" grep -q '"cross_check": {"method": "moreau"' \
  "$tmp/cross/summary.json"
expect 1 'strict: 4 warning\(s\)' -- run "${soft[@]}" --strict
expect 2 'cross-check' -- run "$root/scenes/bridge-exc7.toml" --cross-check rk4 --out "$tmp/x"
# Every shipped scene, with its own settings, is trusted.
for s in bouncing-ball impact-oscillator sliding-block rigid-deck-skew rigid-deck-straight bridge-exc7; do
  expect 0 'warnings   0$' -- run "$root/scenes/$s.toml" --out "$tmp/x" --strict
done
# Values that overflow the computation are bad input (it used to "complete" with null energies):
# beyond 1e100 a scene number is refused at its key.
expect 2 'bouncing-ball\.toml: model\.velocity \(override\): must be at most 1e\+100 in magnitude' \
  -- run "$root/scenes/bouncing-ball.toml" --set model.velocity=1e160 --out "$tmp/x"
# Record files: only regular files, every bad number named with its file and line.
mkdir -p "$tmp/rec/ground-motions"
cp "$root/data/ground-motions/RSN1084_NORTHR_SCS052.AT2" "$tmp/rec/ground-motions/"
sed 's#ground-motions/RSN1084_NORTHR_SCS142.AT2#ground-motions/fifo.AT2#' \
  "$root/scenes/bridge-exc7-sylmar.toml" > "$tmp/rec/fifo.toml"
mkfifo "$tmp/rec/ground-motions/fifo.AT2"
expect 2 'fifo\.toml:[0-9]+:[0-9]+: model\.excitation\.transverse_record: record file "ground-motions/fifo\.AT2" not found' \
  -- run "$tmp/rec/fifo.toml" --out "$tmp/x"
{ head -n 4 "$root/data/ground-motions/RSN1084_NORTHR_SCS142.AT2"; echo "0.1 1e-400 0.2"; } \
  > "$tmp/rec/ground-motions/under.AT2"
sed 's#ground-motions/RSN1084_NORTHR_SCS142.AT2#ground-motions/under.AT2#' \
  "$root/scenes/bridge-exc7-sylmar.toml" > "$tmp/rec/under.toml"
expect 2 "under\.AT2:5: value '1e-400' is outside the range of a double" -- run "$tmp/rec/under.toml" --out "$tmp/x"
{ head -n 3 "$root/data/ground-motions/RSN1084_NORTHR_SCS142.AT2";
  echo "NPTS= 999999999, DT= 0.01 SEC"; echo "0.1 0.2"; } > "$tmp/rec/ground-motions/npts.AT2"
sed 's#ground-motions/RSN1084_NORTHR_SCS142.AT2#ground-motions/npts.AT2#' \
  "$root/scenes/bridge-exc7-sylmar.toml" > "$tmp/rec/npts.toml"
expect 2 'npts\.AT2:5: NPTS = 999999999 \(line 4\) but 2 values found' -- run "$tmp/rec/npts.toml" --out "$tmp/x"
expect 2 'scene file' -- run /dev/null --out "$tmp/x"

# --- nsbridge --version, --quiet and the progress bar --------------------------------------
expect 0 '^nsbridge [0-9]+\.[0-9]+\.[0-9]+' -- --version
for key in 'revision   [0-9a-f]{12}(-dirty)? \(git, at build time\)' 'build      ' \
           'compiler   (gcc|clang) ' 'Eigen      3\.' 'Boost      1\.' 'GSL        2\.' \
           'toml\+\+     3\.' 'CLI11      2\.'; do
  expect 0 "$key" -- --version
done
if command -v git >/dev/null && git -C "$root" rev-parse HEAD >/dev/null 2>&1; then
  check "--version names the checked-out revision" \
    grep -q "revision   $(git -C "$root" rev-parse --short=12 HEAD)" <<<"$("$nsb" --version)"
fi
# Long enough for the bar, which appears after 1 s: 1.1e7 steps, about 3.5 s at the measured
# 0.3 µs per step (docs/benchmarks/moreau.md), so that a faster machine still shows it.
slow=("${sylmar7[@]}" --set solver.step=2e-6 --out "$tmp/slow")
"$nsb" run "${slow[@]}" 2>"$tmp/stderr.txt" >/dev/null
check "no progress bar when standard error is not a terminal" test ! -s "$tmp/stderr.txt"
if command -v script >/dev/null; then
  script -qec "'$nsb' run ${slow[*]}" /dev/null > "$tmp/tty.txt" 2>&1
  check "a progress bar on a terminal: time reached, speed and time left" \
    grep -Eq 't = [0-9.]+ / 22 s .* x real time .* s left' "$tmp/tty.txt"
  script -qec "'$nsb' run ${slow[*]} --quiet" /dev/null > "$tmp/tty-quiet.txt" 2>&1
  check "--quiet silences it" bash -c "! grep -q 'real time .* left' '$tmp/tty-quiet.txt'"
fi

# --- scaling to a spectral acceleration (docs/bridge.md, "Target spectral accelerations") ---
expect 0 'status     completed' -- run "$root/scenes/bridge-exc5.toml" --set model.excitation.scale_to=sa \
  --set model.excitation.target_sa=0.5 --out "$tmp/sa" --quiet
check "summary.json reports input.transverse.sa_g = 0.5" \
  grep -Eq '"input": \{"transverse": \{"pga_g": [0-9.e+-]+, "sa_g": 0\.5, "sa_period": 0\.354[0-9]*, "sa_damping": 0\.05, "scale_factor": [0-9.e+-]+\}, "longitudinal": \{"pga_g": 1, ' \
  "$tmp/sa/summary.json"
expect 2 'bridge-exc5\.toml: model\.excitation\.target_sa \(override\): must be in \[0, 20\] \[g\] \(got -1\)' -- run \
  "$root/scenes/bridge-exc5.toml" --set model.excitation.scale_to=sa --set model.excitation.target_sa=-1

# The suite's spectra scaled to one PSA: every record passes through it, the mean too.
expect 0 '20 records scaled to PSA\(0\.5 s\) = 0\.8 g' -- suite-spectra \
  "$root/data/ground-motions/asce7-suite/records.csv" --period 0.5 --sa 0.8 --out "$tmp/suite"
check "suite-spectra.csv: at T = 0.5 s every record and the mean are 0.8 g" \
  awk -F, '$1 == "0.5" { for (k = 2; k <= 22; ++k) if ($k < 0.8 - 1e-12 || $k > 0.8 + 1e-12) exit 1; found = 1 } END { exit !found }' \
  "$tmp/suite/suite-spectra.csv"
expect 2 'give either --scene' -- suite-spectra "$root/data/ground-motions/asce7-suite/records.csv" --out "$tmp/suite"

# --- bounded messages and the scene file itself ---------------------------------------------
expect 2 '^--jobs: Value -1 not in range 0 to 2147483647$' -- sweep "$root/scenes/sweeps/limit-states.toml" --out "$tmp/j" --jobs -1
mkfifo "$tmp/scene.fifo"
expect 2 'scene\.fifo: cannot open scene file \(not a regular file\)' -- run "$tmp/scene.fifo" --out "$tmp/x"
# A run's work is bounded before it starts, at the key (docs/scenes.md, "The work of a run").
expect 2 'bridge-exc7\.toml: solver\.end_time \(override\): end_time 1e\+99 s with output\.sample_dt 0\.005 s gives 2e\+101 history rows' \
  -- run "$root/scenes/bridge-exc7.toml" --method event_driven --set solver.end_time=1e99 --out "$tmp/x"
expect 2 'bridge-exc7\.toml: solver\.end_time \(override\): must be at most 1e\+100 in magnitude' \
  -- run "$root/scenes/bridge-exc7.toml" --method event_driven --set solver.end_time=1e308 --out "$tmp/x"
expect 2 'bridge-exc7\.toml: output\.sample_dt \(override\): is subnormal' \
  -- run "$root/scenes/bridge-exc7.toml" --set output.sample_dt=1e-310 --out "$tmp/x"

echo "cli: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
