#!/bin/sh
# Regenerates the generated traces in this folder with ff-tracegen.
# usage: test/traces/generate.sh path/to/ff-tracegen
# The same seeds and options give the same files (see README.md).
set -eu
gen=${1:?usage: generate.sh path/to/ff-tracegen}
cd "$(dirname "$0")"
"$gen" -q --strategy along  --duration 10 --seed 1 --noise low                        -o gen_along_low.csv
"$gen" -q --strategy across --duration 10 --seed 2 --noise high --quantise px         -o gen_across_high_px.csv
"$gen" -q --strategy mixed  --duration 8  --seed 3 --noise low  --quantise zforce --rests 2 --lifts 1 -o gen_mixed_zforce_rests.csv
"$gen" -q --strategy mixed  --duration 8  --seed 4 --noise low  --all-faults --events -o gen_all_faults.csv
"$gen" -q --strategy along  --duration 5  --seed 5 --noise low  --wrap --events       -o gen_clock_wrap.csv
