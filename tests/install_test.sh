#!/usr/bin/env bash
# test_install: cmake --install the built tree into a fresh prefix, build
# examples/ against it as a separate project (find_package(trac0r)), run
# it on the built-in scene and check the PNG it writes, and that at 64 spp
# it renders trac0r_viewer's image bit for bit (one set of defaults). The
# installed headers are the public ones, each compiling on its own.
# Usage: tests/install_test.sh BUILD_DIR
set -euo pipefail
source_dir=$(cd "$(dirname "$0")/.." && pwd)
build=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
test -f "$work/prefix/include/trac0r/trac0r.h" || { echo "no trac0r/trac0r.h installed" >&2; exit 1; }
# The public headers only: none of the kernel's, and each compiles on its
# own (what it needs, it includes).
if [ -e "$work/prefix/include/trac0r/kernel" ]; then
    echo "the kernel's headers were installed" >&2; exit 1
fi
for header in "$work"/prefix/include/trac0r/*.h; do
    name=$(basename "$header")
    if grep -q '#include "trac0r/kernel/' "$header"; then
        echo "installed trac0r/$name includes a kernel header" >&2; exit 1
    fi
    echo "#include <trac0r/$name>" >"$work/one_header.cpp"
    c++ -std=c++14 -fsyntax-only -I"$work/prefix/include" "$work/one_header.cpp" ||
        { echo "installed trac0r/$name does not compile on its own" >&2; exit 1; }
done
cmake -S "$source_dir/examples" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
    -DCMAKE_BUILD_TYPE=Release >"$work/configure.log" ||
    { cat "$work/configure.log" >&2; exit 1; }
cmake --build "$work/build" >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; exit 1; }
(cd "$work" && OMP_NUM_THREADS=2 "$work/build/minimal" "" 2 out.png)
head -c 8 "$work/out.png" | od -An -tx1 | grep -q "89 50 4e 47 0d 0a 1a 0a" ||
    { echo "minimal wrote no PNG" >&2; exit 1; }
(cd "$work" && "$work/build/minimal" "" 64 minimal.pfm >/dev/null)
"$build/trac0r_viewer" --headless --spp 64 --output "$work/viewer.pfm" 2>/dev/null
cmp "$work/minimal.pfm" "$work/viewer.pfm" ||
    { echo "examples/minimal at 64 spp differs from trac0r_viewer --headless --spp 64" >&2; exit 1; }
echo "test_install: installed, built examples/minimal against it, rendered out.png;" \
    "at 64 spp it renders trac0r_viewer's image bit for bit"
