#!/usr/bin/env bash
# Builds the libFuzzer target with clang (AddressSanitizer + UndefinedBehaviorSanitizer) and
# runs it for SECONDS (default 600) with the malformed-scene corpus and the example scenes as
# seeds and the scene dictionary. Findings are written as crash-*/leak-*/timeout-* files in
# the work directory; add each to tests/corpus after fixing it.
#
#   tests/fuzz/run_fuzzer.sh [SECONDS] [JOBS]
set -euo pipefail
src="$(cd "$(dirname "$0")/../.." && pwd)"
seconds="${1:-600}" jobs="${2:-1}"
if ! command -v clang++-14 >/dev/null; then
  apt-get install -y --no-install-recommends clang-14 libclang-rt-14-dev >/dev/null
fi
build="$src/build-fuzz"
cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang-14 \
  -DCMAKE_CXX_COMPILER=clang++-14 -DNX_FUZZ=ON -DNX_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j"$(nproc)" --target scene_fuzzer >/dev/null
work="$build/fuzz-work"
mkdir -p "$work/corpus"
cp "$src"/tests/corpus/*.scn "$src"/scenes/*.scn "$work/corpus/" 2>/dev/null || true
cd "$work"
"$build/tests/fuzz/scene_fuzzer" -dict="$src/tests/fuzz/scene.dict" -max_total_time="$seconds" -max_len=8192 \
  -timeout=10 -rss_limit_mb=2048 -jobs="$jobs" -workers="$jobs" -print_final_stats=1 corpus
