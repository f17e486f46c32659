#!/usr/bin/env bash
# Shader reflection: each way a shader can disagree with what its pass binds
# is an error at the shader's line that names the binding, the slot, the pass
# and its plugin, and both sides (docs/graph-format.md, VRG-E064..E067,
# VRG-W004); none crashes. The shaders are written here and found through
# $VOXRG_SHADER_PATH by the reflect_probe plugin (tests/plugins/reflect_probe).
# Usage: test_reflect.sh VOXRG TESTS_DIR OUT_DIR
set -u
voxrg=$1 tests=$2 out=$3
rm -rf "$out" && mkdir -p "$out/sh"
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }
graph="$tests/graphs/reflect_probe.ini"
shader="$out/sh/reflect.comp"
# Each case renders, and `voxrg check --no-device` (which compiles and
# reflects every dispatch the plugin lists, without Vulkan) must say the
# same before any frame: has/hasnt look at both.
render() { # want_rc description [options...]
    local want=$1 what=$2; shift 2
    env VOXRG_SHADER_PATH="$out/sh" "$voxrg" render "$graph" --validate --out "$out/img" "$@" >"$out/stdout" 2>"$out/stderr"
    local rc=$?
    if [ "$rc" -eq "$want" ]; then ok; else bad "$what: exit $rc, want $want"; cat "$out/stderr"; fi
    env VOXRG_SHADER_PATH="$out/sh" "$voxrg" check "$graph" --no-device "$@" >"$out/check_stdout" 2>"$out/check_stderr"
    rc=$?
    want=${check_want:-$want}
    if [ "$rc" -eq "$want" ]; then ok; else bad "$what (check --no-device): exit $rc, want $want"; cat "$out/check_stderr"; fi
}
has() { # pattern description
    for f in stderr check_stderr; do
        if grep -qE -- "$1" "$out/$f"; then ok; else bad "$2 ($f): no '$1' in"; sed 's/^/    /' "$out/$f" | head -20; fi
    done
}
hasnt() { # pattern description
    for f in stderr check_stderr; do
        if grep -qE -- "$1" "$out/$f"; then bad "$2 ($f): '$1' in"; sed 's/^/    /' "$out/$f" | head -20; else ok; fi
    done
}
# write_shader LINE3 LINE4 LINE5 LINE6: the declarations, at lines 3 to 6
write_shader() {
    cat >"$shader" <<GLSL
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
$1
$2
$3
$4
void main() { $5 }
GLSL
}
color='layout(binding = 0, rgba16f) uniform writeonly image2D color_img;'
mask='layout(binding = 1, rgba8) uniform writeonly image2D mask_img;'
counts='layout(std430, binding = 2) writeonly buffer Counts { uint counts[16]; };'
push='layout(push_constant) uniform Push { vec4 tint; } push;'
body='ivec2 p = ivec2(gl_GlobalInvocationID.xy); imageStore(color_img, p, push.tint); imageStore(mask_img, p, vec4(1)); counts[0] = 1u;'
pos="$out/sh/reflect.comp"

write_shader "$color" "$mask" "$counts" "$push" "$body"
render 0 "a shader that matches its pass"
hasnt "VRG-E06[4-8]|VRG-W00[45]" "no reflection message for a matching shader"
if grep -qE "^  probe +reflect_probe +1 dispatch compiled and reflected$" "$out/check_stdout"; then ok; else bad "check lists the dispatches it compiled"; cat "$out/check_stdout"; fi
# with a device too (the device's workgroup shape; a pipeline per dispatch)
env VOXRG_SHADER_PATH="$out/sh" "$voxrg" check "$graph" --validate >"$out/check_device" 2>&1 &&
    grep -qE "^  probe +reflect_probe +1 dispatch compiled and reflected$" "$out/check_device" && ok || { bad "check with a device"; cat "$out/check_device"; }

write_shader "${color/rgba16f/rgba32f}" "$mask" "$counts" "$push" "$body"
render 1 "rgba16f slot, rgba32f shader"
has "^$pos:3: error\[VRG-E066\]: binding 0 'color_img' is rgba32f, but slot 'out.color' of pass 'probe' \(plugin reflect_probe\) is rgba16f$" "format of an HDR output"
has "error\[VRG-E060\]: pass 'probe'.*shader $pos does not match what the pass binds" "the pass fails like a compile error"

write_shader "$color" "${mask/rgba8/rgba16f}" "$counts" "$push" "$body"
render 1 "rgba8 slot, rgba16f shader"
has "^$pos:4: error\[VRG-E066\]: binding 1 'mask_img' is rgba16f, but slot 'out.mask' of pass 'probe' \(plugin reflect_probe\) is rgba8$" "format of an 8-bit output"

# two bindings swapped, of different types: the image at 2, the buffer at 0
write_shader "${color/binding = 0/binding = 2}" "$mask" "${counts/binding = 2/binding = 0}" "$push" "$body"
render 1 "two bindings swapped"
has "^$pos:3: error\[VRG-E065\]: binding 2 'color_img' is a storage image, but slot 'out.counts' of pass 'probe' \(plugin reflect_probe\) is bound as a storage buffer$" "the image at the buffer's binding"
has "^$pos:5: error\[VRG-E065\]: binding 0 'Counts' is a storage buffer, but slot 'out.color' of pass 'probe' \(plugin reflect_probe\) is bound as a storage image$" "the buffer at the image's binding"

# binding numbers reordered: both storage images, told apart by their formats
write_shader "${color/binding = 0/binding = 1}" "${mask/binding = 1/binding = 0}" "$counts" "$push" "$body"
render 1 "binding numbers reordered"
has "^$pos:3: error\[VRG-E066\]: binding 1 'color_img' is rgba16f, but slot 'out.mask' .* is rgba8$" "color at mask's number"
has "^$pos:4: error\[VRG-E066\]: binding 0 'mask_img' is rgba8, but slot 'out.color' .* is rgba16f$" "mask at color's number"

write_shader 'layout(binding = 0) uniform sampler2D color_tex;' "$mask" "$counts" "$push" \
    'ivec2 p = ivec2(gl_GlobalInvocationID.xy); imageStore(mask_img, p, texelFetch(color_tex, p, 0) + push.tint); counts[0] = 1u;'
render 1 "wrong descriptor type"
has "^$pos:3: error\[VRG-E065\]: binding 0 'color_tex' is a sampled image \(sampler2D\), but slot 'out.color' of pass 'probe' \(plugin reflect_probe\) is bound as a storage image$" "sampler for a storage image"

# a binding the plugin never declared: crashed inside the driver before
write_shader "$color" "$mask" "$counts" "$push
layout(binding = 5, rgba16f) uniform writeonly image2D extra;" "$body imageStore(extra, p, vec4(0));"
render 1 "a binding the pass does not bind"
has "^$pos:7: error\[VRG-E064\]: binding 5 'extra' is bound to nothing: pass 'probe' \(plugin reflect_probe\) binds 3 resources \(bindings 0 to 2\)$" "undeclared binding"

write_shader "$color" "$mask" "${counts/binding = 2/set = 1, binding = 2}" "$push" "$body"
render 1 "a binding in another set"
has "^$pos:5: error\[VRG-E064\]: binding 2 'Counts' is in set 1, but pass 'probe' \(plugin reflect_probe\) binds set 0 only$" "set 1"

write_shader "$color" "$mask" "$counts" "${push/vec4 tint;/vec4 tint; vec4 more;}" "$body"
render 1 "push constants larger than the dispatch's"
has "^$pos:6: error\[VRG-E067\]: push-constant block 'Push' is 32 bytes, but pass 'probe' \(plugin reflect_probe\) pushes 16 \(vrg_dispatch_desc.push_size\): set push_size 0 to push by name \(vrg_push_float\)$" "push block too big"
# a C struct larger than the block (16 bytes pushed, an 8-byte block): the
# members' offsets cannot agree
write_shader "$color" "$mask" "$counts" "${push/vec4 tint;/vec2 tint;}" "${body/push.tint/push.tint.xyxy}"
render 1 "push_size larger than the block"
has "^$pos:6: error\[VRG-E067\]: push-constant block 'Push' is 8 bytes, but pass 'probe' \(plugin reflect_probe\) pushes 16 \(vrg_dispatch_desc.push_size\)" "push struct larger than the block"

write_shader "$color" "$mask" "" "$push" 'ivec2 p = ivec2(gl_GlobalInvocationID.xy); imageStore(color_img, p, push.tint); imageStore(mask_img, p, vec4(1));'
render 0 "a bound slot the shader does not declare"
has "^$pos: warning\[VRG-W004\]: slot 'out.counts' of pass 'probe' \(plugin reflect_probe\) is bound at binding 2, which the shader does not declare$" "unused slot warning"

# readonly / writeonly against the slot's access (VRG-E068, VRG-W005); a
# buffer's qualifiers are on its block's members
write_shader "${color/writeonly/readonly}" "$mask" "$counts" "$push" 'ivec2 p = ivec2(gl_GlobalInvocationID.xy); imageStore(mask_img, p, imageLoad(color_img, p) + push.tint); counts[0] = 1u;'
render 1 "a readonly image bound for writing"
has "^$pos:3: error\[VRG-E068\]: binding 0 'color_img' is declared readonly, but slot 'out.color' of pass 'probe' \(plugin reflect_probe\) is bound with storage-write access$" "readonly output"
write_shader "${color/writeonly /}" "$mask" "$counts" "$push" "$body"
render 0 "an output image without writeonly"
has "^$pos:3: warning\[VRG-W005\]: binding 0 'color_img' is declared neither readonly nor writeonly, but slot 'out.color' .* is bound with storage-write access: declare it writeonly$" "missing writeonly"
write_shader "$color" "$mask" "${counts/writeonly /readonly }" "$push" 'ivec2 p = ivec2(gl_GlobalInvocationID.xy); imageStore(color_img, p, push.tint + float(counts[0])); imageStore(mask_img, p, vec4(1));'
render 1 "a readonly buffer bound for writing"
has "^$pos:5: error\[VRG-E068\]: binding 2 'Counts' is declared readonly, but slot 'out.counts' .* is bound with storage-write access$" "readonly buffer output"
write_shader "$color" "$mask" "${counts/writeonly /}" "$push" "$body"
render 0 "an output buffer without writeonly"
has "^$pos:5: warning\[VRG-W005\]: binding 2 'Counts' is declared neither readonly nor writeonly" "missing writeonly on a buffer"

# a dispatch the plugin does not list is refused at run time
write_shader "$color" "$mask" "$counts" "$push" "$body"
env VOXRG_SHADER_PATH="$out/sh" "$voxrg" render "$graph" --out "$out/img" --set probe.push_bytes=20 >"$out/stdout" 2>"$out/stderr"
[ $? -eq 1 ] && grep -qE "error\[VRG-E061\]: pass 'probe' \(plugin [^)]*\): dispatch of reflect.comp \(defines '', push_size 20\) is none of the 1 its plugin lists in vrg_plugin_desc.dispatches" "$out/stderr" &&
    ok || { bad "an unlisted dispatch ran"; cat "$out/stderr"; }

# a GLSL error is found by check, before any frame, without a device
write_shader "$color" "$mask" "$counts" "$push" "$body undeclared_name = 1;"
render 1 "a shader that does not compile"
has "^$pos:7: error\[VRG-E063\]" "the compile error at its line"

echo "test_reflect: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
