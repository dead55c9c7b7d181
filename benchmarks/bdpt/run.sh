#!/bin/sh
# Bidirectional path tracing against next-event estimation path tracing,
# side by side (bench_convergence interleaves their frames): the time each
# takes to an error, on the CPU backend with Sobol samples.
#   cornell.json (the thesis' scene) at 400 x 300: the whole image, and
#     the caustic alone (the floor under the glass sphere, --region);
#   caustic.json (here: a lamp inside a glass sphere) at 400 x 300;
#   cornell_diffuse.json at 400 x 300 (what BDPT costs where it does not
#     help; paths of 64 vertices, as the scene says);
#   many_lights.json at 200 x 150, by relative MSE (64 bulbs: BDPT's light
#     samples by the light tree, as NEE's, and by power).
# The references are BDPT renders of 4096 samples a pixel (another seed),
# kept in OUT (cornell_diffuse.json's: bench_convergence's own NEE render
# of 8192, cached in OUT/cache; many_lights.json's: an NEE render of 4096,
# as docs/performance.md's); docs/bdpt.md explains the figures.
#
#   benchmarks/bdpt/run.sh [OUT]      (from the repository's root, after
#                                      building into build/)
set -eu
build=${BUILD:-build}
out=${1:-bdpt_results}
mkdir -p "$out"
viewer="$build/trac0r_viewer"
bench="$build/benchmarks/bench_convergence"

reference() {  # SCENE NAME
    if [ ! -f "$out/$2.pfm" ]; then
        "$viewer" "$1" --headless --integrator bdpt --width 400 --height 300 --spp 4096 \
            --seed 5 -o "$out/$2.pfm"
    fi
}

compare() {  # NAME SCENE [bench_convergence options...]
    name=$1
    scene=$2
    shift 2
    "$bench" "$scene" --width 400 --height 300 \
        --config integrator=nee,sampler=sobol --config integrator=bdpt,sampler=sobol \
        --csv "$out/$name.csv" --cache "$out/cache" "$@" > "$out/$name.txt"
    grep -A2 "^Time to" "$out/$name.txt"
}

reference scenes/cornell.json cornell_reference
reference benchmarks/bdpt/caustic.json caustic_reference
compare cornell scenes/cornell.json --max-spp 1024 --target-rmse 0.035 \
    --reference "$out/cornell_reference.pfm"
compare cornell_caustic scenes/cornell.json --max-spp 1024 --target-rmse 0.08 \
    --region 164,280,236,300 --reference "$out/cornell_reference.pfm"
compare caustic benchmarks/bdpt/caustic.json --max-spp 256 --target-rmse 0.15 \
    --reference "$out/caustic_reference.pfm"
compare cornell_diffuse scenes/cornell_diffuse.json --max-spp 512 --target-rmse 0.015
if [ ! -f "$out/many_lights_reference.pfm" ]; then
    "$viewer" scenes/many_lights.json --headless --width 200 --height 150 --spp 4096 \
        --light-sampler tree --seed 99 -o "$out/many_lights_reference.pfm"
fi
"$bench" scenes/many_lights.json --width 200 --height 150 --max-spp 1024 \
    --target-relmse 0.02 --reference "$out/many_lights_reference.pfm" \
    --config integrator=nee,sampler=sobol \
    --config integrator=bdpt,sampler=sobol,light_sampler=power \
    --config integrator=bdpt,sampler=sobol,light_sampler=tree \
    --csv "$out/many_lights.csv" > "$out/many_lights.txt"
grep -A3 "^To a relative MSE" "$out/many_lights.txt"
