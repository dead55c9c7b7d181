#!/bin/bash
# The OpenCL program builds for GPUs, with no GPU: for the feature mask of
# each scene in scenes/, benchmarks/gpu_resources compiles it for AMD
# gfx1030, gfx90a and gfx940 and for NVIDIA's PTX (clang-15, -Werror), and
# fails if one does not build. On gfx1030, render_frame for cornell.json and
# cornell_diffuse.json holds its registers: no VGPR spilled and at most
# 1 KB of scratch a work-item (docs/gpu.md).
#   tests/gpu_targets.sh path/to/trac0r_viewer
set -euo pipefail
viewer=$1
root=$(cd "$(dirname "$0")/.." && pwd)
out=$(mktemp)
trap 'rm -f "$out"' EXIT
/usr/bin/python3 "$root/benchmarks/gpu_resources/gpu_resources.py" --viewer "$viewer" --tsv >"$out"
for scene in cornell.json cornell_diffuse.json; do
    line=$(awk -F'\t' -v s="$scene" '$2 == s && $3 == "gfx1030" && $4 == "render_frame"' "$out")
    if [ -z "$line" ]; then
        echo "gpu_targets: no gfx1030 render_frame line for $scene" >&2
        exit 1
    fi
    echo "$line"
    spills=$(echo "$line" | cut -f7)
    scratch=$(echo "$line" | cut -f8)
    if [ "$spills" -ne 0 ] || [ "$scratch" -gt 1024 ]; then
        echo "gpu_targets: render_frame for $scene on gfx1030 spills $spills VGPRs and needs" \
            "$scratch B of scratch a work-item (at most 0 and 1024)" >&2
        exit 1
    fi
done
echo "gpu_targets: $(cut -f1,3 "$out" | sort -u | wc -l) programs (mask, AMD target) built, and their PTX"
