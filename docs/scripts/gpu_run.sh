#!/usr/bin/env bash
# The scripted GPU run behind docs/results.md's GPU section: one command on a lent GPU machine,
# from a checkout of the measured commit with `docs/scripts/bundle.sh`'s archive at
# .gpu/bundle.tar.xz. Order: the benchmark grids first (960x540 with the cost curves, 1920x1080,
# then the default and the tutorial's demo configuration at 3840x2160), the GL tests on the GPU's
# driver last; each step has its own time limit so a slow step cannot take the others' results.
# Results go to $OUT (default gpu-out): one archive of the CSV/JSON/plots and the logs.
# Usage: docs/scripts/gpu_run.sh [SECONDS_FOR_ALL]   (default 520)
set -u
cd "$(dirname "$0")/../.."
out=${OUT:-gpu-out}
mkdir -p "$out"
budget=${1:-520}
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
bench 960x540 200 --grid full --no-temporal --no-glossy
bench 1920x1080 130 --grid full --size 1920x1080 --no-curves --no-temporal --no-glossy
bench 3840x2160 90 --grid full --size 3840x2160 --no-curves --no-temporal --no-glossy \
  --scenes mirror-room,grazing-plane,thin-objects,glossy,sky-heavy \
  --configs "adaptive-l/high,adaptive-l/high-half,adaptive-l/high-no-fallback,hiz/steps128,dda/stride4-thick0.5,position-buffer/tutorial (res0.3-steps5-dist8)"

t0=$(date +%s)
limit=$(left)
[ "$limit" -gt 10 ] || limit=10
SSLR_REQUIRE_GL=1 timeout "$limit" ctest --test-dir build/portable -L gpu -j8 --timeout 300 --output-on-failure \
  >"$out/gl-tests.log" 2>&1
echo "gl-tests: exit $? in $(($(date +%s) - t0)) s" >>"$out/steps.txt"

# Reports without their images (the CSVs, JSON and SVG plots are what the docs use).
tar -cJf "$out/bench.tar.xz" --exclude='*.png' --exclude='*.exr' bench
cat "$out/steps.txt"
