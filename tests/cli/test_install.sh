#!/usr/bin/env bash
# The installed SDK, used the way a user outside the tree uses it: the build
# is installed to a temporary prefix, which is then moved (nothing may point
# into where it was installed, nor into the build or source tree). From a
# folder outside the tree and with a cleared environment, the installed
# voxrg scaffolds a pass (new-pass), CMake builds it with find_package(voxrg)
# against the moved prefix, and the docs' invert pass (docs/plugin-abi.md)
# is compiled with pkg-config; both load in graphs beside shipped passes and
# render under --validate, and `voxrg plugins NAME` finds each. No installed
# binary names the build or source tree, and an installed shader removed is
# an error naming it. Installed over an earlier install, the C version of
# a pass that is one file now (its NAME.so and NAME/) is removed.
# A host program linked with libvoxrg only (not libvoxrg_voxel) renders a
# graph whose scene plugin needs libvoxrg_voxel: the loader finds it from
# the installed plugin's RUNPATH, not the copy it loads.
# usage: test_install.sh BUILD_DIR SOURCE_DIR OUT_DIR CC [HOST_CFLAGS]
# (CC and HOST_CFLAGS build that host: the sanitizer build's libraries
# need the sanitizers' runtime in the program)
set -u
build=$1 src=$2 out=$3 cc=$4 host_cflags=${5:-}
rm -rf "$out" && mkdir -p "$out/work"
fail() { echo "FAIL: $*"; exit 1; }
# installed over an earlier voxrg whose tonemap was a C pass: its
# tonemap.so and shader folder tonemap/ would be the pass (beside a
# NAME.comp, NAME.so wins); the install removes them
mkdir -p "$out/installed/lib/voxrg/plugins/tonemap" || fail "cannot make the earlier install"
echo "an earlier install's C tonemap" > "$out/installed/lib/voxrg/plugins/tonemap.so"
echo "void main() {}" > "$out/installed/lib/voxrg/plugins/tonemap/tonemap.comp"
cmake --install "$build" --prefix "$out/installed" > "$out/install.log" 2>&1 || { cat "$out/install.log"; fail "cmake --install"; }
for stale in tonemap.so tonemap; do
    [ ! -e "$out/installed/lib/voxrg/plugins/$stale" ] || fail "the earlier install's lib/voxrg/plugins/$stale is still there (tonemap is tonemap.comp now)"
done
mv "$out/installed" "$out/prefix" || fail "cannot move the prefix"
prefix=$out/prefix

# no installed program or library names the source or build tree (no
# compiled-in folder, no debug info's paths, no RUNPATH): what is installed
# does not depend on where it was built, and never reads the checkout.
# Checked on the release build, the one made to be installed: clang's
# sanitizers record each file's name as the compiler was given it (ASan's
# globals, UBSan's type names), which -ffile-prefix-map does not remap, so
# an instrumented build names its tree by design.
case " $host_cflags " in
*-fsanitize=*) sanitized=1; echo "note: a sanitizer build: its binaries name its tree (sanitizer metadata); not checked here" ;;
*) sanitized=0 ;;
esac
for dir in "$src" "$build"; do
    [ "$sanitized" = 1 ] && break
    for form in "$dir" "$(cd "$dir" && pwd -P)"; do
        find "$prefix" -type f | while read -r f; do
            [ "$(head -c 4 "$f")" = "$(printf '\177ELF')" ] || continue
            strings -a "$f" | grep -qF -- "$form" && echo "$f"
        done > "$out/named.txt"
        [ -s "$out/named.txt" ] && { cat "$out/named.txt"; fail "installed binaries name $form (from the build or source tree)"; }
    done
done
# a cleared environment: only what a user's shell has (and the sanitizers'
# settings of the sanitizer build)
run() {
    env -i PATH=/usr/local/bin:/usr/bin:/bin HOME="$out/work" \
        ${ASAN_OPTIONS+ASAN_OPTIONS="$ASAN_OPTIONS"} ${LSAN_OPTIONS+LSAN_OPTIONS="$LSAN_OPTIONS"} \
        ${UBSAN_OPTIONS+UBSAN_OPTIONS="$UBSAN_OPTIONS"} "$@"
}
voxrg=$prefix/bin/voxrg
cd "$out/work" || fail "no work folder"

# one version: the program, the CMake package and pkg-config agree
version=$(run "$voxrg" --version) || fail "voxrg --version"
pcversion=$(run PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --modversion voxrg) || fail "pkg-config voxrg"
[ "$version" = "voxrg $pcversion" ] || fail "voxrg --version says '$version', voxrg.pc '$pcversion'"
grep -q "PACKAGE_VERSION \"$pcversion\"" "$prefix/lib/cmake/voxrg/voxrgConfigVersion.cmake" || fail "voxrgConfigVersion.cmake is not $pcversion"

# shipped plugins come from the moved prefix
run "$voxrg" plugins gbuffer > plugins_gbuffer.txt 2>&1 || { cat plugins_gbuffer.txt; fail "voxrg plugins gbuffer"; }
grep -q "file: $prefix/lib/voxrg/plugins/gbuffer.so" plugins_gbuffer.txt || { cat plugins_gbuffer.txt; fail "gbuffer not found in the prefix"; }
# and shipped one-file passes (NAME.comp beside the plugins)
run "$voxrg" plugins tonemap > plugins_tonemap.txt 2>&1 || { cat plugins_tonemap.txt; fail "voxrg plugins tonemap"; }
grep -q "file: $prefix/lib/voxrg/plugins/tonemap.comp" plugins_tonemap.txt || { cat plugins_tonemap.txt; fail "tonemap not found in the prefix"; }

# a host of the render graph only: it does not need libvoxrg_voxel, the
# terrain plugin does, and finds it in the prefix from the plugin's RUNPATH
cat > host.c <<'C'
#include <stdlib.h>
#include "voxrg/voxrg.h"
int main(int argc, char **argv)
{
    vrg_context *ctx;
    vrg_graph *g = NULL;
    vrg_image_data img = {0};
    if (argc != 2 || vrg_context_create(&(vrg_context_desc){.validate = 1, .quiet = 1}, &ctx) != 0)
        return 2;
    int rc = vrg_graph_load(ctx, &(vrg_graph_desc){.path = argv[1]}, &g) != 0 || vrg_graph_frame(g) != 0 ||
             vrg_graph_read(g, vrg_graph_output(g), &img) != 0;
    if (rc == 0)
        printf("rendered %ux%u, pixel (0, 0) %.3f %.3f %.3f\n", img.width, img.height, img.pixels[0], img.pixels[1], img.pixels[2]);
    free(img.pixels);
    vrg_graph_destroy(g);
    rc |= vrg_context_validation_errors(ctx) != 0;
    vrg_context_destroy(ctx);
    return rc;
}
C
cat > host.ini <<'INI'
[graph]
output = ldr
width  = 96
height = 54

[camera]
position = -20 60 20
yaw      = -40
pitch    = -35

[scene]
plugin = terrain
radius = 1

[pass gbuffer]
plugin     = gbuffer
in.world   = world
in.frame   = frame
in.atlas   = atlas
out.albedo = albedo

[pass tonemap]
plugin   = tonemap
in.color = albedo
out.ldr  = ldr
INI
run PKG_CONFIG_PATH="$prefix/lib/pkgconfig" sh -c "$cc -std=c11 $host_cflags host.c -o host -Wl,-rpath,'$prefix/lib' \$(pkg-config --cflags --libs voxrg)" \
    > host_build.log 2>&1 || { cat host_build.log; fail "the host does not build with pkg-config voxrg"; }
readelf -d host > host_dynamic.txt || fail "readelf host"
grep -q 'NEEDED.*libvoxrg\.so' host_dynamic.txt && ! grep -q 'NEEDED.*libvoxrg_voxel' host_dynamic.txt ||
    { cat host_dynamic.txt; fail "the host should need libvoxrg and not libvoxrg_voxel"; }
readelf -d "$prefix/lib/voxrg/plugins/terrain.so" | grep -q 'R.*PATH.*\[\$ORIGIN/\.\./\.\.\]' ||
    fail "the installed terrain.so has no RUNPATH \$ORIGIN/../.."
run ./host host.ini > host.log 2>&1 || { cat host.log; fail "a host linked with libvoxrg only cannot render the terrain scene"; }
grep -q "rendered 96x54" host.log || { cat host.log; fail "the host rendered no image"; }
# the same plugin where its RUNPATH leads to no libvoxrg_voxel: the error
# names the plugin's file and the library it lacks
mkdir -p stray/a/b && cp "$prefix/lib/voxrg/plugins/terrain.so" stray/a/b/stray.so
sed -e 's/^plugin = terrain$/plugin = stray/' -e 's|^\[graph\]$|[graph]\nplugin_path = stray/a/b|' host.ini > stray.ini
run ./host stray.ini > stray.log 2>&1 && fail "the stray plugin without its library loaded"
grep -q "stray.ini:13: error\[VRG-E051\]: cannot load plugin 'stray' from $out/work/stray/a/b/stray.so: libvoxrg_voxel.so.0.[0-9]*: cannot open shared object file" stray.log ||
    { cat stray.log; fail "the missing library is not named with the plugin's path"; }
grep -q "hint: a library it needs is on neither its RUNPATH" stray.log || { cat stray.log; fail "no hint about the plugin's RUNPATH"; }

# the scaffold: refuses a bad name, builds with CMake, renders
run "$voxrg" new-pass 9lives > bad_name.txt 2>&1
[ $? -eq 2 ] && grep -q "not a valid pass name" bad_name.txt || { cat bad_name.txt; fail "new-pass accepted 9lives"; }
run "$voxrg" new-pass tint > new_pass.txt 2>&1 || { cat new_pass.txt; fail "voxrg new-pass tint"; }
# its README in the one form of a pass folder's (docs/plugin-abi.md)
[ "$(grep '^## ' tint/README.md 2>/dev/null | tr '\n' '|')" = "## What it does|## Slots|## Parameters|## Cost|## Debug outputs|" ] ||
    { cat tint/README.md; fail "the scaffold's README.md is not in the pass README form"; }
run "$voxrg" new-pass tint > again.txt 2>&1
[ $? -eq 1 ] && grep -q "tint/tint.c exists; nothing was written" again.txt || { cat again.txt; fail "new-pass overwrote tint/"; }
(run cmake -S tint -B tint/build -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-Werror &&
    run cmake --build tint/build) > tint_build.log 2>&1 || { cat tint_build.log; fail "the scaffolded pass does not build"; }
run "$voxrg" render tint/tint.ini --validate --frames 1 --out tint/out > tint_render.log 2>&1 ||
    { cat tint_render.log; fail "the scaffolded graph does not render"; }
[ -s tint/out/ldr.png ] || fail "tint wrote no ldr.png"
# the scaffold reads the frame uniforms (camera, sky): its haze changes the image
run "$voxrg" render tint/tint.ini --validate --frames 1 --set tint.haze=0 --out tint/out0 > tint_render0.log 2>&1 ||
    { cat tint_render0.log; fail "the scaffolded graph does not render with haze 0"; }
cmp -s tint/out/ldr.png tint/out0/ldr.png && fail "the scaffold's haze (its frame uniforms) changes nothing"
run VOXRG_PLUGIN_PATH="$out/work/tint/build" "$voxrg" plugins tint > plugins_tint.txt 2>&1 &&
    grep -q "file: $out/work/tint/build/tint.so" plugins_tint.txt || { cat plugins_tint.txt; fail "voxrg plugins tint"; }
# installed, the scaffolded pass names neither its source nor its build
# folder, and reads its shader from its own installed folder only: with
# the source folder gone it still renders, and its installed shader
# removed is an error naming that file
run cmake --install tint/build --prefix "$out/work/tint_prefix" > tint_install.log 2>&1 || { cat tint_install.log; fail "cmake --install of the scaffolded pass"; }
tint_so=$out/work/tint_prefix/lib/voxrg/plugins/tint.so
[ -f "$tint_so" ] && [ -f "$out/work/tint_prefix/lib/voxrg/plugins/tint/tint.comp" ] || fail "the scaffolded pass installed no tint.so or tint/tint.comp"
strings -a "$tint_so" | grep -F -e "$out/work/tint" > tint_named.txt && { cat tint_named.txt; fail "the installed tint.so names its source or build folder"; }
mv tint tint_src || fail "cannot move the scaffold's source away"
sed -e 's|^plugin_path *=.*$|plugin_path = ../tint_prefix/lib/voxrg/plugins|' tint_src/tint.ini > tint_installed.ini
mkdir -p tint && cp tint_installed.ini tint/tint.ini
run "$voxrg" render tint/tint.ini --validate --frames 1 --out tint/out_installed > tint_installed.log 2>&1 ||
    { cat tint_installed.log; fail "the installed scaffolded pass does not render without its source folder"; }
rm "$out/work/tint_prefix/lib/voxrg/plugins/tint/tint.comp"
run "$voxrg" render tint/tint.ini --frames 1 --out tint/out_missing > tint_missing.log 2>&1 && fail "tint rendered without its installed shader"
grep -q "shader 'tint.comp' not found (searched $out/work/tint_prefix/lib/voxrg/plugins/tint/tint.comp" tint_missing.log ||
    { cat tint_missing.log; fail "the missing installed shader of tint is not named"; }
grep -q "tint_src" tint_missing.log && { cat tint_missing.log; fail "the installed tint searched its source folder"; }
rm -rf tint && mv tint_src tint || fail "cannot move the scaffold back"

# the docs' invert pass, built with pkg-config against the prefix only
page="$src/docs/plugin-abi.md"
block() {
    awk -v marker="$1" '
        index($0, marker) == 1 { want = 1; next }
        want && /^```/ { if (inside) exit; inside = 1; next }
        inside { print }' "$page"
}
mkdir -p invert
block '`passes/invert/invert.c`:' > invert/invert.c
block '`passes/invert/invert.comp`:' > invert/invert.comp
[ -s invert/invert.c ] && [ -s invert/invert.comp ] || fail "docs/plugin-abi.md has no invert.c or invert.comp block"
# (built beside the folder invert/, where its shader is read from)
run PKG_CONFIG_PATH="$prefix/lib/pkgconfig" sh -c 'gcc -std=c11 -fPIC -shared $(pkg-config --cflags voxrg) \
    invert/invert.c -o invert.so $(pkg-config --libs voxrg)' > invert_build.log 2>&1 ||
    { cat invert_build.log; fail "the docs' invert.c does not build with pkg-config"; }
cat > invert.ini <<'INI'
[graph]
output      = ldr
width       = 160
height      = 90
plugin_path = .

[camera]
position = -20 60 20
yaw      = -40
pitch    = -35

[scene]
plugin = terrain
radius = 1

[pass gbuffer]
plugin     = gbuffer
in.world   = world
in.frame   = frame
in.atlas   = atlas
out.albedo = albedo

[pass invert]
plugin  = invert
in.src  = albedo
out.dst = inverted

[pass tonemap]
plugin   = tonemap
in.color = inverted
out.ldr  = ldr
INI
run "$voxrg" render invert.ini --validate --frames 1 --out invert/out > invert_render.log 2>&1 ||
    { cat invert_render.log; fail "the invert graph does not render"; }
[ -s invert/out/ldr.png ] || fail "invert wrote no ldr.png"
run VOXRG_PLUGIN_PATH="$out/work" "$voxrg" plugins invert > plugins_invert.txt 2>&1 &&
    grep -q "strength" plugins_invert.txt || { cat plugins_invert.txt; fail "voxrg plugins invert"; }

# an installed plugin's shaders are read from the prefix, not from the tree
# it was built in: a broken installed gbuffer.comp is the one reported
printf '#version 460\nthis is not glsl\n' > "$prefix/lib/voxrg/plugins/gbuffer/gbuffer.comp"
run "$voxrg" render invert.ini --frames 1 --out invert/broken > broken.log 2>&1 && fail "a broken installed shader rendered"
grep -q "$prefix/lib/voxrg/plugins/gbuffer/gbuffer.comp:2: error\[VRG-E063\]" broken.log || { cat broken.log; fail "the installed shader was not the one compiled"; }
# an installed shader that is missing is an error naming where it was
# looked for: never a shader read from the tree the plugin was built in
rm "$prefix/lib/voxrg/plugins/gbuffer/gbuffer.comp"
run "$voxrg" render invert.ini --frames 1 --out invert/missing > missing.log 2>&1 && fail "a graph rendered without the installed gbuffer.comp"
grep -q "shader 'gbuffer.comp' not found (searched $prefix/lib/voxrg/plugins/gbuffer/gbuffer.comp," missing.log ||
    { cat missing.log; fail "the missing installed shader is not named with its path"; }
sed -n "s/.*shader 'gbuffer.comp' not found (searched \(.*\))$/\1/p" missing.log | tr ',' '\n' | sed 's/^ //' > searched.txt
grep -v "^$prefix/" searched.txt && { cat missing.log; fail "the missing shader was looked for outside the prefix"; }
echo "install: ok"
