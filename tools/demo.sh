#!/usr/bin/env bash
# Builds fusemap, simulates a short run through the default hall and maps it: the README's
# first command (after tools/install_deps.sh). Outputs land in out/demo/.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${FUSEMAP_BUILD_DIR:-build}
out=${FUSEMAP_DEMO_OUT:-out/demo}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DFUSEMAP_BUILD_TESTS=OFF
cmake --build "$build_dir" -j"$(nproc)"
bin=$build_dir/tools
mkdir -p "$out"

echo "== simulating 40 s in data/worlds/hall.yaml (laser, odometry, IMU, RGB-D at 2 Hz)"
"$bin/sim/fusemap_sim" --world data/worlds/hall.yaml --seconds 40 --seed 1 --rgbd-rate 2 --out "$out"
echo "== mapping $out/sim.lcm"
"$bin/offline/fusemap_offline" --log "$out/sim.lcm" --config config/sim.yaml --out "$out" --threads 2 --quiet
echo "== accuracy against the simulator's ground truth"
"$bin/eval/fusemap_eval" ate --gt "$out/groundtruth.tum" --est "$out/trajectory.tum" | tail -1
echo "== coloured 3D map against the simulator's world (surface distance, dynamic removal, landmarks)"
"$bin/cloudeval/fusemap_cloudeval" --cloud "$out/cloud.ply" --world data/worlds/hall.yaml \
  --gt "$out/groundtruth.tum" | head -2
echo "== ground truth from the floor AprilTags, and the SLAM trajectory scored against it"
"$bin/tagscore/fusemap_tagscore" groundtruth --log "$out/sim.lcm" --tags "$out/tags.yaml" \
  --config config/tagscore.yaml --out "$out/tag_groundtruth.tum"
"$bin/tagscore/fusemap_tagscore" score --gt "$out/tag_groundtruth.tum" --est "$out/trajectory.tum" \
  --report "$out/report" | tail -3
echo "== done: $out/map.png (map + trajectory), $out/map.pgm/.yaml, $out/trajectory.tum,"
echo "   $out/cloud.png (rendered 3D map), $out/cloud.ply/.pcd, $out/octomap.bt/.ot,"
echo "   $out/report/index.html (tag-based score)"
