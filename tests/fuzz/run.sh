#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tests/fuzz) with clang and runs each for
# SECONDS (default 60) from a seed corpus: the scenes and meshes in scenes/
# and tests/fuzz/corpus/. Fails on any crash, hang (a unit over 10 s), leak,
# memory blow-up (2 GB) or sanitizer report; the input that did it is left in
# build-fuzz/artifacts/. Usage: tests/fuzz/run.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-60}
build=build-fuzz
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DTRAC0R_FUZZ=ON -DTRAC0R_BUILD_TESTS=OFF \
    -DTRAC0R_PYTHON=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$build" -j2 --target fuzz_scene fuzz_obj fuzz_mesh fuzz_replay
mkdir -p "$build/artifacts"
# Leaks inside the libraries we call, not ours (tests/lsan.supp says which).
export LSAN_OPTIONS=suppressions=$PWD/tests/lsan.supp:print_suppressions=0
run() {  # harness seed-files...
    local harness=$1
    shift
    local corpus="$build/corpus/$harness"
    rm -rf "$corpus" && mkdir -p "$corpus" && cp "$@" "$corpus/"
    echo "fuzz: $harness for $seconds s from $# seed files"
    "$build/tests/fuzz/$harness" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
        -max_len=65536 -print_final_stats=1 -artifact_prefix="$build/artifacts/$harness-" \
        "$corpus" 2>"$build/$harness.log" || {
        tail -n 60 "$build/$harness.log"
        echo "fuzz: $harness FAILED (input in $build/artifacts/)"
        return 1
    }
    grep -E '^stat::number_of_executed_units' "$build/$harness.log" | sed "s/^/fuzz: $harness /"
}
run fuzz_scene scenes/*.json
run fuzz_obj scenes/meshes/*.obj
# fuzz_mesh: PLY and glTF through assimp, which reads each file in a child
# process of its own (trac0r/isolated_call.h). assimp 5.2's own readers
# crash on some malformed files (a heap overrun in the PLY reader, a null
# dereference in the glTF one: tests/fuzz/findings/assimp_gltf_segv.glb);
# in the child that is the loader's clear error, not a finding, and the
# child's sanitizer report, if any, goes to the log only (the child clears
# the sanitizers' death callback, libFuzzer's included, and resets the
# crash signals). What can fail here is trac0r's own side: the pipe, the
# checks of what the child sends back, the shapes made of it. The child's
# code coverage does not reach libFuzzer (its counters are the child's
# copy), so the fuzzer is guided by the parent's code only.
run fuzz_mesh tests/fuzz/corpus/mesh/*
run fuzz_replay tests/fuzz/corpus/replay/*
echo "fuzz: all harnesses ran $seconds s without a finding"
