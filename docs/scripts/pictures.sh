#!/usr/bin/env bash
# Regenerates the rendered pictures in docs/images (not the debug views or the benchmark figures)
# from the current build. Needs oiiotool (Debian openimageio-tools) for the side-by-side figure
# and xvfb-run for the viewer's.
# Usage: docs/scripts/pictures.sh [build-dir]
set -euo pipefail
build=${1:-build/release}
render="$build/src/apps/sslr-render"
images=$(dirname "$0")/../images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

shot() {  # shot OUTPUT.png ARGS...: sslr-render's final.png
  local out=$1
  shift
  "$render" --out "$tmp/shot" "$@" >/dev/null 2>&1
  cp "$tmp/shot/final.png" "$out"
}
shot "$images/mirror-room.png" --scene mirror-room --size 960x540
shot "$images/mirror-room-no-reflections.png" --scene mirror-room --size 960x540 --method none
for scene in grazing-plane thin-objects sky-heavy; do shot "$images/$scene.png" --scene "$scene" --size 960x540; done

# Composite modes: the fallback alone (no trace), the reflection added on top of it, and the
# reflection blended over it by coverage (the default).
shot "$tmp/none.png" --size 480x270 --method none
shot "$tmp/add.png" --size 480x270 --composite add
shot "$tmp/blend.png" --size 480x270 --composite blend
oiiotool "$tmp"/{none,add,blend}.png --mosaic 3x1 -o "$images/composite-modes.png"
# The viewer (needs xvfb-run): adaptive L against the McGuire-Mara DDA, split screen.
xvfb-run -a -s '-screen 0 1920x1080x24' "$build/src/apps/sslr-view" --size 1280x720 --frames 4 --split dda \
  --screenshot "$images/sslr-view.png" >/dev/null 2>&1
echo "pictures written to $images"
