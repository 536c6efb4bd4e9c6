#!/usr/bin/env bash
# Fault injection for nsbridge records import (docs/ground-motions.md, "Importing a record
# library"; docs/cli.md, "What each fault gets"): each broken library is refused with exit 2,
# a message naming the file, line and column (or the station), and nothing is left behind:
# no suite folder, no staging folder.
# Usage: records_import_faults.sh NSBRIDGE SOURCE_DIR
set -u
nsb=$(realpath "$1")
data=$(cd "$2" && pwd)/sweep/test/data/records-import
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }

# case NAME KIND EDIT PATTERN: a fresh copy of the KIND fixture, EDIT run inside it, then the
# import must exit 2 with PATTERN in its message and write nothing.
case_() {
  local name=$1 kind=$2 edit=$3 pattern=$4
  rm -rf lib out ./.out.tmp* && cp -r "$data/$kind" lib
  (cd lib && eval "$edit")
  msg=$("$nsb" records import lib --out out 2>&1)
  rc=$?
  [ $rc = 2 ] || fail "$name: exit $rc, expected 2: $msg"
  echo "$msg" | grep -q -- "$pattern" || fail "$name: message '$msg' lacks '$pattern'"
  [ ! -e out ] || fail "$name: out/ was written"
  [ -z "$(ls -A | grep -v '^lib$')" ] || fail "$name: left behind: $(ls -A)"
  echo "ok  $name"
}

case_ "missing AT2" peer 'rm RSN202_SYN_B180.AT2' \
  "_SearchResults.csv:9: RSN 202: column Horizontal-1 Acc. Filename: no such file .*RSN202_SYN_B180.AT2"
case_ "broken AT2" peer 'sed -i "5s/3.9600000E-03/3.96x/" RSN101_SYN_A000.AT2' \
  "_SearchResults.csv:8: RSN 101: .*RSN101_SYN_A000.AT2:5: non-numeric token '3.96x'"
case_ "no table" peer 'sed -i "7d" _SearchResults.csv' \
  "_SearchResults.csv: no table of records"
case_ "missing column" peer 'sed -i "7s/ Scale Factor,/ Factor,/" _SearchResults.csv' \
  "_SearchResults.csv:7: no column \"Scale Factor\""
case_ "RSN twice" peer 'sed -i "9s/^ 2, 202,/ 2, 101,/" _SearchResults.csv' \
  "_SearchResults.csv:9: RSN 101 appears twice"
case_ "short row" peer 'sed -i "8s/, RSN101_SYN_A-UP.AT2$//" _SearchResults.csv' \
  "_SearchResults.csv:8: 17 fields, the header has 18"
case_ "one horizontal" peer 'sed -i "9s/RSN202_SYN_B270.AT2/---/" _SearchResults.csv' \
  "_SearchResults.csv:9: RSN 202: column Horizontal-2 Acc. Filename is empty"
case_ "COSMOS header" cosmos 'sed -i "1s/(Format v01.20 with 13 text lines)/(no format)/" SYN02_000.V2' \
  "SYN02_000.V2:1: not a COSMOS v1.20 channel"
case_ "COSMOS real header" cosmos 'sed -i "25s/Real-header/Real/" SYN01.V2c' \
  "SYN01.V2c:25: expected \"<n> Real-header values"
case_ "COSMOS dt" cosmos 'sed -i "36s/    10.000000/     0.000000/" SYN01.V2c' \
  "SYN01.V2c:25: real parameter 62 (sampling interval, ms) is 0"
case_ "COSMOS truncated" cosmos 'sed -i "50,\$d" SYN02_090.V2' \
  "SYN02_090.V2:50: the file ends before the acceleration values"
case_ "COSMOS raw counts" cosmos 'sed -i "15s/^       2/       0/" SYN01.V2c' \
  "SYN01.V2c:14: integer parameter 1 (processing stage) is 0"
case_ "COSMOS lone channel" cosmos 'rm SYN02_090.V2' \
  "station 'NP00125', start '1999-09-21T17:47': 1 horizontal channels"
case_ "empty folder" cosmos 'rm ./*' "lib: holds neither _SearchResults.csv (a PEER search) nor COSMOS files"
echo "records import faults: all refused"
