#!/usr/bin/env bash
# Rebuilds data/vocabulary/orb_k10_l4.bin from natural images shipped by Debian packages
# (opencv-doc's sample photos, mate-backgrounds' nature photos): no evaluation sequence is used,
# so place recognition is not tuned to the images it is scored on. Deterministic (seed 1).
# Usage: bash data/vocabulary/rebuild.sh [BUILD_DIR]   (installs the two packages if missing)
set -euo pipefail
cd "$(dirname "$0")/../.."
build_dir=${1:-build}
if ! dpkg -s opencv-doc mate-backgrounds >/dev/null 2>&1; then
  apt-get install -y --no-install-recommends opencv-doc mate-backgrounds
fi
cv=/usr/share/doc/opencv-doc/examples/data
mate=/usr/share/backgrounds/mate/nature
images=()
for name in aero1.jpg aero3.jpg aloeL.jpg apple.jpg baboon.jpg basketball1.png board.jpg \
  box_in_scene.png building.jpg butterfly.jpg cards.png chicky_512.png ela_original.jpg \
  fruits.jpg graf1.png home.jpg left.jpg leuvenA.jpg messi5.jpg orange.jpg pic2.png pic4.png \
  rubberwhale1.png smarties.png squirrel_cls.jpg starry_night.jpg stuff.jpg \
  left01.jpg left03.jpg left05.jpg left07.jpg left09.jpg left12.jpg left14.jpg; do
  images+=("$cv/$name")
done
for name in Aqua.jpg Blinds.jpg Dune.jpg FreshFlower.jpg Garden.jpg GreenMeadow.jpg LadyBird.jpg \
  RainDrops.jpg Storm.jpg TwoWings.jpg Wood.jpg YellowFlower.jpg; do
  images+=("$mate/$name")
done
cmake --build "$build_dir" --target fusemap_vloop >/dev/null
"$build_dir/tools/vloop/fusemap_vloop" train-vocabulary data/vocabulary/orb_k10_l4.bin "${images[@]}" \
  --k 10 --levels 4 --max-features 2000 --seed 1
