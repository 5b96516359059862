#!/bin/sh
# End to end over UDP: ff-sim (the unchanged firmware on a laptop) plays a
# bundled trace; `ffctl --udp` records it with a condition; `ffctl verify`
# must agree tick for tick (exit 0, default minimum coverage), and FAIL
# (exit 1) against another scene. Skipped (77) until ff-sim is built.
# Usage: ffsim_record_verify.sh FF_SIM FFCTL TRACE WORK_PREFIX
set -u
sim=$1 ffctl=$2 trace=$3 work=$4
. "$(dirname "$0")/ffsim_start.sh"
start_ffsim "$sim" "$work" --trace "$trace"
# 12 s: the trace's finger runs from 10 s to 20 s of its own clock.
"$ffctl" --udp "127.0.0.1:$port" record -o "$work.csv" --seconds 12 --scene heightmap --target top --strength 0.66 ||
  { echo "record failed"; exit 1; }
"$ffctl" verify "$work.csv" || { echo "verify: the device and the native core disagree"; exit 1; }
"$ffctl" verify "$work.csv" --scene heightmap --target bottom --strength 0.66
rc=$?
[ "$rc" -eq 1 ] || { echo "verify against another scene: exit $rc, expected 1 (FAIL)"; exit 1; }
echo "ff-sim + ffctl --udp record + verify: agree, and another scene fails"
