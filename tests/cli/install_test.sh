#!/usr/bin/env bash
# cmake --install into a fresh prefix, then the installed executable run from an empty folder
# elsewhere: it finds its own copy of the assets (not the source tree's: that is hidden from it
# by a scene only the installed copy has), opens a lesson by number and a bundled scene by name.
# Usage: install_test.sh BUILD_DIR
set -euo pipefail
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log" || { cat "$work/install.log"; exit 1; }
exe="$work/prefix/bin/softbody"
[ -x "$exe" ] || { echo "FAIL: no executable at PREFIX/bin/softbody"; exit 1; }
[ -f "$work/prefix/share/softbody/assets/scenes/spring.json" ] || { echo "FAIL: no assets at PREFIX/share/softbody/assets"; exit 1; }
# A scene that only the installed assets hold: found by name, so the installed copy is the one used.
cp "$work/prefix/share/softbody/assets/scenes/spring.json" "$work/prefix/share/softbody/assets/scenes/only_installed.json"
mkdir "$work/elsewhere"
cd "$work/elsewhere"
"$exe" simulate --lesson 1 --ticks 10 > lesson.json || { echo "FAIL: simulate --lesson 1 from elsewhere"; exit 1; }
grep -q '"status": *"ok"' lesson.json || { echo "FAIL: lesson 1 did not run: $(cat lesson.json)"; exit 1; }
"$exe" simulate --scene only_installed.json --ticks 10 > named.json || { echo "FAIL: a scene by name from the installed assets"; exit 1; }
"$exe" simulate --scene assets/scenes/spring.json --ticks 10 > path.json || { echo "FAIL: assets/scenes/spring.json from elsewhere"; exit 1; }
# The same scene gives the same state, installed or not.
cmp <(grep -o '"state_hash": *"[0-9a-f]*"' lesson.json) <(grep -o '"state_hash": *"[0-9a-f]*"' named.json) \
  || { echo "FAIL: the installed scene gave another state"; exit 1; }
[ -z "$(ls -A "$work/elsewhere" | grep -v '\.json$')" ] || { echo "FAIL: files left in the working folder"; exit 1; }
echo "ok: installed to a prefix, ran lesson 1 and bundled scenes from an empty folder"
