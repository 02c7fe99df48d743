#!/bin/bash
# fusemapd benchmark (issue 6). Run from anywhere:
#   tools/bench_daemon.sh BUILD_DIR [REALTIME_SECONDS=60] [LONG_SECONDS=3600] [THREADS=1]
# 1. Real time, 40 Hz laser: fusemap_sim --laser-rate 40 --no-rgbd, played by lcm-logplayer at
#    speed 1 over loopback multicast inside a private network namespace (unshare -n; nothing
#    leaves the machine). Reports the daemon's scan->pose latency (median, p99, over its last
#    2000 scans, from its health line) and its CPU use (utime+stime from /proc over the replay).
# 2. Long run: one 62.5 s lap of the simulated robot (it returns to its start) repeated to
#    LONG_SECONDS as a looping log player would send it (stamps jump back every lap; the daemon
#    re-bases them, daemon.time_reset_threshold_s), replayed with file://...?speed=0 (as fast
#    as possible). Reports resident memory and graph size every 5 minutes of simulated time.
set -u
# shellcheck source=help_lib.sh
source "$(dirname "$0")/help_lib.sh"
if [ $# -lt 1 ] || [ "$1" = "--help" ]; then
  help_from_header "$0"
  exit 2
fi
BUILD=$(realpath "$1") RT_S=${2:-60} LONG_S=${3:-3600} THREADS=${4:-1}
SRC=$(realpath "$(dirname "$0")/..")
FUSEMAPD=$BUILD/tools/fusemapd/fusemapd SIM=$BUILD/tools/sim/fusemap_sim
for f in "$FUSEMAPD" "$SIM"; do [ -x "$f" ] || { echo "missing $f (build it)" >&2; exit 2; }; done

. "$SRC/tools/netns_lib.sh"
netns_enter 1 lcm-logplayer -- "$0" "$@"
URL='udpm://239.255.76.67:7667?ttl=0'
WORK=$(mktemp -d "${TMPDIR:-/tmp}/bench_daemon.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
ticks() { awk '{ print $14 + $15 }' "/proc/$1/stat"; }

echo "== 1. real time, 40 Hz laser, ${RT_S} s, --threads $THREADS"
"$SIM" --world "$SRC/data/worlds/hall.yaml" --seconds "$RT_S" --laser-rate 40 --no-rgbd \
  --seed 1 --out "$WORK/rt" 2>/dev/null | tail -1
"$FUSEMAPD" --config "$SRC/config/daemon.yaml" --lcm-url "$URL" --out "$WORK/rt_out" --threads "$THREADS" \
  >"$WORK/rt.out" 2>"$WORK/rt.err" &
DAEMON=$!
sleep 1
t0=$(date +%s.%N) c0=$(ticks $DAEMON)
lcm-logplayer --lcm-url="$URL" --speed=1.0 "$WORK/rt/sim.lcm" >/dev/null
sleep 1.5  # the last scans and a health tick
t1=$(date +%s.%N) c1=$(ticks $DAEMON)
kill -TERM $DAEMON
wait $DAEMON
awk -v c="$((c1 - c0))" -v hz="$(getconf CLK_TCK)" -v t0="$t0" -v t1="$t1" \
  'BEGIN { printf "CPU: %.1f%% of one core (%.1f s CPU over %.1f s wall)\n",
           100 * c / hz / (t1 - t0), c / hz, t1 - t0 }'
grep '^fusemapd: t=' "$WORK/rt.err" | tail -1 |
  sed 's/.*\(nodes=[0-9]*\).*\(LIDAR=[^ ]*\).*\(latency_p50=[^ ]*\) \(p99=[^ ]*\) \(rss=[^ ]*\).*/\1 \2 (rx\/drop\/bad\/queue) \3 \4 \5/'
# Global SLAM's backlog: loop-closure searches queued, at most over the health lines (1 Hz).
grep '^fusemapd: t=' "$WORK/rt.err" | grep -o 'pending_searches=[0-9]*' | cut -d= -f2 |
  sort -n | tail -1 | sed 's/^/pending_searches max over health lines: /'

echo "== 2. looped lap to ${LONG_S} s of simulated time, file:// at full speed"
"$SIM" --world "$SRC/data/worlds/hall.yaml" --seconds 62.5 --no-rgbd --seed 2 \
  --out "$WORK/lap" 2>/dev/null | tail -1
laps=$(awk -v s="$LONG_S" 'BEGIN { print int((s + 62.49) / 62.5) }')
[ "$LONG_S" -gt 0 ] || exit 0
for ((i = 0; i < laps; ++i)); do cat "$WORK/lap/sim.lcm"; done >"$WORK/looped.lcm"
rm -f "$WORK/lap/sim.lcm"
start=$(date +%s)
/usr/bin/time -f "wall %e s, CPU %U+%S s, peak RSS %M kB" \
  "$FUSEMAPD" --config "$SRC/config/daemon.yaml" --lcm-url "file://$WORK/looped.lcm?speed=0" \
  --out "$WORK/long_out" >"$WORK/long.out" 2>"$WORK/long.err"
echo "fusemapd exit $?, $(($(date +%s) - start)) s for $laps laps"
grep -E '^wall|checkpoints:' "$WORK/long.err" "$WORK/long.out" | sed 's/^[^:]*://'
grep '^fusemapd: t=' "$WORK/long.err" | awk -v every=300 '
  { split($2, a, "="); t = a[2]; if (t0 == "") t0 = t
    for (i = 3; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] }
    m = int((t - t0) / every)
    if (v["pending_searches"] + 0 > max_pending) max_pending = v["pending_searches"] + 0
    if (m > last) { last = m; printf "sim %5.0f min: rss %s nodes %s submaps %s time_resets %s pending_searches %s\n",
                    (t - t0) / 60, v["rss"], v["nodes"], v["submaps"], v["time_resets"],
                    v["pending_searches"] }
    # Least-squares slope of RSS over simulated time once the hall is mapped (after 15 min).
    if (t - t0 >= 900) { h = (t - t0) / 3600; r = v["rss"] + 0; n++; sx += h; sy += r
                         sxx += h * h; sxy += h * r } }
  END { printf "sim %5.0f min (end): rss %s nodes %s submaps %s time_resets %s\n",
        (t - t0) / 60, v["rss"], v["nodes"], v["submaps"], v["time_resets"]
        printf "pending_searches max over health lines: %d\n", max_pending
        if (n > 2 && n * sxx - sx * sx > 0)
          printf "rss trend from 15 min on: %+.1f MB per hour of operation (%d health samples)\n",
                 (n * sxy - sx * sy) / (n * sxx - sx * sx), n }'
grep -v '^fusemapd: t=' "$WORK/long.err" | grep -v checkpoint | tail -3
