#!/usr/bin/env bash
# Packs the `portable` preset's tools and tests with the shared libraries they need beyond glibc,
# libstdc++ and the GL driver (Embree, TBB, tinyglTF, tinyexr, stb), so they run on another x86-64
# Linux machine with a GPU and no packages installed: docs/results.md's GPU figures were measured
# this way. Usage: docs/scripts/bundle.sh [OUT.tar.xz]   (default .gpu/bundle.tar.xz)
#
# On the GPU machine, from a checkout of the same commit:
#   tar xf bundle.tar.xz                      # build/portable/... and build/portable/lib/
#   export LD_LIBRARY_PATH=$PWD/build/portable/lib
#   build/portable/src/apps/sslr-bench --grid full --out bench-gpu
# The test executables carry the checkout's absolute path of this machine (for the golden images
# and the tools they start); link the checkout there, or run the tools alone.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-.gpu/bundle.tar.xz}
cmake --preset portable >/dev/null
cmake --build --preset portable
build=build/portable
bins=("$build/src/apps/sslr-bench" "$build/src/apps/sslr-render" "$build/tests/sslr_gl_tests" "$build/tests/sslr_cpu_tests")
rm -rf "$build/lib" && mkdir -p "$build/lib"
# Everything ldd resolves except the C runtime and the GL dispatch libraries, which the GPU
# machine's own system and driver provide (a newer libstdc++ there is compatible).
skip='/(libc|libm|libdl|librt|libpthread|libgcc_s|libstdc\+\+|libEGL|libGL|libGLX|libGLdispatch|libOpenGL|ld-linux-x86-64)\.so'
ldd "${bins[@]}" | awk '/=> \//{print $3}' | sort -u | grep -Ev "$skip" | while read -r lib; do
  cp -L "$lib" "$build/lib/"
done
mkdir -p "$(dirname "$out")"
# The tests' discovery files and CTest scripts come along so `ctest --test-dir build/portable` runs.
find "$build" \( -name '*.cmake' -o -name 'CTestTestfile.cmake' \) -path '*tests*' -print > "$build/bundle-files"
# What was built, and where: the GPU run names the commit it measured and links this checkout's
# path to its own so the tests find their files.
{
  echo "commit=$(git rev-parse HEAD)$(git diff --quiet HEAD -- src shaders tests CMakeLists.txt || echo -dirty)"
  echo "source-dir=$PWD"
} > "$build/bundle-info"
tar -cJf "$out" "${bins[@]}" "$build/lib" "$build/CTestTestfile.cmake" "$build/bundle-info" -T "$build/bundle-files"
echo "bundle.sh: $out ($(du -h "$out" | cut -f1)); libraries: $(ls "$build/lib" | tr '\n' ' ')"
