#!/bin/bash
# fusemapd crash recovery inside a fresh network namespace (multicast never leaves loopback):
# while lcm-logplayer replays a simulated log, kill -9 the daemon after a few checkpoints,
# restart it with --resume, and check that the final outputs cover the whole run. Then truncate
# the checkpoint: --resume must detect it, use checkpoint.fmck.prev and say so. Last, with the
# visual loop checker on: kill -9 and --resume keep its keyframes.
# usage: kill_resume.sh FUSEMAPD FUSEMAP_SIM SOURCE_DIR
# Exit 77 (ctest: skipped) where network namespaces or the LCM tools are unavailable.
set -u
if [ $# -ne 3 ]; then
  echo "usage: $0 FUSEMAPD FUSEMAP_SIM SOURCE_DIR" >&2
  exit 2
fi
FUSEMAPD=$1 SIM=$2 SRC=$3

. "$SRC/tools/netns_lib.sh"
netns_enter 77 lcm-logplayer -- "$0" "$@"
URL='udpm://239.255.76.67:7667?ttl=0'

WORK=$(mktemp -d "${TMPDIR:-/tmp}/fusemapd_resume.XXXXXX")
PIDS=()
cleanup() {
  for pid in "${PIDS[@]}"; do kill -9 "$pid" 2>/dev/null; done
  wait 2>/dev/null
  rm -rf "$WORK"
}
trap cleanup EXIT
fail() {
  echo "FAIL: $*" >&2
  for f in "$WORK"/daemon*.err; do
    [ -f "$f" ] && sed "s|^|  $(basename "$f"): |" "$f" | tail -8 >&2
  done
  exit 1
}
# wait_for SECONDS COMMAND...: polls every 0.1 s until COMMAND succeeds.
wait_for() {
  local limit=$(( $1 * 10 )); shift
  for ((i = 0; i < limit; ++i)); do
    "$@" && return 0
    sleep 0.1
  done
  return 1
}
count_poses() { grep -vc '^#' "$1"; }
first_stamp() { grep -v '^#' "$1" | head -1 | cut -d' ' -f1; }
last_stamp() { grep -v '^#' "$1" | tail -1 | cut -d' ' -f1; }
# within A B TOLERANCE: |A - B| <= TOLERANCE
within() { awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; exit !(d <= t && -d <= t) }'; }
resumed_nodes() { sed -n 's/.*resumed from .* (\([0-9]*\) nodes.*/\1/p' "$1" | head -1; }

"$SIM" --world "$SRC/data/worlds/hall.yaml" --seconds 24 --seed 5 --no-rgbd --out "$WORK/sim" \
  >"$WORK/sim.out" 2>&1 || fail "fusemap_sim: $(tail -3 "$WORK/sim.out")"
# Checkpoints every 2 s instead of 60 s: the daemon profile with one value changed.
sed 's/^\(  checkpoint_period_s:\).*/\1 2.0/' "$SRC/config/daemon.yaml" >"$WORK/config.yaml"
grep -q '^  checkpoint_period_s: 2.0$' "$WORK/config.yaml" || fail "could not set checkpoint_period_s"
CKPT="$WORK/out/checkpoint.fmck"

"$FUSEMAPD" --config "$WORK/config.yaml" --lcm-url "$URL" --out "$WORK/out" \
  >"$WORK/daemon1.out" 2>"$WORK/daemon1.err" &
FIRST=$!
PIDS+=($FIRST)
sleep 1  # the subscription is a local socket; see netns_integration.sh
# FUSEMAP_PLAYBACK_SPEED < 1 for sanitized builds (tools/run_sanitizers.sh), whose daemon is
# several times slower than real time: at speed 1 its queue overflows and the first scans are
# dropped, which is the overflow policy working, not what this test checks.
lcm-logplayer --lcm-url="$URL" --speed="${FUSEMAP_PLAYBACK_SPEED:-1.0}" "$WORK/sim/sim.lcm" &
PLAYER=$!
PIDS+=($PLAYER)
# Two checkpoints written (the second rotated the first to .prev), then 10 s into the log.
wait_for 30 test -s "$CKPT.prev" || fail "no second checkpoint within 30 s"
wait_for 30 bash -c "[ \$(grep -c 'checkpoint .*nodes' '$WORK/daemon1.err') -ge 4 ]" ||
  fail "fewer than 4 checkpoints"
kill -9 "$FIRST"
wait "$FIRST" 2>/dev/null
echo "killed after: $(grep 'checkpoint .*nodes' "$WORK/daemon1.err" | tail -1)"

"$FUSEMAPD" --config "$WORK/config.yaml" --lcm-url "$URL" --out "$WORK/out" --resume \
  >"$WORK/daemon2.out" 2>"$WORK/daemon2.err" &
SECOND=$!
PIDS+=($SECOND)
wait_for 10 grep -q "resumed from" "$WORK/daemon2.err" || fail "second daemon did not resume"
N_RESUMED=$(resumed_nodes "$WORK/daemon2.err")
echo "resumed with $N_RESUMED nodes"
wait "$PLAYER" || fail "lcm-logplayer failed"
sleep 2  # the queued scans
kill -TERM "$SECOND"
wait "$SECOND"
rc=$?
[ "$rc" -eq 0 ] || fail "resumed fusemapd exit code $rc after SIGTERM"
PIDS=()

TRAJ="$WORK/out/trajectory.tum" NODES="$WORK/out/nodes.tum" GT="$WORK/sim/groundtruth.tum"
[ -s "$TRAJ" ] && [ -s "$NODES" ] && [ -s "$WORK/out/map.pgm" ] || fail "outputs missing"
n_final=$(count_poses "$NODES")
[ "$n_final" -gt $((N_RESUMED + 20)) ] || fail "only $n_final nodes after resuming with $N_RESUMED"
# The whole run: from the log's first scans to its last (the kill gap is inside).
within "$(first_stamp "$TRAJ")" "$(first_stamp "$GT")" 1.0 ||
  fail "trajectory starts at $(first_stamp "$TRAJ"), the log at $(first_stamp "$GT")"
within "$(last_stamp "$TRAJ")" "$(last_stamp "$GT")" 1.0 ||
  fail "trajectory ends at $(last_stamp "$TRAJ"), the log at $(last_stamp "$GT")"
echo "whole run: $n_final nodes, trajectory $(first_stamp "$TRAJ")..$(last_stamp "$TRAJ")" \
  "($(count_poses "$TRAJ") poses), log $(first_stamp "$GT")..$(last_stamp "$GT")"

# A truncated checkpoint: detected, the previous one used and reported, the bad one set aside.
n_prev_expected=$(grep 'checkpoint .*nodes' "$WORK/daemon2.err" | tail -2 | head -1 |
                  sed -n 's/.*: \([0-9]*\) nodes.*/\1/p')
truncate -s $(( $(stat -c %s "$CKPT") / 2 )) "$CKPT"
"$FUSEMAPD" --config "$WORK/config.yaml" --lcm-url "$URL" --out "$WORK/out3" --resume \
  >"$WORK/daemon3.out" 2>"$WORK/daemon3.err"
rc=$?
[ "$rc" -eq 3 ] || fail "--resume without a checkpoint in the folder: exit $rc, expected 3"
mkdir -p "$WORK/out3"
cp "$CKPT" "$CKPT.prev" "$WORK/out3/"
"$FUSEMAPD" --config "$WORK/config.yaml" --lcm-url "$URL" --out "$WORK/out3" --resume \
  >"$WORK/daemon3.out" 2>"$WORK/daemon3.err" &
THIRD=$!
PIDS+=($THIRD)
wait_for 10 grep -q "resumed from" "$WORK/daemon3.err" || fail "third daemon did not resume"
kill -TERM "$THIRD"
wait "$THIRD"
rc=$?
PIDS=()
[ "$rc" -eq 0 ] || fail "fusemapd --resume from .prev: exit code $rc"
grep -q "using the previous checkpoint .*checkpoint.fmck.prev" "$WORK/daemon3.err" ||
  fail "fallback to .prev not reported"
[ -f "$WORK/out3/checkpoint.fmck.rejected" ] || fail "rejected checkpoint not set aside"
n_prev=$(resumed_nodes "$WORK/daemon3.err")
[ "$n_prev" = "$n_prev_expected" ] || fail "resumed $n_prev nodes from .prev, expected $n_prev_expected"
[ "$(count_poses "$WORK/out3/nodes.tum")" -eq "$n_prev" ] || fail "nodes.tum after .prev resume"
echo "truncated checkpoint: $(grep 'previous checkpoint' "$WORK/daemon3.err" | head -1)"

# The visual loop checker's keyframes survive kill -9 too: a short log with RGB-D replayed in
# real time from a file (no multicast needed), the checker on and the cloud off.
"$SIM" --world "$SRC/data/worlds/hall.yaml" --seconds 16 --seed 5 --rgbd-rate 5 \
  --out "$WORK/simv" >"$WORK/simv.out" 2>&1 || fail "fusemap_sim (RGB-D): $(tail -3 "$WORK/simv.out")"
sed '/^cloud:/{n;s/^  enabled: true/  enabled: false/}' "$WORK/config.yaml" >"$WORK/visual.yaml"
printf 'visual_loop:\n  enabled: true\n' >>"$WORK/visual.yaml"
VURL="file://$WORK/simv/sim.lcm?speed=${FUSEMAP_PLAYBACK_SPEED:-1.0}"
KF="$WORK/outv/visual_keyframes.fmvk"
"$FUSEMAPD" --config "$WORK/visual.yaml" --lcm-url "$VURL" --out "$WORK/outv" \
  >"$WORK/daemonv1.out" 2>"$WORK/daemonv1.err" &
FOURTH=$!
PIDS+=($FOURTH)
wait_for 30 test -s "$KF" || fail "no visual keyframes file within 30 s"
wait_for 30 bash -c "[ \$(grep -c 'checkpoint .*nodes' '$WORK/daemonv1.err') -ge 3 ]" ||
  fail "fewer than 3 checkpoints with the visual checker on"
kill -9 "$FOURTH"
wait "$FOURTH" 2>/dev/null
"$FUSEMAPD" --config "$WORK/visual.yaml" --lcm-url "$VURL" --out "$WORK/outv" --resume \
  >"$WORK/daemonv2.out" 2>"$WORK/daemonv2.err" &
FIFTH=$!
PIDS+=($FIFTH)
wait "$FIFTH"
rc=$?
PIDS=()
[ "$rc" -eq 0 ] || fail "resumed fusemapd with the visual checker: exit code $rc"
kept=$(sed -n 's/.*resumed \([0-9]*\) of \([0-9]*\) visual keyframes.*/\1/p' "$WORK/daemonv2.err")
[ -n "$kept" ] && [ "$kept" -gt 0 ] || fail "no visual keyframes resumed"
[ -s "$WORK/outv/loops.tsv" ] || fail "no loops.tsv"
echo "visual: $(grep 'visual keyframes' "$WORK/daemonv2.err" | head -1)"
echo PASS
