#!/usr/bin/env bash
# Installs fusemap's build and test dependencies from Debian 12 packages (run as root).
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends \
  build-essential cmake pkg-config git ca-certificates \
  libeigen3-dev libceres-dev libpcl-dev libopencv-dev \
  liblcm-dev liblcm-bin liblcm-java libglib2.0-dev default-jdk-headless \
  libapriltag-dev liboctomap-dev libgtest-dev libgmock-dev libyaml-cpp-dev \
  zlib1g-dev iproute2 util-linux
# Not needed to build or test: data/vocabulary/rebuild.sh installs opencv-doc and
# mate-backgrounds (the natural images the committed ORB vocabulary is trained on) when run.
