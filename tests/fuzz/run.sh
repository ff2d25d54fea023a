#!/usr/bin/env bash
# Builds the libFuzzer targets with clang 14 (ASan + UBSan) and runs each for
# a bounded time on a copy of its seed corpus (the built-in scenes; a few
# tables; a checkpoint of each of fuzz_checkpoint's scenes, which it writes
# itself). A finding stops with libFuzzer's report and a non-zero exit.
# Usage: tests/fuzz/run.sh [SECONDS per target, default 30] [BUILD_DIR]
# BUILD_DIR: a tree configured with clang 14 and -DSYMPL_FUZZ=ON (CI's
# sanitizer tree, whose library is then compiled once for both); without it,
# build-fuzz is configured here with the fuzz targets alone.
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-30}
build=${2:-}
if [ -z "$build" ]; then
    build=build-fuzz
    CXX=clang++-14 cmake -S . -B "$build" -DSYMPL_FUZZ=ON -DSYMPL_BUILD_TESTS=OFF -DSYMPL_BUILD_BENCH=OFF \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo
fi
grep -q '^SYMPL_FUZZ:BOOL=ON' "$build/CMakeCache.txt" || { echo "run.sh: $build is not configured with -DSYMPL_FUZZ=ON" >&2; exit 2; }
cmake --build "$build" -j2 --target fuzz_scene fuzz_check_table fuzz_checkpoint
rm -rf "$build/corpus" && mkdir -p "$build/corpus/scene" "$build/corpus/table"
cp src/scenes/*.toml "$build/corpus/scene/"
cp tests/fuzz/corpus_table/* "$build/corpus/table/"
# The checkpoint target's seeds: a real checkpoint of each of its scenes.
SYMPL_FUZZ_SEEDS="$build/corpus/checkpoint" "$build/fuzz_checkpoint"
"$build/fuzz_scene" -max_total_time="$seconds" -max_len=8192 -print_final_stats=1 "$build/corpus/scene"
"$build/fuzz_check_table" -max_total_time="$seconds" -max_len=4096 -print_final_stats=1 "$build/corpus/table"
# A resumed run is short: one taking 20 s has been sent somewhere it should not go.
"$build/fuzz_checkpoint" -max_total_time="$seconds" -max_len=16384 -timeout=20 -print_final_stats=1 "$build/corpus/checkpoint"
