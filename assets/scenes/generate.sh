#!/usr/bin/env bash
# Writes every built-in scene as a glTF 2.0 file here, from the definitions in
# src/host/scene/scene.cpp (tests check that these files are current and that loading one gives
# the built-in scene's G-buffer). Usage: assets/scenes/generate.sh [path/to/sslr-render]
set -euo pipefail
cd "$(dirname "$0")"
render=${1:-../../build/release/src/apps/sslr-render}
for name in mirror-room grazing-plane thin-objects sky-heavy mirror-box tilted-mirror facing-mirror mirror-walls \
            curved-mirror glossy; do
  "$render" --scene "$name" --export-gltf "$name.gltf" > /dev/null
done
ls -l ./*.gltf
