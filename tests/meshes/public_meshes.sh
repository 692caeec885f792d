#!/usr/bin/env bash
# Widely used public test meshes, taken from Debian's packages into a folder of your choice, so
# that "any mesh a user brings" can be tried without committing large or other-licensed files:
#
#   tests/meshes/public_meshes.sh OUT_DIR
#   for f in OUT_DIR/*; do build/app/softbody simulate --mesh "$f" --seconds 1; done
#
# Nothing is downloaded but Debian packages, through apt. A package that is installed is read
# where it is; one that is not is fetched with `apt-get download` (no root needed, nothing is
# installed: run `apt-get update` once first) and unpacked into a temporary folder that is
# removed at the end. Each file keeps its own licence (below); none of them is to be committed.
#
# file                       package                licence (of the package / of the model)
# bunny_scan.off             libcgal-demo           CC0 (CGAL data); Stanford 3D Scanning Repository's bunny: credit it
# armadillo.off              libcgal-demo           CC0 (CGAL data); Stanford 3D Scanning Repository: credit it
# cow.off, elephant.off      libcgal-demo           CC0 (CGAL data)
# nefertiti_bust.off         libcgal-demo           CC0 (CGAL data); a scanned bust
# chinese_dragon.off         libcgal-demo           CC0 (CGAL data)
# kitten_points.off          libcgal-demo           CC0 (CGAL data); a point cloud (no faces)
# bunny.obj                  glmark2-data           GPL-3+ (glmark2); Stanford bunny
# teapot.obj                 libtbb-doc             Apache-2.0 (oneTBB's ray-tracer example); Newell's teapot,
#                                                   converted from the example's triangles
# cornell_box.obj            python3-tinyobjloader  Apache-2.0 (Intel Embree's Cornell box, millimetres)
# wuson.obj, spider.obj      assimp-testmodels      BSD-3-clause (assimp's test models)
# mug.obj                    libmujoco-samples      Apache-2.0 (MuJoCo's samples)
# suzanne.obj                python-kivy-examples   Expat (Kivy's examples); Blender's monkey head
# venus_bust.obj             gem-doc                GPL-2+ (Gem's examples); a bust of Venus
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 OUT_DIR" >&2
  exit 2
fi
out=$1
mkdir -p "$out"
work=$(mktemp -d "${TMPDIR:-/tmp}/public-meshes.XXXXXX")
trap 'rm -rf "$work"' EXIT

# The folder that holds a package's files as they would be installed: / when it is installed,
# else the package fetched with apt-get download and unpacked.
package_root() {
  local package=$1
  if dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q 'install ok installed'; then
    echo /
    return
  fi
  if [ ! -d "$work/$package" ]; then
    mkdir -p "$work/debs"
    if ! (cd "$work/debs" && apt-get download -q "$package" >/dev/null 2>"$work/$package.log"); then
      echo "public_meshes.sh: cannot fetch $package with apt-get download (run apt-get update first?):" >&2
      cat "$work/$package.log" >&2
      return 1
    fi
    dpkg-deb -x "$work/debs/${package}"_*.deb "$work/$package"
  fi
  echo "$work/$package"
}

# copy PACKAGE PATH-IN-PACKAGE NAME
copy() {
  local root
  root=$(package_root "$1")
  cp "$root/$2" "$out/$3"
  echo "$out/$3 (from $1)"
}

# --- CGAL's data: OFF files inside one archive -------------------------------------------------
cgal=$(package_root libcgal-demo)
tar -xzf "$cgal/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work" \
  data/meshes/bunny00.off data/meshes/armadillo.off data/meshes/cow.off data/meshes/elephant.off \
  data/meshes/nefertiti.off data/meshes/ChineseDragon-10kv.off data/points_3/kitten.off
for pair in bunny00:bunny_scan armadillo:armadillo cow:cow elephant:elephant nefertiti:nefertiti_bust \
            ChineseDragon-10kv:chinese_dragon; do
  cp "$work/data/meshes/${pair%%:*}.off" "$out/${pair##*:}.off"
  echo "$out/${pair##*:}.off (from libcgal-demo)"
done
cp "$work/data/points_3/kitten.off" "$out/kitten_points.off"
echo "$out/kitten_points.off (from libcgal-demo)"

# --- OBJ files as they are ---------------------------------------------------------------------
copy glmark2-data usr/share/glmark2/models/bunny.obj bunny.obj
copy python3-tinyobjloader usr/share/doc/python3-tinyobjloader/examples/cornell_box.obj cornell_box.obj
copy assimp-testmodels usr/share/assimp/models/OBJ/WusonOBJ.obj wuson.obj
copy assimp-testmodels usr/share/assimp/models/OBJ/spider.obj spider.obj
copy libmujoco-samples usr/share/mujoco/model/mug/mug.obj mug.obj
copy python-kivy-examples usr/share/kivy-examples/3Drendering/monkey.obj suzanne.obj
copy gem-doc usr/share/gem/examples/data/venus.obj venus_bust.obj

# --- The teapot: the ray-tracer scene's smooth triangles ("STRI", with normals) as OBJ ----------
# Each STRI is followed by a line "V0 x y z V1 x y z V2 x y z"; the scene's flat "TRI"
# triangles are its floor, not the teapot, and are left out. Welding joins the corners.
tbb=$(package_root libtbb-doc)
awk 'BEGIN { print "# Newell teapot, from oneTBB example parallel_for/tachyon/dat/teapot.dat (Apache-2.0)" }
     $1 == "STRI" { smooth = 1; next }
     smooth && $1 == "V0" {
       print "v", $2, $3, $4; print "v", $6, $7, $8; print "v", $10, $11, $12
       n += 3; print "f", n - 2, n - 1, n; smooth = 0
     }' "$tbb/usr/share/doc/libtbb-dev/examples/parallel_for/tachyon/dat/teapot.dat" >"$out/teapot.obj"
echo "$out/teapot.obj (from libtbb-doc, converted)"
