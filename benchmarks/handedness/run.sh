#!/bin/bash
# Renders the same scene (uv_quad.obj: a quad with the letters U and V,
# red_cube.obj: a red cube at x = +1.4, seen from (0, 0, 3) looking along
# -z with y up) with Blender's Cycles and with trac0r, and puts the two
# pictures side by side with labels. Both should show the letters readable,
# the blue corner top left, the arrow pointing right and the cube on the
# right (docs/scene-format.md, "The camera convention").
#
#   benchmarks/handedness/run.sh [OUT_DIR] [SPP]
#
# OUT_DIR (default out/handedness) gets blender.png, trac0r.png and
# side_by_side.png; SPP defaults to 64. Needs build/trac0r_viewer (or
# $TRAC0R_VIEWER), Debian's blender and imagemagick. Run from anywhere.
set -euo pipefail
case "${1:-}" in
    -h | --help) sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "$0"; exit 0 ;;
esac
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out=${1:-$root/out/handedness}
spp=${2:-64}
viewer=${TRAC0R_VIEWER:-$root/build/trac0r_viewer}
for tool in blender convert; do
    command -v "$tool" > /dev/null ||
        { echo "run.sh: $tool not found (apt-get install blender imagemagick)" >&2; exit 1; }
done
[ -x "$viewer" ] ||
    { echo "run.sh: $viewer not found: build trac0r_viewer first" >&2; exit 1; }
mkdir -p "$out"
out=$(cd "$out" && pwd)

"$viewer" "$here/scene.json" --headless --spp "$spp" --width 320 --height 240 \
    --output "$out/trac0r.png" 2> "$out/trac0r.log" ||
    { cat "$out/trac0r.log" >&2; exit 1; }
blender -b -P "$here/blender_render.py" -- "$out/blender.png" "$spp" \
    > "$out/blender.log" 2>&1 ||
    { tail -20 "$out/blender.log" >&2; exit 1; }
[ -f "$out/blender.png" ] ||
    { tail -20 "$out/blender.log" >&2; echo "run.sh: Blender wrote no picture" >&2; exit 1; }

label() {  # label IN OUT TEXT: a dark strip with TEXT above the picture
    convert "$1" -background '#202020' -fill white -gravity north \
        -splice 0x22 -font DejaVu-Sans -pointsize 14 -annotate +0+3 "$3" "$2"
}
label "$out/blender.png" "$out/blender_labelled.png" "Blender $(blender --version 2>/dev/null | head -1 | cut -d' ' -f2) (Cycles, $spp spp)"
label "$out/trac0r.png" "$out/trac0r_labelled.png" "trac0r ($spp spp)"
# A 2-pixel grey gap between the halves.
convert "$out/blender_labelled.png" \
    \( "$out/trac0r_labelled.png" -background '#808080' -gravity west -splice 2x0 \) \
    +append -strip "$out/side_by_side.png"
rm "$out/blender_labelled.png" "$out/trac0r_labelled.png"
echo "wrote $out/side_by_side.png"
