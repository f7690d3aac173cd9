#!/bin/sh
# Writes fog_scene.glb beside this script, the procedural scene of fog_two_parameters.json:
# about a million triangles in the scene-wide medium "fog" (whose values the experiment
# sets itself), in a room 300 units across so that the target fog (sigma_s = 1e-3,
# sigma_a = 1e-4) has optical depths that an image can show.
# Usage: make_fog_scene.sh [path to vkdr-make-scene]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
make_scene=${1:-"$here/../../build/tools/vkdr-make-scene"}
"$make_scene" --triangles 1000000 --scale 30 -o "$here/fog_scene.glb" --fog 0.0009,0.2
