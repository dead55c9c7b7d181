#!/bin/bash
# trac0r against Mitsuba 3 and Blender's Cycles (issue 48): the render time
# each needs to reach RMSE 0.0129 on scenes/cornell_diffuse.json at 800 x 600
# with 2 CPU threads. Measurement only, outside the build and the tests.
#
#   benchmarks/peers/run.sh [--out DIR] [--reference PATH] [--ref-spp N]
#       [--rounds R] [--threads T] [--width W] [--height H] [--target E]
#       [--spp-trac0r N] [--spp-mitsuba N] [--spp-cycles N]
#
# 1. The reference: Mitsuba (llvm_ad_rgb, multijitter, all threads), the
#    mean of two renders of --ref-spp / 2 samples (default 8192 in all) with
#    seeds 1001 and 1002, kept at PATH (default DIR/reference_mitsuba_WxH_
#    Nspp.pfm; DIR defaults to out/peers) with its halves beside it
#    (PATH.half1.pfm, PATH.half2.pfm); a later run with the same PATH
#    reuses it. Its own noise, MSE(half 1, half 2) / 4, is printed and taken
#    out of every render's MSE (table.py says why that holds).
# 2. R rounds (default 3), each trac0r, Mitsuba, Cycles in turn, seed = the
#    round, T threads (default 2), at sample counts near the target (trac0r
#    470: NEE, Sobol, its defaults; Mitsuba 432: llvm_ad_rgb, multijitter;
#    Cycles 256: CPU, its default progressive multi-jitter). Times: trac0r's
#    "rendered ... in X s"; Mitsuba's render without kernel compilation;
#    Cycles' bpy.ops.render.render() (see each script's header). Start-up
#    and scene loading are left out of all three.
# 3. The table (benchmarks/peers/table.py): per renderer the RMSE, the
#    median time and the time to the target, time x (RMSE / E)^2, and the
#    ratios of trac0r's time to the others'.
#
# Needs: build/trac0r_viewer (or $TRAC0R_VIEWER); a Python with Mitsuba 3
# and numpy ($PYTHON, default python3; `pip install mitsuba numpy`, e.g. in
# a venv); libLLVM for Mitsuba's LLVM variant (`apt-get install -y
# libllvm19`, or $DRJIT_LIBLLVM_PATH); Debian's Blender 3.4 (`apt-get
# install blender`, or $BLENDER). Logs and images go to DIR. About 10
# minutes for the reference on 2 cores, then about 2 minutes a round.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)

out=$root/out/peers
reference=
ref_spp=8192
rounds=3
threads=2
width=800
height=600
target=0.0129
spp_trac0r=470
spp_mitsuba=432
spp_cycles=256
while [ $# -gt 0 ]; do
    case "$1" in
        -h | --help) sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "$0"; exit 0 ;;
        --out) out=$2 ;;
        --reference) reference=$2 ;;
        --ref-spp) ref_spp=$2 ;;
        --rounds) rounds=$2 ;;
        --threads) threads=$2 ;;
        --width) width=$2 ;;
        --height) height=$2 ;;
        --target) target=$2 ;;
        --spp-trac0r) spp_trac0r=$2 ;;
        --spp-mitsuba) spp_mitsuba=$2 ;;
        --spp-cycles) spp_cycles=$2 ;;
        *) echo "run.sh: unknown option $1 (--help)" >&2; exit 2 ;;
    esac
    [ $# -ge 2 ] || { echo "run.sh: $1 needs a value" >&2; exit 2; }
    shift 2
done
if [ $((ref_spp % 2)) -ne 0 ] || [ "$ref_spp" -lt 2 ]; then
    echo "run.sh: --ref-spp must be even (two halves)" >&2; exit 2
fi

scene=$root/scenes/cornell_diffuse.json
viewer=${TRAC0R_VIEWER:-$root/build/trac0r_viewer}
python=${PYTHON:-python3}
blender=${BLENDER:-blender}
fail() { echo "run.sh: $*" >&2; exit 1; }

# What it needs, each with how to get it.
[ -x "$viewer" ] || fail "$viewer not found: build trac0r_viewer first (or set TRAC0R_VIEWER)"
command -v "$python" > /dev/null || fail "$python not found (set PYTHON)"
"$python" -c 'import numpy' 2> /dev/null ||
    fail "$python has no numpy: pip install mitsuba numpy (or set PYTHON to a venv's python)"
"$python" -c 'import mitsuba' 2> /dev/null ||
    fail "$python has no Mitsuba 3: pip install mitsuba numpy (or set PYTHON to a venv's python)"
if [ -z "${DRJIT_LIBLLVM_PATH:-}" ] && [ ! -e /usr/lib/x86_64-linux-gnu/libLLVM-19.so ] &&
    [ ! -e /usr/lib/x86_64-linux-gnu/libLLVM.so ]; then
    fail "no libLLVM for Mitsuba's llvm_ad_rgb: apt-get install -y libllvm19 (or set DRJIT_LIBLLVM_PATH)"
fi
"$python" -c "import sys; sys.path.insert(0, '$root/benchmarks/mitsuba')
import cornell_diffuse as c; c.load_mitsuba('llvm_ad_rgb')" > /dev/null 2>&1 ||
    fail "Mitsuba's llvm_ad_rgb variant does not load (libLLVM: apt-get install -y libllvm19, or set DRJIT_LIBLLVM_PATH)"
command -v "$blender" > /dev/null ||
    fail "$blender not found: apt-get install blender (Debian 12's 3.4), or set BLENDER"
"$blender" -b --factory-startup --python-exit-code 1 --python-expr 'import numpy' \
    > /dev/null 2>&1 || fail "$blender cannot run Python with numpy (apt-get install python3-numpy)"

mkdir -p "$out"
out=$(cd "$out" && pwd)
[ -n "$reference" ] || reference=$out/reference_mitsuba_${width}x${height}_${ref_spp}spp.pfm
half1=$reference.half1.pfm
half2=$reference.half2.pfm
mitsuba() { "$python" "$root/benchmarks/mitsuba/cornell_diffuse.py" --scene "$scene" \
    --width "$width" --height "$height" --sampler multijitter "$@"; }

echo "trac0r: $("$viewer" --version 2> /dev/null | head -1 || true) ($viewer)"
echo "Mitsuba: $("$python" -c 'import mitsuba, drjit; print(mitsuba.__version__, "drjit", drjit.__version__)'), llvm_ad_rgb"
echo "Blender: $("$blender" --version 2> /dev/null | head -1), Cycles CPU"
echo "CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
echo "$(date -u '+%Y-%m-%d %H:%M UTC'), ${width}x${height}, $threads threads, $rounds rounds, target RMSE $target"

# 1. The reference.
if [ -f "$reference" ] && [ -f "$half1" ] && [ -f "$half2" ]; then
    echo "reference: reusing $reference"
else
    half=$((ref_spp / 2))
    for i in 1 2; do
        h=$reference.half$i.pfm
        echo "reference: Mitsuba, $half spp, seed $((1000 + i)) -> $h"
        mitsuba --spp "$half" --seed $((1000 + i)) --output "$h" \
            > "$out/reference_half$i.log" 2>&1 || { tail -20 "$out/reference_half$i.log" >&2; exit 1; }
        grep '^render' "$out/reference_half$i.log" | sed 's/^/  /'
    done
    "$python" "$here/table.py" --mean "$reference" "$half1" "$half2"
fi

# 2. The rounds.
runs=$out/runs.tsv
: > "$runs"
for r in $(seq 1 "$rounds"); do
    img=$out/trac0r_r$r.pfm
    log=$out/trac0r_r$r.log
    "$viewer" "$scene" --headless --width "$width" --height "$height" --spp "$spp_trac0r" \
        --threads "$threads" --seed "$r" --output "$img" > "$log" 2>&1 ||
        { tail -20 "$log" >&2; exit 1; }
    s=$(tr '\r' '\n' < "$log" | sed -n 's/^rendered .* in \([0-9.]*\) s .*/\1/p' | tail -1)
    [ -n "$s" ] || fail "no render time in $log"
    printf 'trac0r\t%s\t%s\t%s\t%s\t%s\n' "$r" "$spp_trac0r" "$r" "$s" "$img" >> "$runs"
    echo "round $r: trac0r $spp_trac0r spp $s s"

    img=$out/mitsuba_r$r.pfm
    log=$out/mitsuba_r$r.log
    mitsuba --spp "$spp_mitsuba" --seed "$r" --threads "$threads" --output "$img" \
        > "$log" 2>&1 || { tail -20 "$log" >&2; exit 1; }
    s=$(sed -n 's/^render without compiling: \([0-9.]*\) s wall.*/\1/p' "$log")
    [ -n "$s" ] || fail "no render time in $log"
    printf 'Mitsuba\t%s\t%s\t%s\t%s\t%s\n' "$r" "$spp_mitsuba" "$r" "$s" "$img" >> "$runs"
    echo "round $r: Mitsuba $spp_mitsuba spp $s s ($(sed -n 's/^render: \([0-9.]*\) s wall.*/\1/p' "$log") s with compiling)"

    img=$out/cycles_r$r.pfm
    log=$out/cycles_r$r.log
    "$blender" -b --factory-startup --python-exit-code 1 -P "$here/cycles_cornell_diffuse.py" -- \
        --scene "$scene" --width "$width" --height "$height" --spp "$spp_cycles" \
        --seed "$r" --threads "$threads" --output "$img" > "$log" 2>&1 ||
        { grep -v '^Fra:' "$log" | tail -20 >&2; exit 1; }
    [ -f "$img" ] || fail "Blender wrote no image (see $log)"
    s=$(sed -n 's/^render: \([0-9.]*\) s wall.*/\1/p' "$log")
    [ -n "$s" ] || fail "no render time in $log"
    printf 'Cycles\t%s\t%s\t%s\t%s\t%s\n' "$r" "$spp_cycles" "$r" "$s" "$img" >> "$runs"
    echo "round $r: Cycles $spp_cycles spp $s s"
done

# 3. The table.
echo
"$python" "$here/table.py" "$runs" "$reference" "$half1" "$half2" "$target" \
    | tee "$out/table.md"
echo
echo "table: $out/table.md; images and logs: $out"
