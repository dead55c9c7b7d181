#!/usr/bin/env bash
# Loads each model file of a corpus into trac0r_viewer, once leniently (no
# flag) and once with --strict, and classifies what happened.
#
#   benchmarks/model_corpus/run.sh [MODEL_FILE...]
#
# Without arguments the corpus is every .obj, .ply, .gltf and .glb under
# Debian's assimp-testmodels (/usr/share/assimp/models: OBJ, PLY, glTF2,
# invalid, and models-nonbsd where present) and under $MODEL_CORPUS_DIRS
# (space-separated folders, searched for the same extensions).
#
# Each file is placed, with no "material" key, in a scene of its own (the
# viewer's default camera, a grey constant environment and a sun) and
# rendered at 64 x 48, 1 spp. Whether the picture frames the model is not
# judged: only whether the file loads and renders.
#
# Environment: TRAC0R_VIEWER (default build/trac0r_viewer of this checkout),
# TIMEOUT_S (default 120, per run), KEEP=1 keeps the temp folder.
#
# Classes (per run):
#   clean    exit 0, a PNG written, no warning line
#   warn     exit 0, a PNG written, warning lines (their kinds are listed)
#   refused  exit 1: the first line of stderr is shown
#   timeout  exit 124 (killed by timeout after TIMEOUT_S)
#   crash    any other exit status (134 SIGABRT, 139 SIGSEGV, ...) or exit 0
#            without the PNG
#
# Groups (per file):
#   broken      meant to fail: the invalid/ folder, the glTF2 files that
#               assimp's own unit tests (test/unit/utglTF2ImportExport.cpp)
#               expect to be refused, and BoxWithInfinites.glb (every
#               vertex has an infinite coordinate; assimp loads it only to
#               test its exporter's bounds)
#   no-surface  a valid file with no surface: points or lines only, or an
#               empty scene: nothing a renderer of surfaces can show
#   valid       everything else
set -uo pipefail

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
viewer=${TRAC0R_VIEWER:-$root/build/trac0r_viewer}
timeout_s=${TIMEOUT_S:-120}
assimp=/usr/share/assimp

if [[ ! -x $viewer ]]; then
    echo "run.sh: $viewer not found: build it first (cmake --build build --target trac0r_viewer)" >&2
    exit 2
fi

files=()
if (($# > 0)); then
    files=("$@")
else
    dirs=()
    for d in "$assimp/models/OBJ" "$assimp/models/PLY" "$assimp/models/glTF2" \
             "$assimp/models/invalid" "$assimp/models-nonbsd/OBJ" \
             "$assimp/models-nonbsd/PLY" "$assimp/models-nonbsd/glTF2" \
             ${MODEL_CORPUS_DIRS:-}; do
        [[ -d $d ]] && dirs+=("$d")
    done
    if ((${#dirs[@]} == 0)); then
        echo "run.sh: no corpus: apt-get install assimp-testmodels, or give files" >&2
        exit 2
    fi
    mapfile -t files < <(find "${dirs[@]}" -type f \( -iname '*.obj' -o -iname '*.ply' \
        -o -iname '*.gltf' -o -iname '*.glb' \) | LC_ALL=C sort)
fi

# Files meant to fail, by path suffix: assimp's invalid/ folder, and the
# glTF2 files its unit tests expect ReadFile to refuse (MissingBin: a
# missing .bin; RecursiveNodes; NoScene; issue_3269; AllIndicesOutOfRange;
# wrongTypes/*; SchemaFailures: a scene of the wrong JSON type), and
# BoxWithInfinites (no finite vertex).
broken_patterns=(
    '/models/invalid/'
    '/glTF2/MissingBin/'
    '/glTF2/RecursiveNodes/'
    '/glTF2/TestNoRootNode/NoScene.gltf'
    '/glTF2/issue_3269/'
    '/glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf'
    '/glTF2/wrongTypes/'
    '/glTF2/SchemaFailures/'
    '/glTF2/BoxWithInfinites-glTF-Binary/'
)
# Valid files with no surface: points and lines only (glTF-Asset-Generator's
# primitive modes 0-3 and 7-10 are POINTS, LINES, LINE_LOOP, LINE_STRIP;
# the OBJ and PLY ones have p/l statements or vertices alone: assimp's
# pointcloudTest expects issue623.ply to load as 24 points and no face;
# pond.0.ply is 70051 vertices with a point size), a scene without
# nodes (assimp's norootnode_scenewithoutnodes: it loads, with no mesh),
# and number_formats.obj, a test of number syntax whose one face,
# 'f 1 2 4', joins (0,0,0), (1,2,3) and (-1,-2,-3): collinear.
nosurface_patterns=(
    '/Mesh_PrimitiveMode/Mesh_PrimitiveMode_00.gltf'
    '/Mesh_PrimitiveMode/Mesh_PrimitiveMode_01.gltf'
    '/Mesh_PrimitiveMode/Mesh_PrimitiveMode_02.gltf'
    '/Mesh_PrimitiveMode/Mesh_PrimitiveMode_03.gltf'
    '/Mesh_PrimitiveMode/Mesh_PrimitiveMode_07.gltf'
    '/Mesh_PrimitiveMode/Mesh_PrimitiveMode_08.gltf'
    '/Mesh_PrimitiveMode/Mesh_PrimitiveMode_09.gltf'
    '/Mesh_PrimitiveMode/Mesh_PrimitiveMode_10.gltf'
    '/OBJ/testline.obj'
    '/OBJ/testpoints.obj'
    '/OBJ/point_cloud.obj'
    '/PLY/points.ply'
    '/PLY/issue623.ply'
    '/PLY/pond.0.ply'
    '/glTF2/TestNoRootNode/SceneWithoutNodes.gltf'
    '/OBJ/number_formats.obj'
)

group_of() {
    local f=$1 p
    for p in "${broken_patterns[@]}"; do [[ $f == *"$p"* ]] && { echo broken; return; }; done
    for p in "${nosurface_patterns[@]}"; do [[ $f == *"$p"* ]] && { echo no-surface; return; }; done
    echo valid
}

format_of() {
    local ext=${1##*.}
    ext=${ext,,}
    case $ext in
        obj) echo OBJ ;;
        ply) echo PLY ;;
        gltf | glb) echo glTF2 ;;
        *) echo other ;;
    esac
}

# Whether an OBJ file is a textured OBJ + MTL model: one of its mtllib files
# is there and has a map_Kd statement.
textured_obj() {
    local f=$1 lib
    [[ $(format_of "$f") == OBJ ]] || return 1
    while IFS= read -r lib; do
        [[ -f "$(dirname "$f")/$lib" ]] && grep -qE '^[[:space:]]*map_Kd[[:space:]]' \
            "$(dirname "$f")/$lib" && return 0
    done < <(sed -n -e 's/\r$//' -e 's/^[[:space:]]*mtllib[[:space:]]\+//p' "$f")
    return 1
}

json_string() {  # a JSON string literal of $1
    local s=$1
    s=${s//\\/\\\\}
    s=${s//\"/\\\"}
    printf '"%s"' "$s"
}

tmp=$(mktemp -d /tmp/model_corpus.XXXXXX)
if [[ ${KEEP:-0} != 1 ]]; then
    trap 'rm -rf "$tmp"' EXIT
else
    echo "keeping $tmp" >&2
fi

# run_one SCENE OUT ERRFILE [FLAGS...] -> sets run_class, run_detail
run_one() {
    local scene=$1 out=$2 err=$3
    shift 3
    rm -f "$out"
    timeout "$timeout_s" "$viewer" "$scene" --headless --width 64 --height 48 --spp 1 \
        --output "$out" "$@" >/dev/null 2>"$err" </dev/null
    local rc=$?
    run_detail=""
    if ((rc == 0)) && [[ -s $out ]]; then
        if grep -q ': warning: ' "$err"; then
            run_class=warn
            # the kind: the text between "warning: " and the first ";",
            # with quoted names folded to '…'
            run_detail=$(grep ': warning: ' "$err" | sed -e 's/.*: warning: //' -e 's/;.*//' \
                -e "s/'[^']*'/'…'/g" | sort -u | paste -sd '|' -)
        else
            run_class=clean
        fi
    elif ((rc == 1)); then
        run_class=refused
        run_detail=$(grep -v -E '^(\[#|rendered |wrote )' "$err" | head -n 1)
    elif ((rc == 124)); then
        run_class=timeout
        run_detail="no result within ${timeout_s} s"
    else
        run_class=crash
        run_detail="exit $rc: $(grep -v -E '^(\[#|rendered |wrote )' "$err" | head -n 1)"
    fi
}

declare -A count
classes=(clean warn refused timeout crash)
formats=(OBJ PLY glTF2 other)
groups=(valid no-surface broken)
lines=()
start=$(date +%s)
n=0
for f in "${files[@]}"; do
    n=$((n + 1))
    abs=$(readlink -f "$f")
    fmt=$(format_of "$abs")
    grp=$(group_of "$abs")
    scene=$tmp/scene_$n.json
    cat >"$scene" <<EOF
{
  "materials": {"lamp": {"type": "emissive", "color": [1, 1, 1], "emittance": 1}},
  "environment": {"color": [0.8, 0.8, 0.8]},
  "lights": [{"type": "sun", "direction": [0.3, 1, 0.2], "irradiance": 3}],
  "shapes": [{"type": "mesh", "file": $(json_string "$abs")}]
}
EOF
    run_one "$scene" "$tmp/out_$n.png" "$tmp/err_$n.txt"
    lc=$run_class ld=$run_detail
    run_one "$scene" "$tmp/outs_$n.png" "$tmp/errs_$n.txt" --strict
    sc=$run_class sd=$run_detail
    count[$fmt,$lc]=$((${count[$fmt,$lc]:-0} + 1))
    count[$grp,$lc]=$((${count[$grp,$lc]:-0} + 1))
    count[all,$lc]=$((${count[all,$lc]:-0} + 1))
    count[strict,$sc]=$((${count[strict,$sc]:-0} + 1))
    if [[ $grp == valid ]] && textured_obj "$abs"; then
        count[textured,$lc]=$((${count[textured,$lc]:-0} + 1))
        count[textured,n]=$((${count[textured,n]:-0} + 1))
    fi
    count[$fmt,n]=$((${count[$fmt,n]:-0} + 1))
    count[$grp,n]=$((${count[$grp,n]:-0} + 1))
    line="$lc	$grp	$fmt	${f#"$assimp/"}"
    [[ -n $ld ]] && line+="	$ld"
    line+="	| strict: $sc"
    [[ $sc != "$lc" && -n $sd ]] && line+=" ($sd)"
    lines+=("$line")
done
elapsed=$(($(date +%s) - start))

echo "model corpus: ${#files[@]} files, lenient run (no flag) and --strict, ${elapsed} s"
echo
printf '%-12s %5s' "" files
for c in "${classes[@]}"; do printf ' %8s' "$c"; done
echo
for row in "${formats[@]}" "${groups[@]}"; do
    ((${count[$row,n]:-0} == 0)) && continue
    printf '%-12s %5d' "$row" "${count[$row,n]}"
    for c in "${classes[@]}"; do printf ' %8d' "${count[$row,$c]:-0}"; done
    echo
done
printf '%-12s %5d' all "${#files[@]}"
for c in "${classes[@]}"; do printf ' %8d' "${count[all,$c]:-0}"; done
echo
printf '%-12s %5d' "--strict" "${#files[@]}"
for c in "${classes[@]}"; do printf ' %8d' "${count[strict,$c]:-0}"; done
echo
echo
v=${count[valid,n]:-0}
vr=$((${count[valid,clean]:-0} + ${count[valid,warn]:-0}))
if ((v > 0)); then
    echo "valid files rendered with no flag: $vr of $v ($((1000 * vr / v / 10)).$((1000 * vr / v % 10)) %, rounded down)"
fi
t=${count[textured,n]:-0}
tr=$((${count[textured,clean]:-0} + ${count[textured,warn]:-0}))
if ((t > 0)); then
    echo "textured OBJ + MTL models (valid) rendered with no flag: $tr of $t"
fi
vn=$((v + ${count[no-surface,n]:-0}))
vnr=$((vr + ${count[no-surface,clean]:-0} + ${count[no-surface,warn]:-0}))
if ((vn > v)); then
    echo "valid and no-surface files rendered with no flag: $vnr of $vn ($((1000 * vnr / vn / 10)).$((1000 * vnr / vn % 10)) %, rounded down)"
fi
echo
echo "one line per file: lenient class, group, format, file, detail | the --strict class"
printf '%s\n' "${lines[@]}"

bad=$((${count[all,crash]:-0} + ${count[all,timeout]:-0} + ${count[strict,crash]:-0} + ${count[strict,timeout]:-0}))
((bad == 0))
