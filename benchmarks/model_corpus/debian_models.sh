#!/usr/bin/env bash
# Unpacks the Debian 12 packages that hold real OBJ + MTL models into a
# folder, for run.sh's $MODEL_CORPUS_DIRS. The packages are downloaded
# (apt-get download: no install, no root needed beyond apt's cache) and
# extracted with dpkg-deb; nothing is installed.
#
#   benchmarks/model_corpus/debian_models.sh DIR
#   MODEL_CORPUS_DIRS="$(ls -d DIR/*/usr)" benchmarks/model_corpus/run.sh
#
# The packages: every one of Debian 12's whose files include a .mtl
# (apt-file search -x '\.mtl$'), but assimp-testmodels (run.sh's own
# corpus) and the documentation and Sage packages. About 1.2 GB to
# download (redeclipse-data is 860 MB of it) and 1.5 GB unpacked.
set -euo pipefail

if (($# != 1)); then
    echo "usage: $0 DIR" >&2
    exit 2
fi
dir=$1
packages=(bouncy embree-tools gltron lazpaint-qt5 neverball-common python3-pyglet
    python3-tinyobjloader redeclipse-data spring-common stellarium-data sumo-tools)
mkdir -p "$dir/debs"
(cd "$dir/debs" && apt-get download "${packages[@]}")
for deb in "$dir"/debs/*.deb; do
    name=$(basename "$deb" | cut -d_ -f1)
    mkdir -p "$dir/$name"
    dpkg-deb -x "$deb" "$dir/$name"
done
echo "unpacked ${#packages[@]} packages under $dir" >&2
