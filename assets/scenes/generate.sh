#!/usr/bin/env bash
# Writes every built-in scene as a glTF 2.0 file here, from the definitions in
# src/host/scene/scene.cpp (tests check that these files are current and that loading one gives
# the built-in scene's G-buffer), and the asset scenes: real models from Debian's
# assimp-testmodels (BSD-3-clause, the assimp team), converted to glTF by assimp-utils' `assimp`
# and staged by `sslr-render --stage` (src/host/scene/scene.cpp, stageModel).
# Usage: assets/scenes/generate.sh [path/to/sslr-render]
set -euo pipefail
cd "$(dirname "$0")"
render=${1:-../../build/release/src/apps/sslr-render}
for name in mirror-room grazing-plane thin-objects sky-heavy mirror-box tilted-mirror facing-mirror mirror-walls \
            curved-mirror glossy turned-mirror mirror-corridor mirrors-from-above sphere-over-mirror-32 \
            sphere-over-mirror-128 objects-on-mirror bright-emitter; do
  "$render" --scene "$name" --export-gltf "$name.gltf" > /dev/null
done

models=/usr/share/assimp/models
if ! command -v assimp > /dev/null || [ ! -d "$models/OBJ" ]; then
  echo "generate.sh: the asset scenes need assimp-utils and assimp-testmodels (apt-get install assimp-utils assimp-testmodels)" >&2
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# name, source model, stage
while read -r name model stage; do
  assimp export "$models/$model" "$work/$name.glb" -fglb2 > /dev/null
  "$render" --scene "$work/$name.glb" --stage "$stage" --export-gltf "$name.gltf" > /dev/null 2>&1
done <<'LIST'
spider-on-mirror OBJ/spider.obj on-mirror
wuson-as-mirror OBJ/WusonOBJ.obj as-mirror
LIST
ls -l ./*.gltf
