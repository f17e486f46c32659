#!/usr/bin/env bash
# The complete passes of docs/plugin-abi.md, built and run as the page says:
# invert (an image in, an image out) and fog (reads the frame uniforms):
# each one's .c, .comp and graph are cut out of the page, the plugin is
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
# NAME's .c and .comp, and its graph (the block after the line starting
# with GRAPH_MARKER), compiled with the page's command and this build's
# paths (NAME.so beside NAME/, where its shader is read); a plugin author's
# warnings are errors here, so the page's tables stay clean under -Wextra
build_example() {
    name=$1 marker=$2
    mkdir -p "$out/$name"
    block "\`passes/$name/$name.c\`:" > "$out/$name/$name.c"
    block "\`passes/$name/$name.comp\`:" > "$out/$name/$name.comp"
    block "$marker" > "$out/$name.ini"
    for f in $name/$name.c $name/$name.comp $name.ini; do
        [ -s "$out/$f" ] || { echo "FAIL: docs/plugin-abi.md has no $f block"; exit 1; }
    done
    if ! gcc -std=c11 -Wall -Wextra -Werror -fPIC -shared -I"$src/core/runtime/include" \
        "$out/$name/$name.c" -o "$out/$name.so" -L"$libdir" -lvoxrg 2> "$out/gcc-$name.log"; then
        echo "FAIL: the page's $name.c does not compile:"; cat "$out/gcc-$name.log"; exit 1
    fi
}
build_example invert 'A graph that uses it'
build_example fog 'A graph that uses it, with a scene'
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
# fog reads the camera and the sky from the frame uniforms: its graph
# renders, and fog with density 0 leaves hit pixels as they were, so the
# two images differ
for density in 0.02 0; do
    if ! "$voxrg" render "$out/fog.ini" --validate --set fog.density=$density --size 64x36 --out "$out/fog-$density" \
        > "$out/render-fog.log" 2>&1; then
        echo "FAIL: the page's fog graph does not render:"; cat "$out/render-fog.log"; exit 1
    fi
    [ -s "$out/fog-$density/ldr.png" ] || { echo "FAIL: fog wrote no ldr.png"; exit 1; }
done
cmp -s "$out/fog-0.02/ldr.png" "$out/fog-0/ldr.png" && { echo "FAIL: fog's density changes nothing"; exit 1; }
echo "docs example: ok"
