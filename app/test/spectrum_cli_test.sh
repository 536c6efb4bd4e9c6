#!/usr/bin/env bash
# End-to-end tests of `nsbridge spectrum`: the table, --json and --csv layouts, the plot,
# exit code 2 with a message naming the argument for bad input, and no file left behind
# when the input is refused.
#   bash app/test/spectrum_cli_test.sh NSBRIDGE
set -uo pipefail
source "$(dirname "$0")/cli_lib.sh" "$1"

elc=$root/data/ground-motions/elCentro_NS_1940_Peknold.AT2
rsn6=$root/data/ground-motions/RSN6_IMPVALL.I_I-ELC180.AT2

# The table: Chopra §6.4's El Centro system T = 1 s, zeta = 2 %: D = 5.97 in = 0.1516 m,
# A = 0.610 g (docs/spectra.md).
expect 0 'PSA \[g\]' -- spectrum "$elc"
expect 0 ' 1 +0\.610[0-9]* +0\.1516' -- spectrum "$elc" --periods 0.5,1,2 --damping 0.02
# T = 0 is PGA: 0.319 g for this record.
expect 0 '^ +0 +0\.318' -- spectrum "$elc" --periods 0,1
check "the default grid has the 105 NGA-West2 periods" \
  test "$("$nsb" spectrum "$elc" | grep -cE '^ +[0-9.e+-]+ +[0-9.e+-]+ +[0-9.e+-]+ +[0-9.e+-]+$')" -eq 105

# --json: one object per record with the documented keys.
"$nsb" spectrum "$elc" "$rsn6" --periods 0.1:10:7 --json > "$tmp/out.json"
check "--json prints one line per record" test "$(wc -l < "$tmp/out.json")" -eq 2
check "--json keys" grep -q '^{"record": ".*elCentro.*", "damping": 0.05, "periods": \[0.1, .*, 10\], "psa_g": \[.*\], "sd_m": \[.*\], "psv_m_s": \[.*\]}$' "$tmp/out.json"
if command -v python3 >/dev/null; then
  check "--json is valid JSON with 7 periods each" python3 -c "
import json, sys
for line in open(sys.argv[1]):
    o = json.loads(line)
    assert len(o['periods']) == len(o['psa_g']) == len(o['sd_m']) == len(o['psv_m_s']) == 7
" "$tmp/out.json"
fi

# --csv: a header, then one row per record and period.
expect 0 'PSA' -- spectrum "$elc" "$rsn6" --periods 0,0.5,1 --csv "$tmp/s.csv"
check "--csv header" test "$(head -1 "$tmp/s.csv")" = "record,period,psa_g,sd_m,psv_m_s"
check "--csv has 2 x 3 rows" test "$(wc -l < "$tmp/s.csv")" -eq 7
check "--csv rows name their record" test "$(grep -c 'RSN6_IMPVALL' "$tmp/s.csv")" -eq 3

# A two-column record in units of 0.5 m/s^2 read with --unit 0.5 gives the spectrum of the
# same record in m/s^2, bit for bit (doubling and halving are exact).
awk 'NR > 4 { for (i = 1; i <= NF; ++i) printf "%.4f %.17g\n", (n++) * 0.02, $i * 9.81 }' "$elc" \
  > "$tmp/elc-m.txt"
awk '{ printf "%s %.17g\n", $1, $2 * 2 }' "$tmp/elc-m.txt" > "$tmp/elc-half.txt"
a=$("$nsb" spectrum "$tmp/elc-m.txt" --periods 0.2,1 --json | sed 's/"record": "[^"]*"//')
b=$("$nsb" spectrum "$tmp/elc-half.txt" --periods 0.2,1 --unit 0.5 --json |
    sed 's/"record": "[^"]*"//')
check "--unit scales a two-column record" test "$a" = "$b"

# --plot: PNG and SVG by extension, no temporary file left.
if command -v gnuplot >/dev/null; then
  mkdir -p "$tmp/plots"
  expect 0 'PSA' -- spectrum "$elc" "$rsn6" --plot "$tmp/plots/s.png" --csv "$tmp/plots/s.csv"
  check "--plot writes a PNG" bash -c "file '$tmp/plots/s.png' | grep -q PNG"
  expect 0 'PSA' -- spectrum "$elc" --plot "$tmp/plots/s.svg"
  check "--plot writes an SVG" grep -q '<svg' "$tmp/plots/s.svg"
  check "no temporary file is left behind" \
    test "$(ls -A "$tmp/plots" | sort | tr '\n' ' ')" = "s.csv s.png s.svg "
fi

# No gnuplot on the PATH: exit 1, a message, and neither the plot nor the CSV.
mkdir -p "$tmp/nognu"
PATH=/nonexistent "$nsb" spectrum "$elc" --plot "$tmp/nognu/s.png" --csv "$tmp/nognu/s.csv" \
  > /dev/null 2> "$tmp/nognu.err"
check "without gnuplot: exit 1" test $? -eq 1
check "without gnuplot: the message names --plot" grep -q 'plot .*gnuplot failed' "$tmp/nognu.err"
check "without gnuplot: no file written" test -z "$(ls -A "$tmp/nognu")"

# Bad input: exit 2, the argument named, no output file.
expect 2 'missing\.AT2.*does not exist' -- spectrum "$tmp/missing.AT2"
expect 2 'damping' -- spectrum "$elc" --damping 1
expect 2 'damping' -- spectrum "$elc" --damping -0.01
expect 2 'damping' -- spectrum "$elc" --damping nan
expect 2 "periods '1,-2': '-2'" -- spectrum "$elc" --periods 1,-2
expect 2 "periods '1,,2'" -- spectrum "$elc" --periods 1,,2
expect 2 "periods 'inf'" -- spectrum "$elc" --periods inf
expect 2 "periods '1:0\.5:3'" -- spectrum "$elc" --periods 1:0.5:3
expect 2 "periods '0\.1:1:1'" -- spectrum "$elc" --periods 0.1:1:1
expect 2 "periods '0\.1:1:2\.5'" -- spectrum "$elc" --periods 0.1:1:2.5
expect 2 "periods 'a:b'" -- spectrum "$elc" --periods a:b
expect 2 'unit' -- spectrum "$elc" --unit 0
expect 2 'plot .*\.jpg.*png' -- spectrum "$elc" --plot "$tmp/s.jpg"
expect 2 'csv .*no-such-dir' -- spectrum "$elc" --csv "$tmp/no-such-dir/s.csv"
printf 't,a\n0,0\n0.01,nan\n0.02,0\n' > "$tmp/nan.csv"
expect 2 'nan\.csv:3' -- spectrum "$tmp/nan.csv"
expect 2 'missing\.AT2' -- spectrum "$elc" "$tmp/missing.AT2" --csv "$tmp/refused.csv" \
  --plot "$tmp/refused.png"
check "a refused input writes no file" test -z "$(ls -A "$tmp" | grep refused)"
expect 2 'records|required' -- spectrum

echo "spectrum cli: $passed passed, $failed failed"
[[ $failed -eq 0 ]]
