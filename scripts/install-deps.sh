#!/usr/bin/env bash
# Installs the Debian 12 packages diffphoton needs. Idempotent: does nothing when all are present.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libembree-dev libtbb-dev libglm-dev libopenexr-dev libopencv-dev libassimp-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libexiv2-dev  # EXIF focal length for camera calibration
  opencv-doc    # OpenCV's chessboard photographs, used by the calibration tests
  blender-data  # the CC0 light probes the sample project and benchmarks use
  qt6-base-dev  # the studio (Widgets, Test; pulls libqt6gui6 with the offscreen and xcb platforms)
  xvfb xauth    # xvfb-run for the studio's screenshot test and documentation screenshots
  clang libclang-rt-14-dev  # the sanitizer build and the libFuzzer targets (tests/fuzz)
)
# `--bench`: also what the benchmark plots need, and Blender for the Cycles method.
[ "${1:-}" = "--bench" ] && packages+=(python3-matplotlib blender)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
