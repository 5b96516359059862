# Sourced by the ff-sim end-to-end scripts: start_ffsim FF_SIM WORK_PREFIX [ff-sim options]
# starts ff-sim on free ports of its own choosing (two scripts at once never
# collide), waits for its ready line (10 s at most), sets $port to its
# protocol port and stops ff-sim when the script exits. Skips (77) without ff-sim.
start_ffsim() {
  sim=$1 log=$2.sim.log
  shift 2
  [ -x "$sim" ] || { echo "no $sim: skipped"; exit 77; }
  # Emptied here: the background job's own redirection may come after the first
  # grep below, which would then read the last run's ready line and port.
  : >"$log"
  "$sim" --port 0 --finger-port 0 --quiet "$@" >"$log" 2>&1 &
  sim_pid=$!
  # On the way out: stop ff-sim, and show its log if the script failed.
  trap 'rc=$?; kill "$sim_pid" 2>/dev/null; [ "$rc" -eq 0 ] || { echo "ff-sim log:"; cat "$log"; }' EXIT
  i=0
  until grep -q "ff-sim ready" "$log"; do
    i=$((i + 1))
    [ "$i" -gt 100 ] && { echo "ff-sim did not say ready within 10 s:"; cat "$log"; exit 1; }
    sleep 0.1
  done
  port=$(sed -n 's/^ff-sim ready port=\([0-9]*\) .*/\1/p' "$log")
  [ -n "$port" ] || { echo "no port in ff-sim's ready line:"; cat "$log"; exit 1; }
}
