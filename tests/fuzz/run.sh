#!/usr/bin/env bash
# Builds the libFuzzer targets with clang 14 (ASan + UBSan) and runs each for
# a bounded time on a copy of its seed corpus (the built-in scenes; a few
# tables). A finding stops with libFuzzer's report and a non-zero exit.
# Usage: tests/fuzz/run.sh [SECONDS per target, default 30]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-30}
CXX=clang++-14 cmake -S . -B build-fuzz -DSYMPL_FUZZ=ON -DSYMPL_BUILD_TESTS=OFF -DSYMPL_BUILD_BENCH=OFF \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo
cmake --build build-fuzz -j2 --target fuzz_scene fuzz_check_table
rm -rf build-fuzz/corpus && mkdir -p build-fuzz/corpus/scene build-fuzz/corpus/table
cp src/scenes/*.toml build-fuzz/corpus/scene/
cp tests/fuzz/corpus_table/* build-fuzz/corpus/table/
build-fuzz/fuzz_scene -max_total_time="$seconds" -max_len=8192 -print_final_stats=1 build-fuzz/corpus/scene
build-fuzz/fuzz_check_table -max_total_time="$seconds" -max_len=4096 -print_final_stats=1 build-fuzz/corpus/table
