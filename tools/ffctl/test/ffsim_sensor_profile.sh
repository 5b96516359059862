#!/bin/sh
# End to end over UDP: `ffctl --udp sensor-profile` sends a profile to ff-sim
# (the unchanged firmware on a laptop), which acknowledges it; --show and
# status read it back; a recording keeps it and verify replays with it.
# Skipped (77) until ff-sim is built.
# Usage: ffsim_sensor_profile.sh FF_SIM FFCTL TRACE WORK_PREFIX
set -u
sim=$1 ffctl=$2 trace=$3 work=$4
. "$(dirname "$0")/ffsim_start.sh"
# Four times faster than the wall clock: the trace's finger (10 s to 20 s of its clock) comes sooner.
start_ffsim "$sim" "$work" --trace "$trace" --speed 4
dev="--udp 127.0.0.1:$port"
flags="--white-noise-px 1.5 --correlated-noise-px 0.5 --correlation-time-ms 250 --tremor-px 0.25 --tremor-hz 9.5 --report-rate-hz 180 --jitter-us 400 --latency-us 3000"
words="white noise 1.5 px, wander 0.5 px over 250 ms, tremor 0.25 px at 9.5 Hz, 180 reports/s +- 400 us, latency 3000 us"
expect() {  # expect WHAT FILE: FILE must contain the line fragment WHAT
  grep -qF -- "$1" "$2" || { echo "expected \"$1\" in:"; cat "$2"; exit 1; }
}

"$ffctl" $dev sensor-profile --show >"$work.show0" || { echo "sensor-profile --show failed"; exit 1; }
expect "white noise 1 px, wander 0 px over 0 ms, tremor 0 px, 200 reports/s +- 150 us, latency 0 us" "$work.show0"
# shellcheck disable=SC2086
"$ffctl" $dev sensor-profile $flags >"$work.set" || { echo "sensor-profile: exit $?"; cat "$work.set"; exit 1; }
expect "the device's tracker uses: $words" "$work.set"
expect "ffctl sensor-profile $flags" "$work.set"
"$ffctl" $dev sensor-profile --show >"$work.show1" || exit 1
expect "$words" "$work.show1"
"$ffctl" $dev status >"$work.status" || { echo "status failed"; exit 1; }
expect "sensor profile: $words" "$work.status"
"$ffctl" $dev sensor-profile --correlated-noise-px 2 >/dev/null 2>&1
rc=$?
[ "$rc" -eq 2 ] || { echo "a wander without its time: exit $rc, expected 2"; exit 1; }

"$ffctl" $dev record -o "$work.csv" --seconds 12 --scene heightmap --target top --strength 0.66 ||
  { echo "record failed"; exit 1; }
expect "ffctl sensor-profile $flags" "$work.sensor-profile"
"$ffctl" verify "$work.csv" >"$work.verify" || { echo "verify failed:"; cat "$work.verify"; exit 1; }
expect "sensor profile ($work.sensor-profile): $words" "$work.verify"
expect "PASS" "$work.verify"
echo "ff-sim + ffctl --udp sensor-profile: acknowledged, read back, kept by a recording, verified with it"
