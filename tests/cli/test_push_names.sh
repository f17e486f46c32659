#!/usr/bin/env bash
# Binding by name in a C pass (docs/plugin-abi.md, "Push constants and
# bindings by name"): the push_probe plugin dispatches push.comp with
# push_size 0, so its push-constant block is packed by member name from the
# pass's parameters and the values it sets (vrg_push_uint); a member without
# a value, of another type, or a value naming no member is an error at the
# shader's FILE:LINE naming the member (VRG-E082), and a pair of same-typed
# bindings named after slots but swapped is an error naming both (VRG-E083).
# The shaders are written here and found through $VOXRG_SHADER_PATH.
# Usage: test_push_names.sh VOXRG TESTS_DIR OUT_DIR
set -u
voxrg=$1 tests=$2 out=$3
rm -rf "$out" && mkdir -p "$out/sh"
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }
graph="$tests/graphs/push_probe.ini"
pos="$out/sh/push.comp"
render() { # want_rc description [options...]
    local want=$1 what=$2; shift 2
    env VOXRG_SHADER_PATH="$out/sh" "$voxrg" render "$graph" --validate --out "$out/img" "$@" >"$out/stdout" 2>"$out/stderr"
    local rc=$?
    if [ "$rc" -eq "$want" ]; then ok; else bad "$what: exit $rc, want $want"; cat "$out/stderr"; fi
}
check() { # want_rc description: voxrg check --no-device (compiles and reflects the listed dispatch)
    env VOXRG_SHADER_PATH="$out/sh" "$voxrg" check "$graph" --no-device >"$out/check_stdout" 2>"$out/check_stderr"
    local rc=$?
    if [ "$rc" -eq "$1" ]; then ok; else bad "$2 (check --no-device): exit $rc, want $1"; cat "$out/check_stderr"; fi
}
has() { # file pattern description
    if grep -qE -- "$2" "$out/$1"; then ok; else bad "$3 ($1): no '$2' in"; sed 's/^/    /' "$out/$1" | head -20; fi
}
# write_shader BINDINGS MEMBERS: the output bindings at lines 3-4, the
# block's members one a line from line 7
write_shader() {
    cat >"$pos" <<GLSL
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
$1
layout(std430, binding = 2) writeonly buffer Values { uint words[4]; } out_values;
layout(push_constant) uniform Push {
$2
} push;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(out_color, p, vec4(1.0, 0.0, 0.0, 1.0));
    imageStore(out_mask, p, vec4(0.0, 1.0, 0.0, 1.0));
    if (p == ivec2(0)) {
        out_values.words[0] = floatBitsToUint(push.gain);
        out_values.words[1] = uint(push.steps);
        out_values.words[2] = push.frame_index;
        out_values.words[3] = $3;
    }
}
GLSL
}
outputs='layout(binding = 0, rgba16f) uniform writeonly image2D out_color;
layout(binding = 1, rgba16f) uniform writeonly image2D out_mask;'
members='    uint frame_index;
    float gain;
    int steps;'

# the members in another order than any C struct would have: each read at its offset
write_shader "$outputs" "$members" "0u"
render 0 "members packed by name" --frames 3 --set probe.gain=0.25 --set probe.steps=7 --dump values
check 0 "members packed by name"
if [ -f "$out/img/values.bin" ]; then
    words=$(od -An -tx4 -v "$out/img/values.bin" | tr -s ' ' | sed 's/^ //')
    # 0.25f, 7, the third frame's index 2, 0
    if [ "$words" = "3e800000 00000007 00000002 00000000" ]; then ok; else bad "the shader read '$words'"; fi
else
    bad "no values.bin"
fi

# a member the pass has neither a parameter nor a value for (a typo)
write_shader "$outputs" "    uint frame_index;
    float gains;
    int steps;" "0u"
sed -i 's/push\.gain)/push.gains)/' "$pos"
render 1 "a member named after no parameter"
has stderr "^$pos:8: error\[VRG-E082\]: push-constant member 'gains' has no value: pass 'probe' \(plugin push_probe\) has no parameter 'gains' and set none with vrg_push_\* before this dispatch$" "the member without a value at its line"

# a parameter of another type than its member: found by check before any frame
write_shader "$outputs" "    uint frame_index;
    int gain;
    int steps;" "0u"
sed -i 's/floatBitsToUint(push\.gain)/uint(push.gain)/' "$pos"
render 1 "an int member for a float parameter"
has stderr "^$pos:8: error\[VRG-E082\]: push-constant member 'gain' is a int, but parameter 'gain' of pass 'probe' \(plugin push_probe\) is a float$" "the type mismatch at the member's line"
check 1 "an int member for a float parameter"
has check_stderr "^$pos:8: error\[VRG-E082\]: push-constant member 'gain' is a int" "check finds the type mismatch"

# a value the pass computes, of another type than its member
write_shader "$outputs" "    float frame_index;
    float gain;
    int steps;" "0u"
sed -i 's/= push\.frame_index;/= uint(push.frame_index);/' "$pos"
render 1 "a float member set with vrg_push_uint"
has stderr "^$pos:7: error\[VRG-E082\]: push-constant member 'frame_index' is a float, but pass 'probe' \(plugin push_probe\) sets it with vrg_push_uint, a uint$" "the setter's type at the member's line"

# a value set that names no member
write_shader "$outputs" "$members" "0u"
render 1 "a value naming no member" --set probe.set_extra=1
has stderr "^$pos:6: error\[VRG-E082\]: pass 'probe' \(plugin push_probe\) sets 'extra' \(vrg_push_float\), but push-constant block 'Push' has no member 'extra' \(its members: frame_index, gain, steps\)$" "the unknown name at the block's line"
# ... which the block may declare
write_shader "$outputs" "$members
    float extra;" "floatBitsToUint(push.extra)"
render 0 "a value the block declares" --set probe.set_extra=1 --dump values
words=$(od -An -tx4 -v "$out/img/values.bin" 2>/dev/null | tr -s ' ' | sed 's/^ //')
if [ "$words" = "3f000000 00000003 00000000 3f800000" ]; then ok; else bad "extra: the shader read '$words'"; fi

# a value set after the last dispatch: no dispatch reads it
write_shader "$outputs" "$members" "0u"
render 1 "a value set after the last dispatch" --set probe.set_late=1
has stderr "error\[VRG-E062\]: pass 'probe' \(plugin [^)]*\): 'frame_index' was set with vrg_push_uint after the pass's last dispatch: no dispatch read it" "the value no dispatch read"

# an array member, set by the pass (vrg_push_floats) with its length
write_shader "$outputs" "$members
    float weights[2];" "floatBitsToUint(push.weights[1])"
render 0 "an array member" --set probe.set_array=2 --dump values
words=$(od -An -tx4 -v "$out/img/values.bin" 2>/dev/null | tr -s ' ' | sed 's/^ //')
if [ "$words" = "3f000000 00000003 00000000 3f400000" ]; then ok; else bad "array: the shader read '$words'"; fi
render 1 "an array set with another count" --set probe.set_array=3
has stderr "^$pos:10: error\[VRG-E082\]: push-constant member 'weights' is an array of 2 float, but pass 'probe' \(plugin push_probe\) sets it with vrg_push_floats, 3 float$" "the array's count at its line"
render 1 "an array no value fills"
has stderr "^$pos:10: error\[VRG-E082\]: push-constant member 'weights' \(an array of 2\) has no value" "the unset array at its line"

# a vector member cannot be packed by name
write_shader "$outputs" "$members
    vec2 extra;" "0u"
render 1 "a vector member"
has stderr "^$pos:10: error\[VRG-E082\]: push-constant member 'extra' is not a scalar float, int, uint or bool" "the vector member at its line"

# bound by the shader's names: the bindings in any order (the buffer first)
write_shader 'layout(binding = 1, rgba16f) uniform writeonly image2D out_color;
layout(binding = 2, rgba16f) uniform writeonly image2D out_mask;' "$members" "0u"
sed -i 's/binding = 2) writeonly buffer Values/binding = 0) writeonly buffer Values/' "$pos"
render 0 "bindings in another order than the slots, bound by name" --dump values
check 1 "the listed dispatch (color, mask, values at 0, 1, 2) does not fit that order"
words=$(od -An -tx4 -v "$out/img/values.bin" 2>/dev/null | tr -s ' ' | sed 's/^ //')
if [ "$words" = "3f000000 00000003 00000000 00000000" ]; then ok; else bad "by name: the shader read '$words'"; fi
# the output (color) red: written through its own name
python3 - "$out/img/color.png" "$(dirname "$0")" <<'PY' && ok || bad "by name: color is not red"
import sys
sys.path.insert(0, sys.argv[2])
import png_pixels
_, _, pixel = png_pixels.load(sys.argv[1])
sys.exit(0 if tuple(pixel(0, 0))[:3] == (255, 0, 0) else 1)
PY

# two same-typed bindings swapped (same format, same access) where the pass
# lists its bindings: every other check passes; the names find the swap
write_shader 'layout(binding = 0, rgba16f) uniform writeonly image2D out_mask;
layout(binding = 1, rgba16f) uniform writeonly image2D out_color;' "$members" "0u"
render 1 "two same-typed bindings swapped" --set probe.listed=1
has stderr "^$pos:3: error\[VRG-E083\]: bindings 0 'out_mask' and 1 'out_color' \($pos:4\) are swapped: pass 'probe' \(plugin push_probe\) binds slot 'out.color' at binding 0 and slot 'out.mask' at 1$" "the swapped pair, both lines"
check 1 "two same-typed bindings swapped"
has check_stderr "^$pos:3: error\[VRG-E083\]: bindings 0 'out_mask' and 1 'out_color' \($pos:4\) are swapped" "check finds the swap"
# one named after a slot bound elsewhere
write_shader 'layout(binding = 0, rgba16f) uniform writeonly image2D out_mask;
layout(binding = 1, rgba16f) uniform writeonly image2D out_other;' "$members" "0u"
sed -i 's/imageStore(out_color,/imageStore(out_other,/' "$pos"
render 1 "a binding named after a slot bound elsewhere"
has stderr "^$pos:3: error\[VRG-E083\]: binding 0 'out_mask' is named after slot 'out.mask', but pass 'probe' \(plugin push_probe\) binds slot 'out.color' there$" "the misnamed binding"

# An internal resource (vrg_pass_request_image) bound by name, its access
# the shader's: scratch = 1 dispatches push.comp with FIRST, which writes
# the internal image 'scratch' through out_scratch, then with SECOND, which
# reads it through in_scratch (a readonly storage image, then a sampler:
# the pass says neither) and copies it to color. The shaders name no list.
# write_scratch READ FETCH: SECOND's declaration of in_scratch and its read
write_scratch() {
    cat >"$pos" <<GLSL
#version 450
layout(local_size_x = 8, local_size_y = 8) in;
#if defined(FIRST)
layout(binding = 0, rgba16f) uniform writeonly image2D out_${3:-scratch};
#elif defined(SECOND)
$1
layout(binding = 1, rgba16f) uniform writeonly image2D out_color;
layout(binding = 2, rgba16f) uniform writeonly image2D out_mask;
layout(std430, binding = 3) writeonly buffer Values { uint words[4]; } out_values;
#else // the plugin's other dispatches, which check compiles too
layout(binding = 0, rgba16f) uniform writeonly image2D out_color;
layout(binding = 1, rgba16f) uniform writeonly image2D out_mask;
layout(std430, binding = 2) writeonly buffer Values { uint words[4]; } out_values;
#endif
layout(push_constant) uniform Push { uint frame_index; float gain; int steps; } push;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
#if defined(FIRST)
    imageStore(out_${3:-scratch}, p, vec4(0.0, 0.0, push.gain, 1.0));
#else
#if defined(SECOND)
    imageStore(out_color, p, $2);
#else
    imageStore(out_color, p, vec4(0.0));
#endif
    imageStore(out_mask, p, vec4(1.0));
    if (p == ivec2(0))
        out_values.words[0] = floatBitsToUint(push.gain) + uint(push.steps) + push.frame_index;
#endif
}
GLSL
}
blue() { # description: color is (0, 0, 255): the scratch image went through
    python3 - "$out/img/color.png" "$(dirname "$0")" <<'PY' && ok || bad "$1: color is not blue"
import sys
sys.path.insert(0, sys.argv[2])
import png_pixels
_, _, pixel = png_pixels.load(sys.argv[1])
sys.exit(0 if tuple(pixel(5, 5))[:3] == (0, 0, 255) else 1)
PY
}
write_scratch 'layout(binding = 0, rgba16f) uniform readonly image2D in_scratch;' 'imageLoad(in_scratch, p)'
rm -f "$out/img/color.png"
render 0 "an internal image written and read by name" --set probe.scratch=1 --set probe.gain=1
blue "an internal image read as a readonly storage image"
check 0 "an internal image bound by name"
has check_stdout "probe +push_probe +4 dispatches compiled and reflected; 2 bindings to internal resources checked with a device only" "check leaves the internal image to a device"
write_scratch 'layout(binding = 0) uniform sampler2D in_scratch;' 'texelFetch(in_scratch, p, 0)'
rm -f "$out/img/color.png"
render 0 "an internal image read through a sampler, its access the shader's" --set probe.scratch=1 --set probe.gain=1
blue "an internal image read as a sampler"
# in_/out_ names that match no slot and no internal resource: an error at
# the binding's line naming the pass's internal resources
write_scratch 'layout(binding = 0, rgba16f) uniform readonly image2D in_scratch;' 'imageLoad(in_scratch, p)' scratchy
render 1 "a binding named after nothing" --set probe.scratch=1
has stderr "^$pos:4: error\[VRG-E083\]: binding 0 'out_scratchy' is named after no slot or internal resource of pass 'probe' \(plugin push_probe\): it has no output slot 'scratchy', and its internal resources are scratch$" "the binding named after nothing, at its line"

echo "test_push_names: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
