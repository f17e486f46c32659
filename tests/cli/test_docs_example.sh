#!/usr/bin/env bash
# The complete pass of docs/plugin-abi.md, built and run as the page says:
# its invert.c, invert.comp and graph are cut out of the page, the plugin is
# compiled with the page's "Outside CMake" command, and the graph renders
# under --validate. A page that no longer builds fails this test.
# usage: test_docs_example.sh VOXRG_BINARY SOURCE_DIR LIBDIR PLUGIN_DIR OUT_DIR
set -u
voxrg=$1 src=$2 libdir=$3 plugins=$4 out=$5
rm -rf "$out" && mkdir -p "$out/invert"
page="$src/docs/plugin-abi.md"
# the fenced block after the line that names the file
block() {
    awk -v marker="$1" '
        index($0, marker) == 1 { want = 1; next }
        want && /^```/ { if (inside) exit; inside = 1; next }
        inside { print }' "$page"
}
block '`passes/invert/invert.c`:' > "$out/invert/invert.c"
block '`passes/invert/invert.comp`:' > "$out/invert/invert.comp"
block 'A graph that uses it' > "$out/invert.ini"
for f in invert/invert.c invert/invert.comp invert.ini; do
    [ -s "$out/$f" ] || { echo "FAIL: docs/plugin-abi.md has no $f block"; exit 1; }
done
# the page's command, with this build's paths; a plugin author's warnings
# are errors here, so the page's tables stay clean under -Wextra
if ! gcc -std=c11 -Wall -Wextra -Werror -fPIC -shared -I"$src/core/runtime/include" -DVRG_PLUGIN_DIR="\"$out/invert\"" \
    "$out/invert/invert.c" -o "$out/invert.so" -L"$libdir" -lvoxrg 2> "$out/gcc.log"; then
    echo "FAIL: the page's invert.c does not compile:"; cat "$out/gcc.log"; exit 1
fi
# docs/world.md's scene tables (VRG_SCENE_PARAMS and _SLOTS included) under
# the same flags
awk '/^static const vrg_param_desc params/ { want = 1 } want { print } want && /^static const vrg_slot_desc/ { exit }' \
    "$src/docs/world.md" > "$out/scene_tables.c"
[ -s "$out/scene_tables.c" ] || { echo "FAIL: docs/world.md has no scene parameter table"; exit 1; }
printf '#include <voxrg/plugin.h>\n#include <voxrg/world.h>\n#include "scene_tables.c"\nconst void *tables[] = {params, slots};\n' \
    > "$out/scene.c"
if ! gcc -std=c11 -Wall -Wextra -Werror -fsyntax-only -I"$src/core/runtime/include" -I"$src/core/voxel/include" \
    "$out/scene.c" 2> "$out/gcc-scene.log"; then
    echo "FAIL: docs/world.md's scene tables do not compile warning-free:"; cat "$out/gcc-scene.log"; exit 1
fi
export VOXRG_PLUGIN_PATH="$out:$plugins"
"$voxrg" plugins invert > "$out/plugins.txt" 2>&1 || { echo "FAIL: voxrg plugins invert"; cat "$out/plugins.txt"; exit 1; }
grep -q "strength" "$out/plugins.txt" || { echo "FAIL: invert's parameters are not listed"; cat "$out/plugins.txt"; exit 1; }
if ! "$voxrg" render "$out/invert.ini" --validate --set invert.strength=1 --size 64x36 --out "$out/r" > "$out/render.log" 2>&1; then
    echo "FAIL: the page's graph does not render:"; cat "$out/render.log"; exit 1
fi
[ -s "$out/r/inverted.png" ] || { echo "FAIL: no inverted.png"; exit 1; }
echo "docs example: ok"
