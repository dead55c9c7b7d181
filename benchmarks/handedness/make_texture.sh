#!/bin/sh
# Draws uv_texture.png, the quad's map_Kd: "U" on the left half, "V" on
# the right, a blue triangle in the top-left corner and an arrow along the
# bottom pointing right, so a mirrored or upside-down picture shows at once.
# Needs ImageMagick (Debian's imagemagick) and the DejaVu fonts; the PNG is
# committed, so a render needs neither.
set -eu
cd "$(dirname "$0")"
font=/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf
convert -size 256x192 xc:white \
  -fill none -stroke black -strokewidth 4 -draw 'rectangle 2,2 253,189' \
  -stroke none -fill '#1f4fd0' -draw 'polygon 4,4 64,4 4,64' \
  -fill black -font "$font" -pointsize 120 \
  -draw "text 18,140 'U'" -draw "text 136,140 'V'" \
  -fill '#148a28' -draw 'rectangle 40,160 196,172' \
  -draw 'polygon 192,150 230,166 192,182' \
  -strip -colors 16 -define png:compression-level=9 PNG8:uv_texture.png
echo "wrote $(pwd)/uv_texture.png"
