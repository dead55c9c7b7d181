#!/bin/bash
# Two versions of the kernel headers (trac0r/kernel) timed side by side in
# one process, on one thread: frames of A and B alternated, and the median
# and quartiles over the pairs of B's frame time over A's, with whether the
# two accumulated the same image. Each version is linked at four code
# offsets, which the pairs take in turn, so that where the linker puts a hot
# loop does not decide the comparison. A version against itself gives
# medians within half a per cent of 1, where alternated runs of two builds
# differ by a few per cent (docs/performance.md, "Measuring side by side").
#
#   benchmarks/ab_kernels.sh A B [SCENE.json] [--accel flat|bvh]
#       [--integrator naive|nee] [--sampler random|sobol] [--pairs N]
#       [--size W H]
#
# A and B: git revisions (HEAD, main~2, a commit) or directories that hold
# trac0r/kernel (. is the working tree). Defaults: scenes/cornell.json, bvh,
# naive, random, 150 pairs after one warm-up pair, 200 x 150. Both versions must
# have trac0r/kernel/tile.h and lay out the packed buffers as this tree packs
# them (checked). Compiled with the Release flags (and -march=native where
# the build has TRAC0R_NATIVE=ON) against the library in build/ (or
# $TRAC0R_BUILD): build it first.
set -euo pipefail
usage() { sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "$0"; }
case "${1:-}" in
    -h | --help) usage; exit 0 ;;
esac
if [ $# -lt 2 ]; then
    echo "ab_kernels.sh: expected two versions, A and B (see --help)" >&2
    exit 2
fi
a=$1
b=$2
shift 2
root=$(cd "$(dirname "$0")/.." && pwd)
build=${TRAC0R_BUILD:-$root/build}
if [ ! -f "$build/libtrac0r.a" ] || [ ! -f "$build/CMakeCache.txt" ]; then
    echo "ab_kernels.sh: no library in $build: build the project first (or set TRAC0R_BUILD)" >&2
    exit 1
fi
cxx=${CXX:-g++}
flags=(-O3 -DNDEBUG -ffp-contract=off -std=c++14 -Wall -Wextra)
if grep -q '^TRAC0R_NATIVE:BOOL=ON' "$build/CMakeCache.txt"; then
    flags+=(-march=native)
fi
# GCC keeps the padding (variant.cpp) ahead of the code only in source
# order (checked: each offset moves the kernel's functions by 16 bytes);
# clang has no such flag and puts top-level asm first (not checked).
order=()
if "$cxx" -fno-toplevel-reorder -x c++ -c /dev/null -o /dev/null 2>/dev/null; then
    order=(-fno-toplevel-reorder)
fi
libs=(-ltinyobjloader -lassimp -ltinyexr -lstb)
if grep -q '^TRAC0R_OPENCL:BOOL=ON' "$build/CMakeCache.txt"; then
    libs+=(-lOpenCL)
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The kernel headers of version $1 into $work/$2/trac0r/kernel.
fetch() {
    local version=$1 name=$2
    mkdir -p "$work/$name/trac0r"
    if [ -d "$version" ]; then
        if [ ! -d "$version/trac0r/kernel" ]; then
            echo "ab_kernels.sh: $version has no trac0r/kernel" >&2
            exit 2
        fi
        cp -r "$version/trac0r/kernel" "$work/$name/trac0r/"
    elif git -C "$root" rev-parse --verify --quiet "$version^{commit}" >/dev/null; then
        git -C "$root" archive "$version" trac0r/kernel | tar -x -C "$work/$name"
    else
        echo "ab_kernels.sh: '$version' is neither a directory nor a git revision" >&2
        exit 2
    fi
    # variant.cpp calls render_tile with a TileRect (tile_grid.h).
    if [ ! -f "$work/$name/trac0r/kernel/tile_grid.h" ]; then
        echo "ab_kernels.sh: $version has no trac0r/kernel/tile_grid.h (it predates the" \
            "kernel's split by concept, which this tool's variant.cpp needs)" >&2
        exit 2
    fi
}

# Version $1's headers as namespace trac0r::kernel_$2$3, compiled with its
# code 16 x $3 bytes further on (variant.cpp).
compile() {
    local version=$1 name=$2 layout=$3
    local dir=$work/$name$layout
    cp -r "$work/$name" "$dir"
    sed -i "s/^\(    namespace \)kernel {/\1kernel_$name$layout {/" "$dir/trac0r/kernel/compat.h"
    if ! grep -q "namespace kernel_$name$layout {" "$dir/trac0r/kernel/compat.h"; then
        echo "ab_kernels.sh: could not rename the kernel namespace in $version's compat.h" >&2
        exit 1
    fi
    "$cxx" "${flags[@]}" "${order[@]}" -I"$dir" -DAB_NAMESPACE="kernel_$name$layout" \
        -DAB_PAD=$((64 + 16 * layout)) -c "$root/benchmarks/ab_kernels/variant.cpp" \
        -o "$work/$name$layout.o"
}

fetch "$a" a
fetch "$b" b
echo "ab_kernels.sh: compiling A ($a) and B ($b), each at four code offsets" >&2
pids=()
for layout in 0 1 2 3; do
    compile "$a" a $layout &
    pids+=($!)
    compile "$b" b $layout &
    pids+=($!)
done
"$cxx" "${flags[@]}" -I"$root" -isystem /usr/include/stb -c "$root/benchmarks/ab_kernels/main.cpp" \
    -o "$work/main.o"
for pid in "${pids[@]}"; do
    wait "$pid"
done
"$cxx" -fopenmp "$work/main.o" "$work"/a?.o "$work"/b?.o "$build/libtrac0r.a" "${libs[@]}" \
    -o "$work/ab_kernels"
"$work/ab_kernels" "$@"
