#!/bin/bash
# fusemapd end to end inside a fresh network namespace, so multicast never leaves loopback:
# simulate a short log, start the daemon on udpm://...?ttl=0, replay with lcm-logplayer, record
# the daemon's outputs with lcm-logger, stop the daemon with SIGTERM and check what it wrote.
# usage: netns_integration.sh FUSEMAPD FUSEMAP_SIM DAEMON_LOG_CHECK SOURCE_DIR
# Exit 77 (ctest: skipped) where network namespaces or the LCM tools are unavailable.
set -u
if [ $# -ne 4 ]; then
  echo "usage: $0 FUSEMAPD FUSEMAP_SIM DAEMON_LOG_CHECK SOURCE_DIR" >&2
  exit 2
fi
FUSEMAPD=$1 SIM=$2 CHECK=$3 SRC=$4

. "$SRC/tools/netns_lib.sh"
netns_enter 77 lcm-logplayer lcm-logger -- "$0" "$@"
URL='udpm://239.255.76.67:7667?ttl=0'

WORK=$(mktemp -d "${TMPDIR:-/tmp}/fusemapd_netns.XXXXXX")
PIDS=()
cleanup() {
  for pid in "${PIDS[@]}"; do kill "$pid" 2>/dev/null; done
  wait 2>/dev/null
  rm -rf "$WORK"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*" >&2
  [ -f "$WORK/daemon.err" ] && sed 's/^/  daemon: /' "$WORK/daemon.err" | tail -20 >&2
  exit 1
}

"$SIM" --world "$SRC/data/worlds/hall.yaml" --seconds 12 --seed 3 --no-rgbd --out "$WORK/sim" \
  >"$WORK/sim.out" 2>&1 || fail "fusemap_sim: $(tail -3 "$WORK/sim.out")"
[ -s "$WORK/sim/sim.lcm" ] || fail "no simulated log"

lcm-logger -q -f --lcm-url="$URL" -c 'FUSEMAP_.*' "$WORK/out.lcm" &
PIDS+=($!)
"$FUSEMAPD" --config "$SRC/config/daemon.yaml" --lcm-url "$URL" --out "$WORK/out" \
  >"$WORK/daemon.out" 2>"$WORK/daemon.err" &
DAEMON=$!
PIDS+=($DAEMON)
# Both subscribers must be up before the replay starts; their subscriptions are local sockets,
# so a short settle is enough (a missed first message would only lower the counts).
sleep 1
kill -0 "$DAEMON" 2>/dev/null || fail "fusemapd exited early"
lcm-logplayer --lcm-url="$URL" --speed=1.0 "$WORK/sim/sim.lcm" || fail "lcm-logplayer failed"
sleep 2  # the daemon's last health tick and submap list
kill -TERM "$DAEMON"
wait "$DAEMON"
rc=$?
[ "$rc" -eq 0 ] || fail "fusemapd exit code $rc after SIGTERM"
kill -INT "${PIDS[0]}" 2>/dev/null
wait "${PIDS[0]}" 2>/dev/null
PIDS=()

[ -s "$WORK/out/trajectory.tum" ] || fail "trajectory.tum missing or empty"
[ -s "$WORK/out/map.pgm" ] || fail "map.pgm missing"
[ -s "$WORK/out/map.yaml" ] || fail "map.yaml missing"
[ -s "$WORK/out/map.png" ] || fail "map.png missing"
summary=$("$CHECK" "$WORK/out.lcm") || fail "recorded outputs: $summary"
echo "recorded: $summary"
echo "daemon: $(head -1 "$WORK/daemon.out")"
echo "trajectory poses: $(grep -vc '^#' "$WORK/out/trajectory.tum")"
echo PASS
