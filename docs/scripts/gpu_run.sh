#!/usr/bin/env bash
# The scripted GPU run behind docs/results.md's GPU section: one command on a lent GPU machine,
# from a checkout of the measured commit with `docs/scripts/bundle.sh`'s archive at
# .gpu/bundle.tar.xz. Order: the benchmark grids first (960x540 in two halves), per-pass times
# with the ray-work model (sslr-render --stats), the main configurations at 1920x1080, the GL
# tests on the GPU's driver last; each step has its own time limit, so a slow step cannot take
# the others' results.
# Results go to $OUT (default gpu-out): one archive of the CSV/JSON/plots and the logs.
# With a baseline's bundle at .gpu/base.tar.xz (bundle.sh in a checkout of that commit), the run
# begins with gpu_compare.sh: the new code beside the baseline, the lean trace's GPU targets.
# Usage: docs/scripts/gpu_run.sh [SECONDS_FOR_ALL]   (default 560; 0.9's run on an H100 used 575)
set -u
cd "$(dirname "$0")/../.."
out=${OUT:-gpu-out}
mkdir -p "$out"
budget=${1:-560}
start=$(date +%s)
left() { echo $((budget - ($(date +%s) - start))); }

# GL loader libraries where the machine has none (the device tool's recipe; see its README).
if [ -d .gl ] && ! ldconfig -p | grep -q libEGL.so.1; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
tar xf .gpu/bundle.tar.xz
export LD_LIBRARY_PATH=$PWD/build/portable/lib
info() { sed -n "s/^$1=//p" build/portable/bundle-info; }
# The test executables name the checkout's path on the build machine (golden images, tools).
src=$(info source-dir)
if [ -n "$src" ] && [ "$src" != "$PWD" ] && [ ! -e "$src" ]; then
  mkdir -p "$(dirname "$src")" && ln -s "$PWD" "$src"
fi
{
  echo "commit: $(info commit)"
  nvidia-smi --query-gpu=name,driver_version,clocks.max.sm,memory.total --format=csv 2>&1
  nproc
} >"$out/machine.txt"

# The lean trace's GPU targets (#57) first, the new commit beside the baseline whose bundle is
# .gpu/base.tar.xz (gpu_compare.sh; COMPARE_SECONDS of the budget, default 300); the steps below
# get what is left.
if [ -f .gpu/base.tar.xz ]; then
  t0=$(date +%s)
  OUT=$out NEW_DIR=. docs/scripts/gpu_compare.sh "${COMPARE_SECONDS:-300}" >>"$out/steps.txt" 2>&1
  if command -v python3 >/dev/null; then
    python3 docs/scripts/gpu_compare.py "$out/compare.log" >"$out/compare.md" 2>&1
  fi
  echo "compare: in $(($(date +%s) - t0)) s" >>"$out/steps.txt"
fi

bin=build/portable/src/apps
bench() {  # NAME LIMIT ARGS...: one grid, its log beside its results
  local name=$1 limit=$2
  shift 2
  [ "$(left)" -gt 20 ] || { echo "$name: skipped, no time left" >>"$out/steps.txt"; return; }
  [ "$limit" -le "$(left)" ] || limit=$(left)
  local t0=$(date +%s)
  timeout "$limit" "$bin/sslr-bench" "$@" --out "bench/$name" >"bench-$name.log" 2>&1
  echo "$name: exit $? in $(($(date +%s) - t0)) s" >>"$out/steps.txt"
  mv "bench-$name.log" "bench/$name/" 2>/dev/null || true
}
mkdir -p bench
# The configurations every size measures. Not the full grid: on a machine whose NVIDIA shader
# cache starts empty, each configuration's own trace variant costs seconds to compile, and 0.9.3's
# run spent its 960x540 limits compiling the first scene's (docs/results/gpu-h100.md, "0.9.3").
configs="adaptive-l/high,adaptive-l/high-no-fallback,adaptive-l/high-half,adaptive-l/high-gpu-profile,adaptive-l/high-software-profile,adaptive-l/high-gpu-one-body,hiz/steps112,dda/stride2-thick0.5,ffx-sssr/thick0.5,position-buffer/tutorial (res0.3-steps5-dist8)"
# The eight scenes of earlier GPU runs first (their first scene pays the compiles), then the
# scenes nobody here made and the sphere scenes: two grids, so one that runs out of time keeps
# the other's results.
bench 960x540 150 --grid full --no-curves --no-temporal --no-glossy --configs "$configs" \
  --scenes mirror-room,grazing-plane,thin-objects,glossy,sky-heavy,facing-mirror,mirror-walls,curved-mirror
bench 960x540-more 70 --grid full --no-curves --no-temporal --no-glossy --configs "$configs" \
  --scenes turned-mirror,mirror-corridor,mirrors-from-above,spider-on-mirror,wuson-as-mirror,sphere-over-mirror-32,sphere-over-mirror-128

# Per-pass GPU times (GL_TIMESTAMP) beside the modelled ray work of the same run: the data that
# calibrates the cost model of docs/results/ray-work.md. Default, the default with the traversal in
# one loop body (ContextDesc::oneBodyTraversal), FidelityFX SSSR (its step against the
# traversal's), traversal alone.
t0=$(date +%s)
for scene in mirror-room glossy facing-mirror mirror-walls thin-objects sky-heavy; do
  for mode in "" "--one-body-traversal" "--method ffx-sssr" "--method hiz"; do
    [ "$(left)" -gt 150 ] || break 2
    echo "== $scene ${mode:-default}"
    timeout 30 "$bin/sslr-render" --scene "$scene" --size 960x540 --stats --frames 100 $mode --out "render/$scene" 2>&1 |
      grep -E "traced pixels|ray work|pass times|frame times|commands"
  done
done >"$out/passes.log" 2>&1
echo "passes: in $(($(date +%s) - t0)) s" >>"$out/steps.txt"

# The same configurations on nine scenes: 0.9's run did this in 92 s on an H100.
bench 1920x1080 90 --grid full --size 1920x1080 --no-curves --no-temporal --no-glossy \
  --scenes mirror-room,thin-objects,spider-on-mirror,sky-heavy,mirror-walls,facing-mirror,wuson-as-mirror,sphere-over-mirror-32,glossy \
  --configs "$configs"

# The glossy study's time on a GPU: the stochastic mode against the cone blur (#40's 1.5x target,
# so far measured on llvmpipe only). 960x540 with 64 reference rays a pixel keeps the Embree
# reference to seconds; the error columns are noisier than the docs' 256-ray study.
bench glossy 50 --grid quick --size 64x36 --frames 10 --warmup 2 --scenes sky-heavy --no-curves --no-temporal \
  --glossy-scenes glossy,mirror-room@rough0.25,curved-mirror@rough0.3,facing-mirror@rough0.3 \
  --glossy-size 960x540 --glossy-samples 64 --glossy-frames 8

# Stereo on a GPU (#40's item 2): one context of two views against a context a view, where a
# frame's fixed commands weigh more than on llvmpipe. 1920x1080 a eye.
bench views 40 --grid quick --size 64x36 --frames 10 --warmup 2 --scenes sky-heavy --configs adaptive-l/high \
  --no-curves --no-temporal --no-glossy --views-scenes mirror-room,glossy,sky-heavy,thin-objects \
  --views-size 1920x1080

t0=$(date +%s)
limit=$(left)
[ "$limit" -gt 10 ] || limit=10
# Without the soak (a count-bounded run for leaks, CPU-side) and Mesa's shader-cache test: both run
# in CI, and on the GPU their minutes go to the others (0.9's run: 304 s were not enough for all).
SSLR_REQUIRE_GL=1 timeout "$limit" ctest --test-dir build/portable -L gpu -E "Soak|GlFreshCompile" -j16 --timeout 300 --output-on-failure \
  >"$out/gl-tests.log" 2>&1
echo "gl-tests: exit $? in $(($(date +%s) - t0)) s" >>"$out/steps.txt"

# Reports without their images (the CSVs, JSON and SVG plots are what the docs use).
tar -cJf "$out/bench.tar.xz" --exclude='*.png' --exclude='*.exr' bench
cat "$out/steps.txt"
