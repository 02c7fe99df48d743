#!/usr/bin/env bash
# fusemapd's pose latency with the ORB visual loop checker off and on (issue 17: "pose latency
# unchanged, p99 within 10 % of checker off"). For each world, same seed as
# tools/bench_vloop_sim.sh: simulate two laps with RGB-D at 2 Hz, then replay the log in real
# time (file://...?speed=1: no multicast) through fusemapd with config/daemon.yaml (cloud off, so
# that only the checker differs), checker off and on alternated ROUNDS times, and print each
# run's scan->pose latency (p50, p99 over the daemon's last 2,000 scans, from its last health
# line), then per world the median p99 on over off. Runs alternate so that a change in the
# machine's load falls on both; read the ratio, not the absolute figures.
# Usage: tools/bench_vloop_daemon.sh [BUILD_DIR [OUT_DIR [ROUNDS [THREADS]]]]
#        (defaults build, out/bench_vloop_daemon, 2, 2); FUSEMAP_BENCH_WORLDS ("corridor rooms ring ring_rooms").
# Exit codes: 0 all runs done, 1 a run failed (its stderr is in OUT_DIR), 2 usage or missing build.
set -euo pipefail
# shellcheck source=help_lib.sh
source "$(dirname "$0")/help_lib.sh"
if [[ ${1:-} == --help || ${1:-} == -h ]]; then
  help_from_header "$0"
  exit 0
fi
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-out/bench_vloop_daemon}
rounds=${3:-2}
threads=${4:-2}
worlds=${FUSEMAP_BENCH_WORLDS:-corridor rooms ring ring_rooms}
sim=$build/tools/sim/fusemap_sim
daemon=$build/tools/fusemapd/fusemapd
for tool in "$sim" "$daemon"; do
  [[ -x $tool ]] || { echo "bench_vloop_daemon: $tool missing: build it first" >&2; exit 2; }
done
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "bench_vloop_daemon: ROUNDS must be >= 1" >&2; exit 2; }
mkdir -p "$out"
out=$(realpath "$out")

# config/daemon.yaml with the cloud off; "on" adds the checker.
awk '/^cloud:/ { in_cloud = 1 } in_cloud && /^  enabled:/ { print "  enabled: false"; in_cloud = 0; next }
     { print }' config/daemon.yaml > "$out/off.yaml"
{ cat "$out/off.yaml"; printf 'visual_loop:\n  enabled: true\n'; } > "$out/on.yaml"

# value KEY FILE: the value of KEY=value on the file's last health line.
# "-" where the line has no such key (the checker's counts when it is off).
value() {
  local v
  v=$(grep '^fusemapd: t=' "$2" | tail -1 | grep -oE "(^| )$1=[^ ]*" | cut -d= -f2 || true)
  echo "${v:--}"
}

# median V...: the median of the numbers given.
median() {
  printf '%s\n' "$@" | sort -g |
    awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}

summary=()
for world in $worlds; do
  log=$out/$world/sim.lcm
  echo "== $world: simulating (seed 1, RGB-D 2 Hz)" >&2
  "$sim" --world "data/worlds/$world.yaml" --to-end --seed 1 \
    --rgbd-rate 2 --threads "$threads" --out "$out/$world" 2>/dev/null | tail -1 >&2
  p99s_off=() p99s_on=()
  for round in $(seq 1 "$rounds"); do
    for mode in off on; do
      run=$out/$world/${mode}_$round
      rm -rf "$run"
      if ! "$daemon" --config "$out/$mode.yaml" --lcm-url "file://$log?speed=1" --out "$run" \
          --threads "$threads" > "$run.out" 2> "$run.err"; then
        echo "bench_vloop_daemon: fusemapd failed on $world ($mode, round $round): $run.err" >&2
        exit 1
      fi
      p50=$(value latency_p50 "$run.err") p99=$(value p99 "$run.err")
      printf '%-9s %-3s round %d  latency p50 %-7s p99 %-7s keyframes %s dropped frames %s LIDAR %s  load %s\n' \
        "$world" "$mode" "$round" "$p50" "$p99" "$(value visual_keyframes "$run.err")" \
        "$(value visual_dropped "$run.err")" "$(value LIDAR "$run.err")" \
        "$(cut -d' ' -f1 /proc/loadavg)"
      if [[ $mode == off ]]; then p99s_off+=("${p99%ms}"); else p99s_on+=("${p99%ms}"); fi
    done
  done
  off=$(median "${p99s_off[@]}") on=$(median "${p99s_on[@]}")
  summary+=("$(awk -v w="$world" -v a="$off" -v b="$on" -v n="$rounds" \
    'BEGIN { printf "%s: median p99 over %d runs, checker off %.1f ms, on %.1f ms, on/off %.2f", w, n, a, b, b / a }')")
done
printf '%s\n' "${summary[@]}"
