#!/usr/bin/env bash
# The two commands of README.md, each complete on its own on a fresh Debian 12 machine:
#   ./dev.sh demo   install what is missing, build the app (not the tests), open the interactive demo
#   ./dev.sh test   install what is missing, build, run every test; then the browser version in
#                   headless Chromium (build-web/), the unit, kernel and CLI tests again under
#                   AddressSanitizer + UndefinedBehaviorSanitizer (clang, build-asan/), and a fixed
#                   set of inputs to each fuzz target (built in the same build-asan/)
#   ./dev.sh soak   install, build the app, run the demo for 20,000 scripted frames (virtual display)
#   ./dev.sh web    install what is missing, build the browser version (build-web/site/) and serve
#                   it at http://127.0.0.1:8080/ until stopped (WEB_PORT for another port)
#   ./dev.sh python install what is missing, build the Python module (app/python), open python3
#                   with it importable (`import softbody`); with arguments, `python3 -m jupyter ARGS`
#                   instead (./dev.sh python notebook assets/notebooks/, with Debian's jupyter-notebook)
# Everything comes from Debian's packages (the browser version's few C++ sources from Debian's
# source packages, by apt); nothing is downloaded from anywhere else.
# ffmpeg is for videos: the app's Record button and `softbody render --video` run it (found at run
# time; without it they write PNG frames), and the video tests read the clips back with ffprobe.
set -euo pipefail
cd "$(dirname "$0")"

PACKAGES=(
  cmake ninja-build g++ pkg-config
  libglfw3-dev libglm-dev libimgui-dev libosmesa6-dev libtinyobjloader-dev python3-glad libstb-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev zlib1g-dev libqhull-dev libmeshoptimizer-dev
  xvfb xauth libgl1-mesa-dri libglx-mesa0
  ffmpeg
  pybind11-dev python3-dev python3-numpy
)
# Only `test` needs these: clang and its runtimes for the fuzz targets (libFuzzer).
TEST_PACKAGES=(clang libclang-rt-14-dev)
# The lesson notebooks (assets/notebooks): `test` runs them headless, `python` opens them.
NOTEBOOK_PACKAGES=(python3-matplotlib python3-nbclient python3-ipykernel)
# The browser version (`web`, and `test`, which tests it in a browser): emscripten compiles it,
# chromium runs the tests. The sources of Dear ImGui, Qhull and meshoptimizer, which Debian
# ships built for this machine only, come from their Debian source packages (web/fetch_sources.py).
WEB_PACKAGES=(emscripten chromium)
BUILD_DIR=${BUILD_DIR:-build}
WEB_DIR=${WEB_DIR:-build-web}
JOBS=$(nproc 2>/dev/null || echo 2)
# A new build folder is built by Ninja (one already configured keeps its generator): it sees the
# whole build as one graph, so a target's sources compile while the libraries before it link,
# and it checks dependencies itself. The native build here: 5 min 36 s against 6 min 9 s.
export CMAKE_GENERATOR=${CMAKE_GENERATOR:-Ninja}

install_missing() {
  local missing=() package
  for package in "${PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed' || missing+=("$package")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "dev.sh: installing ${missing[*]}"
  local sudo=()
  if [ "$(id -u)" -ne 0 ]; then sudo=(sudo); fi
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq "${missing[@]}"
}

# Every target with no argument (the tests too); with one, that target and what it needs: the
# demo builds only the app, so the first window does not wait for the tests to compile.
build() {
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$BUILD_DIR" -j"$JOBS" ${1:+--target "$1"}
}

# The browser version, into $WEB_DIR/site: two builds of web/ (CMake, emscripten), with
# WebAssembly threads and without (web/CMakeLists.txt says why both), and the page.
build_web() {
  local start=$SECONDS variant threads
  python3 web/fetch_sources.py "$WEB_DIR/sources"
  # emscripten's JavaScript optimiser needs Debian's acorn module, which a node installed from
  # elsewhere (first on PATH) does not look for.
  export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
  for variant in single threads; do
    threads=OFF
    if [ "$variant" = threads ]; then threads=ON; fi
    emcmake cmake -S web -B "$WEB_DIR/$variant" -DCMAKE_BUILD_TYPE=Release -DSOFTBODY_WEB_THREADS="$threads" \
      -DSOFTBODY_WEB_SOURCES="$PWD/$WEB_DIR/sources" -DSOFTBODY_WEB_SITE="$PWD/$WEB_DIR/site" >/dev/null
    cmake --build "$WEB_DIR/$variant" -j"$JOBS"
  done
  echo "dev.sh: browser build took $(( SECONDS - start )) s ($WEB_DIR/site)"
}

# The browser version in headless Chromium (tests/web/browser_test.py): the scripted pile run's
# summary against the native build's, its picture against a reference, and the threaded and
# one-thread builds on a soft body. Needs the native build (its softbody and image comparison).
web_tests() {
  local start=$SECONDS
  build_web
  python3 tests/web/browser_test.py --site "$WEB_DIR/site" --softbody "$BUILD_DIR/app/softbody" \
    --compare "$BUILD_DIR/tests/render/softbody_image_compare" --module "$BUILD_DIR/app/python" --work "$WEB_DIR/tests"
  echo "dev.sh: browser build and tests took $(( SECONDS - start )) s"
}

# The unit, kernel, CLI and fuzz-regression tests again under AddressSanitizer and
# UndefinedBehaviorSanitizer (CMakePresets.json, preset asan: clang, build-asan/, no renderer
# or window, only the targets these tests need, and the fuzz targets, which link the same
# sanitized libraries). Any report fails the test that made it.
sanitizer_tests() {
  local start=$SECONDS
  cmake --preset asan >/dev/null
  cmake --build --preset asan -j"$JOBS"
  ASAN_OPTIONS=halt_on_error=1:detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    ctest --preset asan -j"$JOBS"
  echo "dev.sh: sanitizer build and tests took $(( SECONDS - start )) s"
}

# Each fuzz target (built by sanitizer_tests) from its seeds and every input that once broke it, copied to a temporary
# folder (the fuzzer adds what it finds there, never in tests/). By default a fixed seed and a
# fixed number of inputs (FUZZ_RUNS, default 30,000: 3 to 35 s a target here), the same amount
# of fuzzing on any machine; with FUZZ_SECONDS set, for that long from a fresh seed each time,
# to look for new findings. A
# crash, a sanitizer's report, a broken invariant or a slow input fails, and its input is kept.
fuzz_smoke() {
  local start=$SECONDS work target budget
  if [ -n "${FUZZ_SECONDS:-}" ]; then
    budget=(-max_total_time="$FUZZ_SECONDS")
  else
    budget=(-seed=1 -runs="${FUZZ_RUNS:-30000}")
  fi
  work=$(mktemp -d "${TMPDIR:-/tmp}/softbody-fuzz.XXXXXX")
  for target in fuzz_mesh fuzz_scene fuzz_set; do
    mkdir -p "$work/$target"
    cp tests/fuzz/corpus/"$target"/* "$work/$target/"
    if [ -d tests/fuzz/regressions/"$target" ]; then
      find tests/fuzz/regressions/"$target" -type f -exec cp {} "$work/$target/" \;
    fi
    if ! build-asan/tests/fuzz/"$target" "${budget[@]}" -timeout=10 -rss_limit_mb=2048 \
         -dict=tests/fuzz/dict/"$target".dict -artifact_prefix="$work/" "$work/$target" >"$work/$target.log" 2>&1; then
      tail -n 60 "$work/$target.log" >&2
      echo "dev.sh: $target failed; its log and the input that failed are in $work" >&2
      exit 1
    fi
    echo "dev.sh: $target: $(grep -o 'Done [0-9]* runs in [0-9]* second(s)' "$work/$target.log")"
  done
  rm -rf "$work"
  echo "dev.sh: fuzz runs took $(( SECONDS - start )) s"
}

case "${1:-}" in
  demo)
    install_missing
    build softbody
    shift
    if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
      echo "dev.sh: no display to open a window on; run this from a desktop session" >&2
      echo "        (headless: '$BUILD_DIR/app/softbody render --help', or './dev.sh test')" >&2
      exit 1
    fi
    exec "$BUILD_DIR/app/softbody" "$@"
    ;;
  test)
    install_missing "${TEST_PACKAGES[@]}" "${NOTEBOOK_PACKAGES[@]}" "${WEB_PACKAGES[@]}"
    build
    ctest --test-dir "$BUILD_DIR" --output-on-failure -j"$JOBS"
    web_tests
    sanitizer_tests
    fuzz_smoke
    ;;
  soak)
    # Everything a user does, for 20,000 frames, in one process; memory is reported at frame
    # 100 and at the end (the JSON line's memory_kib).
    install_missing
    build softbody
    frames=${SOAK_FRAMES:-20000}
    runner=()
    if [ -z "${DISPLAY:-}" ]; then runner=(xvfb-run -a -s "-screen 0 1280x800x24"); fi
    start=$(date +%s)
    "${runner[@]}" "$BUILD_DIR/app/softbody" run --size 800x600 --frames "$frames" --script tests/soak/soak.script
    echo "dev.sh: soak of $frames frames took $(( $(date +%s) - start )) s"
    ;;
  python)
    # The interpreter the module was built for (Debian's python3: app/python/CMakeLists.txt).
    install_missing "${NOTEBOOK_PACKAGES[@]}"
    build softbody_python
    shift
    interpreter=$(cat "$BUILD_DIR/app/python/interpreter")
    PYTHONPATH="$(cd "$BUILD_DIR/app/python" && pwd)${PYTHONPATH:+:$PYTHONPATH}"
    export PYTHONPATH
    if [ $# -eq 0 ]; then exec "$interpreter"; fi
    install_missing jupyter-notebook  # the notebook server, for this use only
    exec "$interpreter" -m jupyter "$@"
    ;;
  web)
    install_missing "${WEB_PACKAGES[@]}"
    build_web
    echo "dev.sh: open http://127.0.0.1:${WEB_PORT:-8080}/ (Ctrl+C stops the server; $WEB_DIR/site can go on any static host)"
    exec python3 web/serve.py --port "${WEB_PORT:-8080}" "$WEB_DIR/site"
    ;;
  *)
    echo "usage: ./dev.sh demo   (install, build, open the demo)" >&2
    echo "       ./dev.sh test   (install, build, run every test, then under the sanitizers, then the fuzzers)" >&2
    echo "       ./dev.sh soak   (install, build, 20,000 scripted frames of the demo)" >&2
    echo "       ./dev.sh web    (install, build the browser version, serve it at http://127.0.0.1:8080/)" >&2
    echo "       ./dev.sh python (install, build the Python module, open python3 with it; ARGS: jupyter ARGS)" >&2
    exit 2
    ;;
esac
