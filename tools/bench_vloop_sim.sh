#!/usr/bin/env bash
# End-to-end benchmark of the visual loop checker (issue 17) on the simulator's worlds where a
# 2D laser cannot close the loop right: for each world, same seed, simulate two laps, map the
# log laser-only and with the checker on, and score both against the simulator's truth.
# Usage: tools/bench_vloop_sim.sh [BUILD_DIR [OUT_DIR]]   (defaults build, out/bench_vloop_sim)
# Environment: FUSEMAP_BENCH_SEED (1), FUSEMAP_BENCH_WORLDS ("corridor rooms ring ring_rooms"),
#              FUSEMAP_BENCH_RGBD_RATE (2 Hz), FUSEMAP_BENCH_THREADS (2, rendering only: the
#              mapping runs with --threads 1, which is reproducible bit for bit).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
out=${2:-out/bench_vloop_sim}
seed=${FUSEMAP_BENCH_SEED:-1}
worlds=${FUSEMAP_BENCH_WORLDS:-corridor rooms ring ring_rooms}
rate=${FUSEMAP_BENCH_RGBD_RATE:-2}
threads=${FUSEMAP_BENCH_THREADS:-2}
sim=$build/tools/sim/fusemap_sim
offline=$build/tools/offline/fusemap_offline
evaluate=$build/tools/eval/fusemap_eval
for tool in "$sim" "$offline" "$evaluate"; do
  [[ -x $tool ]] || { echo "bench_vloop_sim: $tool missing: build it first" >&2; exit 1; }
done
mkdir -p "$out"

# config/sim.yaml without submap trimming (a trimmed submap's loops leave the graph before they
# can be scored) and without the cloud (not measured here; it doubles the run time).
laser_config=$out/laser.yaml
awk '
  /^  overlapping_submaps_trimmer:/ { skip = 1; next }
  skip && /^    / { next }
  { skip = 0 }
  /^cloud:/ { in_cloud = 1 }
  in_cloud && /^  enabled:/ { print "  enabled: false"; next }
  { print }' config/sim.yaml > "$laser_config"
checker_config=$out/checker.yaml
{ cat "$laser_config"; printf 'visual_loop:\n  enabled: true\n'; } > "$checker_config"

# value KEY FILE: the value of KEY=value (KEY a whole word) on the file's last line that has it.
value() { grep -oE "(^| )$1=[^ ]*" "$2" | tail -1 | cut -d= -f2; }

rows=()
notes=()
for world in $worlds; do
  dir=$out/$world
  echo "== $world: simulating (seed $seed, RGB-D $rate Hz)" >&2
  "$sim" --world "data/worlds/$world.yaml" --to-end --seed "$seed" --rgbd-rate "$rate" \
    --threads "$threads" --out "$dir" 2>/dev/null | tee "$dir.sim.txt" >&2
  for mode in laser checker; do
    run=$dir/$mode
    config=$out/$mode.yaml
    echo "== $world: mapping $mode" >&2
    if ! "$offline" --log "$dir/sim.lcm" --config "$config" --out "$run" --threads 1 --quiet > "$run.txt" 2>&1; then
      if [[ $mode == checker ]] && grep -q "visual_loop" "$run.txt"; then
        notes+=("$world $mode wrong_by_decision=$(value wrong_by_decision "$run.loops.txt") held_across_only=$(value held_across_only "$run.loops.txt")")
    rows+=("$(printf '%-9s %-8s %s' "$world" "$mode" "not available in this build: $(grep -m1 visual_loop "$run.txt")")")
        continue
      fi
      echo "bench_vloop_sim: $offline failed on $world ($mode), see $run.txt" >&2
      exit 1
    fi
    if grep -q "^visual_loop:" "$run.txt"; then notes+=("$world $mode $(grep "^visual_loop:" "$run.txt")"); fi
    grep -E "^(global_slam|scans)=?" "$run.txt" | sed "s|^|$world $mode |" >&2 || true
    "$evaluate" start-end --gt "$dir/groundtruth.tum" --est "$run/trajectory.tum" > "$run.start_end.txt"
    "$evaluate" ate --se2 --gt "$dir/groundtruth.tum" --est "$run/trajectory.tum" > "$run.ate.txt"
    "$evaluate" loops --gt "$dir/groundtruth.tum" --dir "$run" --verbose > "$run.loops.txt"
    notes+=("$world $mode wrong_by_decision=$(value wrong_by_decision "$run.loops.txt") held_across_only=$(value held_across_only "$run.loops.txt")")
    rows+=("$(printf '%-9s %-8s %13s %13s %10s %6s %8s %14s %8s  %s' "$world" "$mode" \
      "$(value start_end_m "$run.start_end.txt")" "$(value start_end_deg "$run.start_end.txt")" \
      "$(value ate_rmse_m "$run.ate.txt")" "$(value loops "$run.loops.txt")" \
      "$(value accepted "$run.loops.txt")" "$(value wrong_accepted "$run.loops.txt")" \
      "$(value unscored "$run.loops.txt")" "$(value decisions "$run.loops.txt")")")
  done
done
printf '%-9s %-8s %13s %13s %10s %6s %8s %14s %8s  %s\n' world mode start_end_m start_end_deg \
  ate_rmse_m loops accepted wrong_accepted unscored decisions
printf '%s\n' "${rows[@]}"
[[ ${#notes[@]} -eq 0 ]] || printf '%s\n' "${notes[@]}"
