#!/bin/sh
# Regenerates the generated traces in this folder with ff-tracegen, then the
# golden replays of golden.txt with the same build's tests.
# usage: test/traces/generate.sh path/to/build/tools/tracegen/ff-tracegen
# The same seeds and options give the same files (see README.md). The golden
# replays are change detectors (their own output, stored): regenerate them
# only after an intended change, and look at what moved.
set -eu
gen=${1:?usage: generate.sh path/to/ff-tracegen}
gen=$(cd "$(dirname "$gen")" && pwd)/$(basename "$gen")
build=$(dirname "$(dirname "$(dirname "$gen")")")
cd "$(dirname "$0")"
"$gen" -q --strategy along  --duration 10 --seed 1 --noise low                        -o gen_along_low.csv
"$gen" -q --strategy across --duration 10 --seed 2 --noise high --quantise px         -o gen_across_high_px.csv
"$gen" -q --strategy mixed  --duration 8  --seed 3 --noise low  --quantise zforce --rests 2 --lifts 1 -o gen_mixed_zforce_rests.csv
"$gen" -q --strategy mixed  --duration 8  --seed 4 --noise low  --all-faults --events -o gen_all_faults.csv
"$gen" -q --strategy along  --duration 5  --seed 5 --noise low  --wrap --events       -o gen_clock_wrap.csv
FF_UPDATE_GOLDEN=1 ctest --test-dir "$build" -R GoldenReplay >/dev/null
echo "regenerated the traces and the golden replays (git diff shows what moved)"
