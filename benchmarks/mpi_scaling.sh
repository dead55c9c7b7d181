#!/usr/bin/env bash
# Strong scaling on one machine: the same render (scene, seed, spp, size)
# by one trac0r_viewer process of 2 threads and by trac0r_mpi on 2 ranks of
# 1 thread, alternated ROUNDS times so that both see the same load. Prints
# each run's render seconds (the "rendered ... in S s" line: loading and
# MPI's start are left out) and wall seconds, then the ratios of the
# medians (ranks' time / one process's).
# Usage: benchmarks/mpi_scaling.sh [SCENE] [SPP] [ROUNDS] [BUILD]
# e.g.   benchmarks/mpi_scaling.sh scenes/cornell_diffuse.json 32 3
set -euo pipefail
scene=${1:-scenes/cornell_diffuse.json}
spp=${2:-32}
rounds=${3:-3}
build=${4:-build}
for p in "$build/trac0r_viewer" "$build/trac0r_mpi"; do
    [ -x "$p" ] || { echo "mpi_scaling.sh: $p not found (build first; MPI: libopenmpi-dev)" >&2; exit 1; }
done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
common=("$scene" --width 800 --height 600 --spp "$spp" --seed 3)
# One run: "render_seconds wall_seconds".
run() {
    local start end
    start=$(date +%s.%N)
    "$@" 2>"$out/err" >/dev/null || { cat "$out/err" >&2; exit 1; }
    end=$(date +%s.%N)
    local render
    render=$(sed -n 's/^rendered .* in \([0-9.]*\) s .*/\1/p' "$out/err")
    echo "$render $(awk -v a="$start" -v b="$end" 'BEGIN {printf "%.2f", b - a}')"
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
: >"$out/one"
: >"$out/two"
echo "round  one process, 2 threads: render s, wall s   2 ranks, 1 thread each: render s, wall s"
for r in $(seq "$rounds"); do
    a=$(run "$build/trac0r_viewer" "${common[@]}" --headless --threads 2 --output "$out/one.pfm")
    b=$(run mpirun -q --oversubscribe -n 2 "$build/trac0r_mpi" "${common[@]}" --threads 1 \
        --output "$out/two.pfm")
    echo "$a" >>"$out/one"
    echo "$b" >>"$out/two"
    echo "$r      $a                                     $b"
done
one_render=$(cut -d' ' -f1 "$out/one" | median)
two_render=$(cut -d' ' -f1 "$out/two" | median)
one_wall=$(cut -d' ' -f2 "$out/one" | median)
two_wall=$(cut -d' ' -f2 "$out/two" | median)
awk -v a="$one_render" -v b="$two_render" -v c="$one_wall" -v d="$two_wall" 'BEGIN {
    printf "median render: %.2f s vs %.2f s, ratio %.3f; wall: %.2f s vs %.2f s, ratio %.3f\n",
        a, b, b / a, c, d, d / c }'
