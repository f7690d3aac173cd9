#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then the installed tree is used the way a
# user would: the binary's version, the scene and plume generators, a render of an
# installed scene, the help text naming
# the installed guide, the Python module imported from the installed dist-packages, and
# the Blender add-on zip holding the add-on's Python files.
# Usage: install_test.sh BUILD_DIR VERSION SOURCE_DIR PYTHON_BUILT(ON|OFF)
set -euo pipefail
build=$1 version=$2 source=$3 python_built=$4
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" > "$prefix/install.log" || { cat "$prefix/install.log"; fail "cmake --install"; }

binary=$prefix/bin/vkdiffrender
[ -x "$binary" ] || fail "no $binary"
[ "$("$binary" --version)" = "vkdiffrender $version" ] || fail "--version printed '$("$binary" --version)'"

docs=$prefix/share/doc/vkdiffrender
for file in README.md "$source"/docs/*.md; do
  [ -f "$docs/$(basename "$file")" ] || fail "$(basename "$file") is not installed in $docs"
done
# The installed binary names the guide where it is installed, not a source path.
"$binary" optimize --help | tr -s ' \n' ' ' | grep -qF "$docs/optimisation.md" \
  || fail "optimize --help does not name $docs/optimisation.md"

scenes=$prefix/share/vkdiffrender/scenes
for scene in cornell_box.gltf cornell_fog.gltf cornell_smoke.gltf experiments/cornell_absorption.json; do
  [ -f "$scenes/$scene" ] || fail "$scene is not installed in $scenes"
done
# The generators of benchmark rooms and smoke plumes run from the prefix.
"$prefix/bin/vkdr-make-scene" --triangles 200 -o "$prefix/room.glb" > /dev/null || fail "vkdr-make-scene"
[ -s "$prefix/room.glb" ] || fail "vkdr-make-scene wrote no room.glb"
"$prefix/bin/vkdr-make-plume" --resolution 8 --seed 1 "$prefix/plume.vdb" > /dev/null || fail "vkdr-make-plume"
[ -s "$prefix/plume.vdb" ] || fail "vkdr-make-plume wrote no plume.vdb"
# Rendered from the installed scenes, in a directory away from the source and build trees.
(cd "$prefix" && "$binary" render "$scenes/cornell_fog.gltf" --width 8 --height 6 --spp 1 --max-depth 2 \
  -o "$prefix/fog.exr" --png "$prefix/fog.png" > /dev/null 2>&1) || fail "render of the installed cornell_fog.gltf"
[ -s "$prefix/fog.exr" ] && [ -s "$prefix/fog.png" ] || fail "the render wrote no image"

if [ "$python_built" = ON ]; then
  site=$prefix/lib/python3/dist-packages
  (cd "$prefix" && PYTHONPATH=$site /usr/bin/python3 -c '
import sys, vkdiffrender
assert vkdiffrender.__file__.startswith(sys.argv[1]), vkdiffrender.__file__
assert vkdiffrender.__version__ == sys.argv[2], vkdiffrender.__version__
image = vkdiffrender.Scene(sys.argv[3]).render(spp=1, seed=1, width=8, max_depth=2)
assert image.shape[1:] == (8, 3), image.shape
' "$site" "$version" "$scenes/cornell_fog.gltf") || fail "the module does not import or render from $site"
fi

addon=$source/tools/blender/vkdiffrender_blender
zip=$prefix/share/vkdiffrender/blender/vkdiffrender_blender.zip
if [ -d "$addon" ]; then
  [ -f "$zip" ] || fail "no $zip"
  expected=$(cd "$source/tools/blender" && find vkdiffrender_blender -name '*.py' -not -path '*/__pycache__/*' | sort)
  listed=$(/usr/bin/python3 -c 'import sys, zipfile; print("\n".join(sorted(zipfile.ZipFile(sys.argv[1]).namelist())))' "$zip")
  [ "$listed" = "$expected" ] || fail "the add-on zip holds '$listed', the add-on directory '$expected'"
fi
echo "installed and ran from $prefix"
