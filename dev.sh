#!/usr/bin/env bash
# The two commands of README.md, each complete on its own on a fresh Debian 12 machine:
#   ./dev.sh demo   install what is missing, build, open the interactive demo
#   ./dev.sh test   install what is missing, build, run every test
#   ./dev.sh soak   install, build, run the demo for 20,000 scripted frames (virtual display)
# Everything comes from Debian's packages; nothing is downloaded from anywhere else.
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(
  cmake g++ pkg-config
  libglfw3-dev libglm-dev libimgui-dev libosmesa6-dev libtinyobjloader-dev python3-glad libstb-dev
  nlohmann-json3-dev libgtest-dev libbenchmark-dev zlib1g-dev
  xvfb xauth libgl1-mesa-dri libglx-mesa0
)
BUILD_DIR=${BUILD_DIR:-build}
JOBS=$(nproc 2>/dev/null || echo 2)

install_missing() {
  local missing=() package
  for package in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed' || missing+=("$package")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "dev.sh: installing ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}"
}

build() {
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$BUILD_DIR" -j"$JOBS"
}

case "${1:-}" in
  demo)
    install_missing
    build
    shift
    if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
      echo "dev.sh: no display to open a window on; run this from a desktop session" >&2
      echo "        (headless: '$BUILD_DIR/app/softbody render --help', or './dev.sh test')" >&2
      exit 1
    fi
    exec "$BUILD_DIR/app/softbody" "$@"
    ;;
  test)
    install_missing
    build
    ctest --test-dir "$BUILD_DIR" --output-on-failure -j"$JOBS"
    ;;
  soak)
    # Everything a user does, for 20,000 frames, in one process; memory is reported at frame
    # 100 and at the end (the JSON line's memory_kib).
    install_missing
    build
    frames=${SOAK_FRAMES:-20000}
    runner=()
    if [ -z "${DISPLAY:-}" ]; then runner=(xvfb-run -a -s "-screen 0 1280x800x24"); fi
    start=$(date +%s)
    "${runner[@]}" "$BUILD_DIR/app/softbody" run --size 800x600 --frames "$frames" --script tests/soak/soak.script
    echo "dev.sh: soak of $frames frames took $(( $(date +%s) - start )) s"
    ;;
  *)
    echo "usage: ./dev.sh demo   (install, build, open the demo)" >&2
    echo "       ./dev.sh test   (install, build, run every test)" >&2
    echo "       ./dev.sh soak   (install, build, 20,000 scripted frames of the demo)" >&2
    exit 2
    ;;
esac
