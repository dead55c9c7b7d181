#!/usr/bin/env bash
# Unpacks the models of PyPI's pybullet 3.2.7 wheel (its pybullet_data
# folder: robots, tables, trays, toys, a stadium, a checkered plane and
# 1000 random objects, 1117 OBJ files, 46 MTL files with a map_Kd) into a
# folder, for run.sh's $MODEL_CORPUS_DIRS. The wheel is downloaded with
# pip download (no install) and only pybullet_data is extracted from it (a
# wheel is a zip); nothing is installed.
#
#   benchmarks/model_corpus/pypi_models.sh DIR
#   MODEL_CORPUS_DIRS=DIR/pybullet/pybullet_data benchmarks/model_corpus/run.sh
#
# The wheel asked for is CPython 3.11's manylinux one, whatever the local
# Python: pybullet_data is the same in each. About 100 MB to download and
# 140 MB unpacked.
set -euo pipefail

if (($# != 1)); then
    echo "usage: $0 DIR" >&2
    exit 2
fi
dir=$1
mkdir -p "$dir/wheels" "$dir/pybullet"
python3 -m pip download pybullet==3.2.7 --no-deps --only-binary=:all: \
    --python-version 3.11 --implementation cp --abi cp311 \
    --platform manylinux_2_17_x86_64 -d "$dir/wheels"
wheels=("$dir"/wheels/pybullet-3.2.7-*.whl)
wheel=${wheels[0]}
python3 - "$wheel" "$dir/pybullet" <<'EOF'
import sys
import zipfile

with zipfile.ZipFile(sys.argv[1]) as wheel:
    members = [m for m in wheel.namelist() if m.startswith("pybullet_data/")]
    wheel.extractall(sys.argv[2], members)
EOF
echo "unpacked $(find "$dir/pybullet/pybullet_data" -type f | wc -l) files of $(basename "$wheel")" \
    "under $dir/pybullet/pybullet_data" >&2
