#!/usr/bin/env bash
# The new code beside a baseline commit on one GPU, for the GPU targets of the lean trace (#57):
# prepare() with a cold driver cache, each pass's GL_TIMESTAMP time and the ray work at 1920x1080
# and 3840x2160 (both commits' default and FidelityFX SSSR at thickness 0.5; the new half
# resolution and the new default with ContextDesc::occupancyExit), the two commits interleaved
# scene by scene. gpu_run.sh runs it first when a baseline bundle is there; alone:
#   docs/scripts/bundle.sh                                  # this checkout: .gpu/bundle.tar.xz
#   (cd BASELINE_CHECKOUT && docs/scripts/bundle.sh)        # then copy its archive to .gpu/base.tar.xz
#   docs/scripts/gpu_compare.sh [SECONDS]                   # default 300
# The log goes to $OUT/compare.log (default gpu-out); docs/scripts/gpu_compare.py turns it into the
# targets' table. SIZES, SCENES and FRAMES override the sizes, scenes and timed frames (a CPU
# rasterizer tries the script at small sizes); NEW_DIR names a directory where this commit's
# bundle is unpacked already (gpu_run.sh's checkout), instead of unpacking it again.
set -u
cd "$(dirname "$0")/../.."
out=${OUT:-gpu-out}
budget=${1:-300}
sizes=${SIZES:-1920x1080 3840x2160}
scenes=${SCENES:-mirror-room thin-objects mirror-walls sky-heavy facing-mirror}
frames=${FRAMES:-30}
start=$(date +%s)
left() { echo $((budget - ($(date +%s) - start))); }
mkdir -p "$out"
log=$out/compare.log

# Each commit's tools from its own bundle (bundle.sh's archive), with its own libraries.
unpack() {  # ARCHIVE DIR
  rm -rf "$2" && mkdir -p "$2" && tar xf "$1" -C "$2"
}
[ -f .gpu/bundle.tar.xz ] && [ -f .gpu/base.tar.xz ] || {
  echo "gpu_compare.sh: needs .gpu/bundle.tar.xz (this commit) and .gpu/base.tar.xz (the baseline)" >&2
  exit 2
}
new_dir=${NEW_DIR:-.gpu/new}
[ -n "${NEW_DIR:-}" ] || unpack .gpu/bundle.tar.xz "$new_dir" || exit 1
unpack .gpu/base.tar.xz .gpu/base || exit 1
render() {  # WHICH ARGS...: one sslr-render of commit WHICH (new or base): its --stats lines, errors
  local dir=.gpu/base
  [ "$1" = new ] && dir=$new_dir
  shift
  LD_LIBRARY_PATH=$PWD/$dir/build/portable/lib timeout 60 "$dir/build/portable/src/apps/sslr-render" \
    --stats --out "$dir/out" "$@" 2>&1 | grep -E "GL_RENDERER|traced pixels|ray work|pass times|frame times|rror|exist"
}

{
  for which in new base; do
    dir=.gpu/base
    [ "$which" = new ] && dir=$new_dir
    echo "commit $which: $(sed -n 's/^commit=//p' "$dir/build/portable/bundle-info")"
  done
  # prepare() with the driver's shader caches off (NVIDIA's and Mesa's): what a new user waits.
  for round in 1 2; do
    for which in new base; do
      for method in default ffx-sssr; do
        m=()
        [ "$method" = default ] || m=(--method ffx-sssr --ffx-thickness 0.5)
        echo "== cold $which $method round $round"
        __GL_SHADER_DISK_CACHE=0 MESA_SHADER_CACHE_DISABLE=true render "$which" --size 160x90 --frames 2 "${m[@]}"
      done
    done
  done
  # Frames: the commits interleaved per scene and size, so that drift hits both alike.
  for size in $sizes; do
    for scene in $scenes; do
      for variant in default ffx half exit; do
        for which in new base; do
          [ "$which" = base ] && { [ "$variant" = half ] || [ "$variant" = exit ]; } && continue
          [ "$(left)" -gt 10 ] || { echo "== stopped: out of time"; break 4; }
          case $variant in
            default) v=() ;;
            ffx) v=(--method ffx-sssr --ffx-thickness 0.5) ;;
            half) v=(--half-res) ;;
            exit) v=(--occupancy-exit) ;;
          esac
          echo "== frame $which $variant $scene $size"
          render "$which" --scene "$scene" --size "$size" --frames "$frames" "${v[@]}"
        done
      done
    done
  done
} >"$log"
echo "gpu_compare: $(grep -c '^== frame' "$log") frame runs in $(($(date +%s) - start)) s -> $log"
