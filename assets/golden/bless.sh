#!/usr/bin/env bash
# Re-blesses the golden images from the current build (run after an intended visual change and
# look at the result before committing). Usage: assets/golden/bless.sh [build-dir]
set -euo pipefail
build=${1:-build/release}
SSLR_BLESS=1 "$build/tests/sslr_gl_tests" --gtest_filter='Golden.*'
echo "blessed: $(dirname "$0")/mirror-room.exr ($(cat "$(dirname "$0")/mirror-room.renderer.txt"))"
