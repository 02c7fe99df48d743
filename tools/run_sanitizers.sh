#!/usr/bin/env bash
# Sanitizer runs (not part of .ci/run: a sanitized build and suite take far longer than CI has).
#   bash tools/run_sanitizers.sh [asan|tsan]        (default: asan)
# asan: configures build-asan with -DFUSEMAP_SANITIZE=address,undefined (ASan + UBSan, UBSan
#       aborting at its first report), builds everything, runs the whole ctest suite, then the
#       demo (tools/demo.sh, outputs in build-asan/demo).
# tsan: configures build-tsan with -DFUSEMAP_SANITIZE=thread, builds fusemapd, fusemap_sim and
#       fusemap_offline, simulates 6 s of the hall (fusemap_sim --threads 2) and replays it
#       through fusemapd --threads 2 from file://...?speed=0 (outputs in build-tsan/replay), then
#       once more with the ORB visual loop checker on (visual_loop.enabled: its own thread;
#       outputs in build-tsan/replay/visual), then maps two laps of the hall (125 s, no camera)
#       with fusemap_offline --threads 2 as fast as it runs, with room for 100 queued searches
#       and 2 MB of grids: searches displaced from a full queue, grids released and rebuilt,
#       submaps trimmed (build-tsan/replay/offline).
# ASan, LSan and TSan reports are written to BUILD/sanitizer-logs/ (so one in a child whose
# exit code a test expects to be nonzero still counts), UBSan ones to stderr with exit code 86.
# The run fails if any report was written or any step failed. Exit codes: 0 clean, 1 a step
# failed or a sanitizer reported, 2 usage error.
set -euo pipefail
# shellcheck source=help_lib.sh
source "$(dirname "$0")/help_lib.sh"
cd "$(dirname "$0")/.."
mode=${1:-asan}
case "$mode" in
  asan) build_dir=build-asan sanitize=address,undefined ;;
  tsan) build_dir=build-tsan sanitize=thread ;;
  --help | -h) help_from_header "$0"; exit 0 ;;
  *) echo "usage: bash tools/run_sanitizers.sh [asan|tsan]" >&2; exit 2 ;;
esac
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
jobs=$(nproc)
logs=$PWD/$build_dir/sanitizer-logs
rm -rf "$logs"
mkdir -p "$logs"
# Release flags plus the sanitizers: the same -O3 code the suite normally runs, and the demo
# (which configures the folder again with Release) does not trigger a rebuild.
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DFUSEMAP_SANITIZE="$sanitize" \
  -DFUSEMAP_BUILD_TESTS="$([ "$mode" = asan ] && echo ON || echo OFF)" "${launcher[@]}" >/dev/null
export ASAN_OPTIONS="log_path=$logs/asan:detect_leaks=1:strict_init_order=1"
# GCC's UBSan prints to stderr whatever log_path says: it exits with 86 instead, which no test
# expects, and ctest's log of every test's output is searched for its reports below.
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=86"
export TSAN_OPTIONS="log_path=$logs/tsan:second_deadlock_stack=1:suppressions=$PWD/tools/tsan.supp"

status=0
if [ "$mode" = asan ]; then
  cmake --build "$build_dir" -j"$jobs"
  echo "== ctest (ASan + UBSan)"
  # Sanitized daemons run several times slower than real time: replays at speed 1 would
  # overflow their queues (test/daemon/kill_resume.sh).
  export FUSEMAP_PLAYBACK_SPEED=0.25
  (cd "$build_dir" && ctest --output-on-failure --no-tests=error -j"$jobs" --timeout 1800) || status=1
  echo "== demo (ASan + UBSan)"
  FUSEMAP_BUILD_DIR=$build_dir FUSEMAP_DEMO_OUT=$build_dir/demo bash tools/demo.sh || status=1
else
  cmake --build "$build_dir" -j"$jobs" --target fusemapd fusemap_sim_tool fusemap_offline
  out=$build_dir/replay
  rm -rf "$out"
  echo "== simulating 6 s (laser, odometry, IMU, RGB-D)"
  "$build_dir/tools/sim/fusemap_sim" --world data/worlds/hall.yaml --seconds 6 --seed 1 --threads 2 \
    --out "$out" | tail -1 || status=1
  echo "== fusemapd --threads 2 over file://$PWD/$out/sim.lcm?speed=0 (TSan)"
  "$build_dir/tools/fusemapd/fusemapd" --config config/daemon.yaml \
    --lcm-url "file://$PWD/$out/sim.lcm?speed=0" --out "$out/daemon" --threads 2 --quiet ||
    status=1
  echo "== the same with the visual loop checker's thread (visual_loop.enabled: true)"
  # daemon.yaml has no visual_loop: section (a repeated key would be refused), so one is added.
  grep -q '^visual_loop:' config/daemon.yaml && { echo "daemon.yaml has visual_loop: now" >&2; exit 1; }
  { cat config/daemon.yaml; printf '\nvisual_loop:\n  enabled: true\n'; } >"$out/daemon_visual.yaml"
  "$build_dir/tools/fusemapd/fusemapd" --config "$out/daemon_visual.yaml" \
    --lcm-url "file://$PWD/$out/sim.lcm?speed=0" --out "$out/visual" --threads 2 --quiet ||
    status=1
  echo "== fusemap_offline --threads 2 over two laps of the hall, queue and grid budget tight (TSan)"
  # At full speed the searches fall behind; a small queue and budget make the search scheduler
  # drop, release and rebuild (config/sim.yaml sets neither key, so they are added).
  "$build_dir/tools/sim/fusemap_sim" --world data/worlds/hall.yaml --seconds 125 --seed 1 \
    --threads 2 --no-rgbd --out "$out/laps" | tail -1 || status=1
  sed 's/^global_slam:$/global_slam:\n  max_pending_searches: 100\n  matcher_memory_budget_mb: 2.0/' \
    config/sim.yaml >"$out/offline_tight.yaml"
  "$build_dir/tools/offline/fusemap_offline" --log "$out/laps/sim.lcm" \
    --config "$out/offline_tight.yaml" --out "$out/offline" --threads 2 --quiet --no-cloud |
    grep -E '^global_slam_memory:' || status=1
fi

if [ -f "$build_dir/Testing/Temporary/LastTest.log" ]; then
  grep -B2 -A12 "runtime error:" "$build_dir/Testing/Temporary/LastTest.log" > "$logs/ubsan.ctest" ||
    rm -f "$logs/ubsan.ctest"
fi
reports=$(find "$logs" -type f | sort)
if [ -n "$reports" ]; then
  echo "== sanitizer reports ($(echo "$reports" | wc -l) files in $logs):"
  for f in $reports; do
    echo "---- $f"
    cat "$f"
  done
  status=1
fi
echo "== $mode: $([ "$status" = 0 ] && echo clean || echo FAILED)"
exit "$status"
