#!/bin/bash
# A glTF model with metallic-roughness, normal and emissive textures
# (KhronosGroup's ClearCoatTest, as Debian's assimp-testmodels ships it)
# rendered by trac0r and by Blender's glTF importer with Cycles, side by
# side in docs/gltf_compare.png (trac0r left, Blender right). Measurement only: needs Debian's blender
# and ImageMagick, and a built trac0r_viewer.
#
#   bash benchmarks/gltf_compare/run.sh [SPP]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
spp=${1:-128}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$root/build/trac0r_viewer" "$here/scene.json" --headless --spp "$spp" --output "$out/trac0r.png"
blender -b -P "$here/blender_render.py" -- "$out/blender.png" "$spp" >"$out/blender.log" 2>&1 ||
    { tail -20 "$out/blender.log" >&2; exit 1; }
convert "$out/trac0r.png" "$out/blender.png" +append "$root/docs/gltf_compare.png"
echo "wrote docs/gltf_compare.png"
