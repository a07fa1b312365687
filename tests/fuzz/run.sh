#!/usr/bin/env bash
# Builds the glTF/GLB loader fuzzer (the `fuzz` preset: clang, libFuzzer, ASan + UBSan) and runs
# it for a bounded time: tests/fuzz/run.sh [SECONDS=120] [JOBS=1].
# Seeds: Debian's assimp-testmodels glTF 2.0 files (a .gltf with external buffers or images gets
# them embedded as data: URIs by embed_external.py, so the seed loads as the model does), the
# built-in scenes as glTF (assets/scenes), the crafted seeds in tests/fuzz/seeds (strips, fans, a
# texture, a camera, a flattened node, nested extras) and every input kept in tests/fuzz/regressions. A crashing input is copied into
# tests/fuzz/regressions (replayed by the `Gltf.FuzzRegressions*` test in every build) and the
# script fails. Prints libFuzzer's final statistics (executions, coverage) at the end.
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-120}
jobs=${2:-1}
cmake --preset fuzz > /dev/null
cmake --build --preset fuzz
fuzzer=build/fuzz/tests/fuzz/sslr-fuzz-gltf
work=$(mktemp -d /tmp/sslr-fuzz-run.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/corpus" "$work/seeds" "$work/artifacts"
n=0
for dir in /usr/share/assimp/models/glTF2 assets/scenes tests/fuzz/seeds tests/fuzz/regressions; do
  [ -d "$dir" ] || continue
  while IFS= read -r -d '' f; do
    seed="$work/seeds/seed-$n-$(basename "$f")"
    case "$f" in
      *.gltf) tests/fuzz/embed_external.py "$f" "$seed" || cp "$f" "$seed" ;;
      *) cp "$f" "$seed" ;;
    esac
    if [ "$(stat -c %s "$seed")" -le 262144 ]; then n=$((n + 1)); else rm -f "$seed"; fi
  done < <(find "$dir" -type f \( -iname '*.gltf' -o -iname '*.glb' -o -path '*regressions/*' \) ! -name README.md -print0)
done
echo "fuzz: $n seed files, ${seconds}s, $jobs job(s)"
status=0
# From inside the scratch folder: in jobs mode libFuzzer writes its fuzz-N.log files to the
# current directory.
root=$PWD
cd "$work"
"$root/$fuzzer" -max_total_time="$seconds" -max_len=262144 -timeout=20 -rss_limit_mb=4096 -jobs="$jobs" -workers="$jobs" \
  -dict="$root/tests/fuzz/gltf.dict" -artifact_prefix="$work/artifacts/" -print_final_stats=1 \
  "$work/corpus" "$work/seeds" 2>&1 | tee "$work/log" | grep -E "^#[0-9]+[[:space:]]+(INITED|DONE)|stat::|ERROR|SUMMARY|loader promise" || true
if grep -qE "ERROR: (libFuzzer|AddressSanitizer|UndefinedBehaviorSanitizer)|loader promise broken|SUMMARY: " "$work/log"; then status=1; fi
for a in "$work"/artifacts/*; do
  [ -e "$a" ] || continue
  name="$(basename "$a")"
  cp "$a" "$root/tests/fuzz/regressions/$name"
  echo "fuzz: crashing input kept as tests/fuzz/regressions/$name"
  status=1
done
exit $status
