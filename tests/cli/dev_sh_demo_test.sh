#!/usr/bin/env bash
# ./dev.sh demo builds only what the window needs (the softbody target); the tests are built by
# ./dev.sh test. Run with stand-ins for cmake and dpkg-query on PATH, which record what they are
# asked and build nothing, and without a display, so the script stops once it has built.
set -euo pipefail
source_dir=$1
work=$(mktemp -d "${TMPDIR:-/tmp}/softbody-devsh.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir "$work/bin"
cat >"$work/bin/cmake" <<'STUB'
#!/bin/sh
echo "cmake $*" >>"$CALLS"
STUB
cat >"$work/bin/dpkg-query" <<'STUB'
#!/bin/sh
printf 'install ok installed'
STUB
chmod +x "$work/bin/cmake" "$work/bin/dpkg-query"
export CALLS=$work/calls.txt
status=0
env -u DISPLAY -u WAYLAND_DISPLAY PATH="$work/bin:$PATH" BUILD_DIR="$work/build" \
  bash "$source_dir/dev.sh" demo >/dev/null 2>"$work/stderr.txt" || status=$?
if [ "$status" -ne 1 ] || ! grep -q "no display" "$work/stderr.txt"; then
  echo "expected dev.sh demo to stop for want of a display (exit 1), got $status:" >&2
  cat "$work/stderr.txt" >&2
  exit 1
fi
if [ "$(grep -c -- "--build" "$CALLS")" -ne 1 ] || ! grep -- "--build" "$CALLS" | grep -q -- "--target softbody$"; then
  echo "dev.sh demo should build the softbody target alone; it ran:" >&2
  cat "$CALLS" >&2
  exit 1
fi
echo "dev.sh demo built: $(grep -- "--build" "$CALLS")"
