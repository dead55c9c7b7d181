#!/bin/bash
# Instructions a path of the CPU backend's frame executes, counted by
# callgrind (one thread): a measure that the machine's load cannot move,
# for comparing kernel changes. Needs valgrind (Debian package valgrind).
#
#   benchmarks/instructions_per_path.sh [SCENE.json] [flat|bvh] [SPP]
#
# Renders SCENE (default scenes/cornell.json) at 400 x 300 with SPP samples
# per pixel (default 2) and prints the instructions of
# CpuBackend::render_frame over the paths traced (one per pixel per sample).
set -euo pipefail
scene=${1:-scenes/cornell.json}
accel=${2:-bvh}
spp=${3:-2}
viewer=${TRAC0R_VIEWER:-build/trac0r_viewer}
if ! command -v valgrind >/dev/null; then
    echo "instructions_per_path.sh: needs valgrind (apt-get install valgrind)" >&2
    exit 1
fi
out=$(mktemp)
trap 'rm -f "$out" "$out.png"' EXIT
OMP_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file="$out" "$viewer" "$scene" \
    --headless --backend cpu --accel "$accel" --width 400 --height 300 --spp "$spp" \
    --output "$out.png" >/dev/null 2>&1
callgrind_annotate --inclusive=yes "$out" 2>/dev/null |
    awk -v paths=$((400 * 300 * spp)) -v scene="$scene" -v accel="$accel" '
        /CpuBackend::render_frame.*omp_fn/ { gsub(",", "", $1); n = $1 }
        END {
            if (n == 0) { print "instructions_per_path.sh: no render_frame in the profile" > "/dev/stderr"; exit 1 }
            printf "%s, %s: %.0f instructions a path\n", scene, accel, n / paths
        }'
