#!/usr/bin/env bash
# The voxrg CLI: help and exit codes, `check` output (schedule, culled passes,
# resources, barriers, memory) and --dot, `render` files and JSON, `plugins`.
# Usage: test_cli.sh VOXRG TESTS_DIR OUT_DIR [SECTION]
# The sections below are independent: ctest runs each as its own test
# (cli_SECTION, each with its own OUT_DIR) so that they spread over the
# cores; without SECTION all run in order.
set -u
voxrg=$1 tests=$2 out=$3 only=${4:-all}
rm -rf "$out" && mkdir -p "$out"
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fail=$((fail + 1)); }
expect_rc() { # want_rc description cmd...
    local want=$1 what=$2; shift 2
    "$@" >"$out/stdout" 2>"$out/stderr"; local rc=$?
    if [ "$rc" -eq "$want" ]; then ok; else bad "$what: exit $rc, want $want"; cat "$out/stderr"; fi
}
# A section that cannot run here says why and checks nothing: run alone (as
# ctest runs it) the script exits 77, ctest's SKIP_RETURN_CODE.
skipped=
skip() { echo "skipped: $*"; skipped="$skipped $section"; }
has() { # file pattern description
    if grep -qE -- "$2" "$1"; then ok; else bad "$3: no '$2' in $1"; sed 's/^/    /' "$1" | head -40; fi
}

section_usage() { # help, exit codes and messages of bad arguments, long paths and names, --set
    expect_rc 0 "voxrg --help" "$voxrg" --help
    has "$out/stdout" "check GRAPH" "main help"
    for c in check render plugins; do
        expect_rc 0 "voxrg $c --help" "$voxrg" "$c" --help
        has "$out/stdout" "usage: voxrg $c" "$c help"
    done
    expect_rc 2 "no command" "$voxrg"
    expect_rc 2 "unknown command" "$voxrg" frobnicate
    expect_rc 2 "unknown option" "$voxrg" check "$tests/graphs/alias.ini" --bogus
    expect_rc 2 "bad --size" "$voxrg" render "$tests/graphs/alias.ini" --size 12by4
    has "$out/stderr" "--size '12by4': expected WxH, W and H whole numbers from 1 to 16384" "--size range in the message"
    expect_rc 2 "--size over the range" "$voxrg" render "$tests/graphs/alias.ini" --size 16385x4
    has "$out/stderr" "from 1 to 16384" "--size range in the message"
    expect_rc 2 "bench --size over the range" "$voxrg" bench --size 0x4
    has "$out/stderr" "from 1 to 16384" "bench --size range in the message"
    expect_rc 2 "bad --interval" "$voxrg" render "$tests/graphs/alias.ini" --interval soon
    has "$out/stderr" "--interval .soon.: expected milliseconds" "--interval message"
    expect_rc 2 "negative --frames" "$voxrg" render "$tests/graphs/alias.ini" --frames -1
    # the window's options: checked before any window opens, refused elsewhere
    expect_rc 2 "run --scale over 1" "$voxrg" run "$tests/graphs/alias.ini" --scale 2
    has "$out/stderr" "--scale '2': expected a number in \(0, 1\]" "--scale range in the message"
    expect_rc 2 "run --scale with --size" "$voxrg" run "$tests/graphs/alias.ini" --scale 0.5 --size 64x64
    has "$out/stderr" "--scale and --size both set the render size" "--scale and --size message"
    expect_rc 2 "run --filter unknown" "$voxrg" run "$tests/graphs/alias.ini" --filter cubic
    has "$out/stderr" "--filter 'cubic': expected nearest or bilinear" "--filter message"
    expect_rc 2 "render --window" "$voxrg" render "$tests/graphs/alias.ini" --window 64x64
    has "$out/stderr" "--window is an option of .voxrg run." "a window option given to render"
    expect_rc 1 "missing graph file" "$voxrg" check "$tests/graphs/does-not-exist.ini" --no-device
    has "$out/stderr" "cannot open graph file" "missing graph message"
    # any number of plugin folders: every one searched, none left out
    many=$(seq -f "$out/plugin_dir_%g" 40 | paste -sd:)
    expect_rc 1 "many plugin folders" env VOXRG_PLUGIN_PATH="$many" "$voxrg" plugins nonesuch
    has "$out/stderr" "plugin_dir_40 \(VOXRG_PLUGIN_PATH\)" "the 40th plugin folder is searched"
    # a FIFO as the graph file: refused at once, never waited on
    mkfifo "$out/fifo.ini"
    expect_rc 1 "FIFO as the graph file" timeout 20 "$voxrg" check "$out/fifo.ini" --no-device
    has "$out/stderr" "graph file '$out/fifo.ini' is not a regular file" "FIFO message"
    # a graph path over 1023 characters (deep folders) is read like any other
    deep="$out"
    while [ ${#deep} -lt 1100 ]; do deep="$deep/folder_with_a_long_name_for_the_path_length_test"; done
    mkdir -p "$deep" && cp "$tests/graphs/chain.ini" "$deep/chain.ini"
    expect_rc 0 "graph path over 1023 characters" "$voxrg" check "$deep/chain.ini" --no-device
    cp "$tests/bad/unknown_key.ini" "$deep/unknown_key.ini"
    expect_rc 1 "errors of a graph path over 1023 characters" "$voxrg" check "$deep/unknown_key.ini" --no-device
    has "$out/stderr" "^$deep/unknown_key.ini:[0-9]+: error\[VRG-E012\]: unknown key" "the whole path and the message"
    long=$(printf '%04100d' 0)
    expect_rc 1 "graph path over 4095 characters" "$voxrg" check "$out/$long.ini" --no-device
    has "$out/stderr" "graph path is longer than 4095 characters" "long path message"
    # --out deeper than 1023 characters: that folder, not a cut one
    expect_rc 0 "render --out over 1023 characters" "$voxrg" render "$tests/graphs/chain.ini" --size 8x8 --out "$deep/render"
    if [ -s "$deep/render/$(sed -n 's/^output *= *//p' "$tests/graphs/chain.ini").png" ]; then ok; else bad "render --out over 1023 characters: no PNG in $deep/render"; fi
    # names at the documented limit render
    expect_rc 0 "63-character names" "$voxrg" render "$tests/graphs/long_names.ini" --validate --frames 2 --out "$out/long_names"
    if [ -s "$out/long_names/$(printf 'r%.0s' $(seq 63)).png" ]; then ok; else bad "63-character names: no output PNG"; ls "$out/long_names"; fi
    expect_rc 1 "unknown --set parameter" "$voxrg" check "$tests/graphs/alias.ini" --no-device --set gen.nope=1
    has "$out/stderr" "has no parameter 'nope'" "--set unknown parameter"
    expect_rc 1 "out-of-range --set" "$voxrg" check "$tests/graphs/alias.ini" --no-device --set gen.value=5
    has "$out/stderr" "out of range" "--set range"
}

section_check_render() { # check's report and --dot, render's files and JSON, output files on a full disk, fixed tables
    # check: a multi-pass graph with a culled pass, aliasing and barriers
    expect_rc 0 "check alias.ini" "$voxrg" check "$tests/graphs/alias.ini" --validate --dot "$out/alias.dot"
    has "$out/stdout" "^schedule:" "check schedule"
    has "$out/stdout" "^culled passes:" "check culled header"
    has "$out/stdout" "^  unused .*reach neither" "check culled pass"
    has "$out/stdout" "^resources:" "check resources"
    has "$out/stdout" "lifetime [0-9]+\.\.[0-9]+" "check lifetimes"
    has "$out/stdout" "block 0 @ [0-9]+" "check placement"
    has "$out/stdout" "aliased" "check alias marker"
    has "$out/stdout" "^barriers" "check barriers"
    has "$out/stdout" "COMPUTE/STORAGE_WRITE -> COMPUTE/SAMPLED_READ  GENERAL -> SHADER_READ_ONLY" "check read-after-write barrier"
    has "$out/stdout" "^memory: transient naive .*aliased .*saved [1-9][0-9]*\.[0-9]%" "check memory line"
    has "$out/alias.dot" "^digraph" "dot file"
    has "$out/alias.dot" "style=dashed" "dot culled pass"
    # a culled pass is a warning at its line in every command that loads the graph
    culled="^$tests/graphs/alias.ini:36: warning\[VRG-W008\]: pass 'unused' is culled \(not run\): no pass reads its outputs \('nobody_reads'\)"
    has "$out/stderr" "$culled" "check warns of the culled pass"
    expect_rc 0 "render alias.ini" "$voxrg" render "$tests/graphs/alias.ini" --validate --frames 1 --out "$out/alias"
    has "$out/stderr" "$culled" "render warns of the culled pass"
    expect_rc 0 "compare alias.ini" "$voxrg" compare "$tests/graphs/alias.ini" --reference "$tests/graphs/alias.ini" --frames 1 --warmup 0 \
        --size 16x16 --out "$out/alias_compare" --cache "$out/alias_cache"
    has "$out/stderr" "$culled" "compare warns of the culled pass"
    # culled because its only reader is culled: that reader named
    expect_rc 0 "check shadow_denoise.ini" "$voxrg" check "$tests/graphs/shadow_denoise.ini" --no-device
    has "$out/stderr" "shadow_denoise.ini:30: warning\[VRG-W008\]: pass 'shadow' is culled \(not run\): its outputs \('shadow.visibility', 'shadow.occluder'\) are read only by passes culled themselves \('denoise'\)" "culled reader named"

    # check without a device gives the same schedule
    expect_rc 0 "check --no-device" "$voxrg" check "$tests/graphs/history.ini" --no-device
    has "$out/stdout" "@prev" "history resource listed"
    has "$out/stdout" "x2 \(history\)" "history memory"

    # render: PNG, dumps, JSON timings, progress line
    expect_rc 0 "render chain.ini" "$voxrg" render "$tests/graphs/chain.ini" --validate --frames 3 --size 40x24 --out "$out/r" --json "$out/r.json" --dump gradient
    has "$out/stderr" "frame 3/3" "progress line"
    for f in "$out/r/final.png"; do
        if [ -s "$f" ] && [ "$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; then ok; else bad "no PNG $f"; fi
    done
    # a dumped image is OpenEXR by default (its magic number)
    if [ -s "$out/r/gradient.exr" ] && [ "$(head -c 4 "$out/r/gradient.exr" | od -An -tx1 | tr -d ' \n')" = "762f3101" ]; then ok; else bad "no OpenEXR $out/r/gradient.exr"; fi
    if python3 - "$out/r.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["frames"] == 3 and d["width"] == 40 and d["height"] == 24, d
names = [p["name"] for p in d["passes"]]
assert names and all(len(p["gpu_ms"]) == 3 for p in d["passes"]), d
assert all(x >= 0 for p in d["passes"] for x in p["gpu_ms"]), d
assert d["memory"]["transient_aliased_bytes"] <= d["memory"]["transient_naive_bytes"], d
PY
    then ok; else bad "render JSON"; fi
    expect_rc 1 "dump of an unknown resource" "$voxrg" render "$tests/graphs/chain.ini" --dump nonesuch --out "$out/r2"
    has "$out/stderr" "nonesuch" "dump error names the resource"

    # output files: written whole or not at all, errors with the system's reason
    # (a full disk: /dev/full, or the file size limit where no device is
    # opened, since lavapipe's memory is a file that the limit caps too)
    if [ -c /dev/full ]; then
        expect_rc 1 "check --dot on a full disk" "$voxrg" check "$tests/graphs/chain.ini" --no-device --dot /dev/full
        has "$out/stderr" "cannot write /dev/full: No space left on device" "--dot full disk message"
        expect_rc 1 "render --json on a full disk" "$voxrg" render "$tests/graphs/chain.ini" --size 40x24 --out "$out/full" --json /dev/full
        has "$out/stderr" "cannot write /dev/full: No space left on device" "--json full disk message"
        mkdir -p "$out/full_png" && ln -sf /dev/full "$out/full_png/final.png"
        expect_rc 1 "render PNG on a full disk" "$voxrg" render "$tests/graphs/chain.ini" --size 40x24 --out "$out/full_png"
        has "$out/stderr" "cannot write $out/full_png/final.png: No space left on device" "PNG full disk message"
    fi
    # a real full file system: a 64 KiB tmpfs in a private mount namespace,
    # filled but for the old file (plugins' private copies go to $TMPDIR, which
    # is not full; `ulimit -f` would stop those too)
    if unshare -rm true 2>/dev/null; then
        mkdir -p "$out/fullfs"
        unshare -rm sh -c 'mount -t tmpfs -o size=64k voxrg-full "$1" && cp "$2" "$1/good.dot" &&
            { head -c 1048576 /dev/zero > "$1/filler" 2>/dev/null; true; } &&
            "$3" check "$4" --no-device --dot "$1/good.dot" >/dev/null; echo "rc=$?"; cmp -s "$2" "$1/good.dot" && echo same;
            ls -A "$1"' sh "$out/fullfs" "$out/alias.dot" "$voxrg" "$tests/graphs/chain.ini" >"$out/stdout" 2>"$out/stderr"
        has "$out/stdout" "^rc=1$" "check --dot on a full file system exits 1"
        has "$out/stderr" "cannot write $out/fullfs/good.dot: No space left on device" "--dot on a full file system names the reason"
        has "$out/stdout" "^same$" "a failed --dot write keeps the old file"
        if grep -qvE "^(rc=1|same|good.dot|filler)$" "$out/stdout"; then bad "temporary files left on the full file system: $(cat "$out/stdout")"; else ok; fi
        # a noexec $TMPDIR: plugins' private copies go to memory instead
        mkdir -p "$out/noexec"
        unshare -rm sh -c 'mount -t tmpfs -o noexec,size=1m voxrg-noexec "$1" && TMPDIR="$1" "$2" plugins pattern' sh "$out/noexec" "$voxrg" \
            >"$out/stdout" 2>"$out/stderr"
        has "$out/stdout" "^pattern \(pass plugin" "a plugin loads with a noexec \$TMPDIR"
    else
        echo "note: no mount namespace here (unshare -rm): the full file system case is covered by test_output only"
    fi
    # fixed tables of the command line fail with the limit named, never drop
    many=$(for i in $(seq 33); do printf 'r%d,' "$i"; done)
    expect_rc 2 "--dump of 33 resources" "$voxrg" render "$tests/graphs/chain.ini" --dump "${many%,}"
    has "$out/stderr" "--dump: more than 32 resources" "--dump limit message"
    many=$(for i in $(seq 65); do printf 'gen.value=0.5,'; done)
    expect_rc 1 "compare --variant with 65 overrides" "$voxrg" compare "$tests/graphs/chain.ini" --reference "$tests/graphs/chain.ini" --out "$out/cmp_many" --variant "v:${many%,}"
    has "$out/stderr" "more than 64 overrides" "--variant override limit message"
    # an unwritable --out or --json folder: found before the first frame
    : >"$out/a_file"
    expect_rc 1 "render --out under a file" "$voxrg" render "$tests/graphs/chain.ini" --frames 3 --size 40x24 --out "$out/a_file/r"
    has "$out/stderr" "$out/a_file/r: Not a directory" "--out message"
    if grep -q "frame 3/3" "$out/stderr"; then bad "--out checked only after rendering"; else ok; fi
    expect_rc 1 "render --json under a file" "$voxrg" render "$tests/graphs/chain.ini" --frames 3 --size 40x24 --out "$out/r3" --json "$out/a_file/r.json"
    has "$out/stderr" "cannot write in $out/a_file: Not a directory" "--json folder message"
    if grep -q "frame 3/3" "$out/stderr"; then bad "--json folder checked only after rendering"; else ok; fi
}

section_killed() { # kill -9 during render --sequence
    # kill -9 during `render --sequence`: no temporary file left, every frame whole
    # (dumps too: more of each frame's time is spent writing files)
    mkdir -p "$out/killed"
    for run in 1 2 3 4 5; do
        rm -f "$out/killed"/final-0000[0-4].png # the run's first frames: it has started writing once they are back
        "$voxrg" render "$tests/graphs/chain.ini" --sequence --frames 0 --interval 0 --size 320x180 \
            --dump gradient,blurred --dump-format png --out "$out/killed" >/dev/null 2>&1 &
        for _ in $(seq 600); do [ -e "$out/killed/final-00001.png" ] && break; sleep 0.1; done
        sleep "0.$((RANDOM % 10))$((RANDOM % 10))"
        kill -9 $! && wait $! 2>/dev/null
    done
    if python3 - "$out/killed" <<'PY'
import os, re, struct, sys, zlib
names = sorted(os.listdir(sys.argv[1]))
frames = [n for n in names if re.fullmatch(r"(final|gradient|blurred)-\d{5}\.png", n)]
assert frames, names                                     # the runs got to write frames
assert not [n for n in names if n not in frames], names  # no *.part, no hidden temporary files
for n in frames:  # whole: every chunk's CRC right, IEND last, all the rows there
    data, i, idat, kinds = open(os.path.join(sys.argv[1], n), "rb").read(), 8, b"", []
    while i < len(data):
        size, kind = struct.unpack(">I4s", data[i:i + 8])
        body = data[i + 8:i + 8 + size]
        assert zlib.crc32(kind + body) == struct.unpack(">I", data[i + 8 + size:i + 12 + size])[0], (n, kind)
        idat += body if kind == b"IDAT" else b""
        kinds.append(kind)
        i += 12 + size
    w, h = struct.unpack(">II", data[16:24])
    assert kinds[-1] == b"IEND" and (w, h) == (320, 180) and len(zlib.decompress(idat)) == h * (w * 3 + 1), n
print(len(frames), "frames whole")
PY
    then ok; else bad "frames of killed --sequence runs"; fi
}

section_json_shaders() { # --json-frames, --validate, shader #include and errors
    # --json under a long run: per-frame lists of the last --json-frames frames, means of all
    expect_rc 2 "bad --json-frames" "$voxrg" render "$tests/graphs/chain.ini" --json-frames 0
    expect_rc 0 "render --json-frames" "$voxrg" render "$tests/graphs/chain.ini" --frames 6 --size 16x16 --json "$out/ring.json" --json-frames 4 --out "$out/ring"
    expect_rc 0 "render --json-frames above --frames" "$voxrg" render "$tests/graphs/chain.ini" --frames 6 --size 16x16 --json "$out/all.json" --json-frames 6 --out "$out/ring"
    if python3 - "$out/ring.json" "$out/all.json" <<'PY'
import json, sys
ring, full = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
assert ring["frames"] == 6 and ring["frames_dropped"] == 2, ring
assert full["frames"] == 6 and full["frames_dropped"] == 0, full
assert ring["passes"] and all(len(p["gpu_ms"]) == 4 for p in ring["passes"]), ring
for p in full["passes"]:  # the means: every frame's, kept or not
    assert len(p["gpu_ms"]) == 6 and abs(p["mean_gpu_ms"] - sum(p["gpu_ms"]) / 6) < 1e-3, p
PY
    then ok; else bad "--json-frames"; fi
    # --validate: a validation message fails the run
    expect_rc 1 "render with a hazard under --validate" "$voxrg" render "$tests/graphs/hazard.ini" --validate --out "$out/hz"
    has "$out/stderr" "SYNC-HAZARD-WRITE.AFTER.WRITE" "sync validation names the hazard"
    has "$out/stderr" "validation message" "validation summary"

    # shaders: #include resolution and compile errors naming FILE:LINE
    mkdir -p "$out/sh"
    cat >"$out/sh/inc.glsl" <<'GLSL'
// included
vec4 shade(ivec2 p) { return vec4(0.25, 0.5, 1.0, 1.0); }
GLSL
    cat >"$out/sh/user.comp" <<'GLSL'
#version 450
#include "inc.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba16f) uniform writeonly image2D dst;
void main() { imageStore(dst, ivec2(gl_GlobalInvocationID.xy), shade(ivec2(0))); }
GLSL
    expect_rc 0 "shader with #include" env VOXRG_SHADER_PATH="$out/sh" "$voxrg" render "$tests/graphs/shader_file.ini" --validate --out "$out/sh_ok"
    sed -i 's/return vec4/return vec3/' "$out/sh/inc.glsl"   # a type error on line 2 of the include
    expect_rc 1 "shader error in an include" env VOXRG_SHADER_PATH="$out/sh" "$voxrg" render "$tests/graphs/shader_file.ini" --validate --out "$out/sh_bad"
    has "$out/stderr" "^$out/sh/inc.glsl:2: error\[VRG-E063\]:" "include error names the included file and line"
    printf '#version 450\nlayout(local_size_x = 8) in;\nvoid main() { undefined_call(); }\n' >"$out/sh/user.comp"
    expect_rc 1 "shader error in the main file" env VOXRG_SHADER_PATH="$out/sh" "$voxrg" render "$tests/graphs/shader_file.ini" --out "$out/sh_bad2"
    has "$out/stderr" "^$out/sh/user.comp:3: error\[VRG-E063\]:.*undefined_call" "main-file error names file and line"
    has "$out/stderr" "shader_file.ini:8: error\[VRG-E060\]: pass 'user'" "the failing pass is named at its line"
    # a shader's text quoted in a message is escaped: no terminal control from the file
    printf '#version 450\n#include "no\033[2Jsuch.glsl"\nlayout(local_size_x = 8) in;\nvoid main() { }\n' >"$out/sh/user.comp"
    expect_rc 1 "an #include name with an escape" env VOXRG_SHADER_PATH="$out/sh" "$voxrg" render "$tests/graphs/shader_file.ini" --out "$out/sh_bad3"
    has "$out/stderr" "^$out/sh/user.comp:2: error\[VRG-E063\]: cannot find include file \"no\\\\x1b\[2Jsuch.glsl\"$" "the include's name escaped"
}

section_camera_device() { # camera paths, determinism of the terrain, ray query, --device, plugins beside a graph
    # --camera: a path moves the camera; a bad path names FILE:LINE
    expect_rc 0 "render still" "$voxrg" render "$tests/graphs/blocks_wall.ini" --validate --out "$out/still"
    printf '# two keys\n0 16 30 60 10 -20\n1 20 25 50 30 -30\n' >"$out/move.path"
    expect_rc 0 "render --camera" "$voxrg" render "$tests/graphs/blocks_wall.ini" --validate --camera "$out/move.path" --frames 2 --out "$out/moved"
    if cmp -s "$out/still/view.png" "$out/moved/view.png"; then bad "--camera did not move the camera"; else ok; fi
    printf '0 1 2 3 4 5\n0.5 1 2 three 4 5\n' >"$out/bad.path"
    expect_rc 1 "render --camera bad path" "$voxrg" render "$tests/graphs/blocks_wall.ini" --camera "$out/bad.path" --out "$out/badcam"
    has "$out/stderr" "^$out/bad.path:2: error:" "bad path names FILE:LINE"
    expect_rc 1 "render --camera missing" "$voxrg" render "$tests/graphs/blocks_wall.ini" --camera "$out/none.path" --out "$out/badcam"
    has "$out/stderr" "none.path" "missing path named"

    # determinism: the same graph gives the same image whatever the thread count
    expect_rc 0 "terrain, 1 thread" "$voxrg" render "$tests/../graphs/terrain-debug.ini" --size 64x36 --set scene.radius=3 --set scene.threads=1 --out "$out/t1"
    expect_rc 0 "terrain, 2 threads" "$voxrg" render "$tests/../graphs/terrain-debug.ini" --size 64x36 --set scene.radius=3 --set scene.threads=2 --out "$out/t2"
    if cmp -s "$out/t1/view.png" "$out/t2/view.png"; then ok; else bad "terrain image differs between 1 and 2 generator threads"; fi
    expect_rc 0 "terrain, other seed" "$voxrg" render "$tests/../graphs/terrain-debug.ini" --size 64x36 --set scene.radius=3 --set scene.seed=99 --out "$out/t3"
    if cmp -s "$out/t1/view.png" "$out/t3/view.png"; then bad "the seed does not change the terrain"; else ok; fi
    expect_rc 1 "terrain, bad stream mode" "$voxrg" check "$tests/../graphs/terrain-debug.ini" --no-device --set scene.stream=sometimes
    has "$out/stderr" "expected wait or budget" "stream mode error"

    # the ray-query backend builds its BLASes and TLAS under synchronization validation
    if "$voxrg" check "$tests/graphs/chain.ini" 2>&1 | grep -q "ray query yes"; then
        expect_rc 0 "terrain with traversal = rayquery" "$voxrg" render "$tests/../graphs/terrain-debug.ini" --validate --size 64x36 --frames 2 \
            --set scene.radius=3 --set scene.traversal=rayquery --json "$out/trq.json" --out "$out/trq"
        has "$out/trq.json" '"tlas_instances": [1-9]' "TLAS instances"
    else
        echo "skipped: no VK_KHR_ray_query on this device"
    fi

    # --device by name and by index; a device that does not exist
    expect_rc 0 "--device by name" "$voxrg" check "$tests/graphs/chain.ini" --device llvmpipe
    has "$out/stderr" "device llvmpipe" "chosen device"
    expect_rc 0 "--device by index" "$voxrg" check "$tests/graphs/chain.ini" --device 0
    expect_rc 1 "--device unknown" "$voxrg" check "$tests/graphs/chain.ini" --device no-such-gpu
    has "$out/stderr" "matches no device" "unknown device message"
    has "$out/stderr" "0: " "device list"

    # a plugin beside the graph never shadows a built-in one (issue 15's policy;
    # tests/cli/test_plugin_faults.py has the rest): the build's pattern is used, and
    # a note says the graph's copy is not
    mkdir -p "$out/rel/plugins"
    sed 's/^\[graph\]$/[graph]\nplugin_path = plugins/' "$tests/graphs/chain.ini" > "$out/rel/chain.ini"
    cp "$(dirname "$voxrg")/plugins/pattern.so" "$out/rel/plugins/"
    expect_rc 0 "graph-relative plugin" "$voxrg" check "$out/rel/chain.ini" --no-device
    has "$out/stdout" "plugin pattern .*$(dirname "$voxrg")/plugins/pattern.so" "the built-in plugin is used"
    has "$out/stderr" "$out/rel/plugins/pattern.so .*is not used" "the graph's copy is said to be ignored"

    # --camera: paths refuse what graph files refuse (hex) and positions
    # outside the world, naming FILE:LINE
    printf '0 0 40 0 0 0\n0x2 0 40 0 0 0\n' >"$out/hex.path"
    expect_rc 1 "render --camera hex path" "$voxrg" render "$tests/graphs/blocks_wall.ini" --camera "$out/hex.path" --out "$out/badcam"
    has "$out/stderr" "hex\.path:2: error: '0x2' is not a decimal number" "hex path message"
    printf '0 0 40 0 0 0\n1 3e9 40 0 0 0\n' >"$out/far.path"
    expect_rc 1 "render --camera far path" "$voxrg" render "$tests/graphs/blocks_wall.ini" --camera "$out/far.path" --out "$out/badcam"
    has "$out/stderr" "far\.path:2: error: position 3e9 40 0 is outside the world" "far path message"
}

section_bench() { # bench --smoke
    # bench: a smoke run (no timing assertion), JSON complete and well-formed
    expect_rc 0 "bench --help" "$voxrg" bench --help
    expect_rc 2 "bench unknown suite" "$voxrg" bench --suite nonesuch
    expect_rc 2 "bench bad size" "$voxrg" bench --size huge
    expect_rc 1 "bench --graphs naming a missing graph" "$voxrg" bench --suite frame --smoke --graphs raw.ini,nonesuch.ini
    has "$out/stderr" "--graphs: 'nonesuch.ini' is not a graph in .*graphs" "bench --graphs names the missing graph"
    expect_rc 0 "bench --smoke" "$voxrg" bench --smoke --json "$out/bench.json"
    has "$out/stdout" "smoke: tiny inputs" "bench smoke says so"
    if python3 - "$out/bench.json" "$tests/../graphs" <<'PY'
import json, os, sys
d = json.load(open(sys.argv[1]))
figs = d["figures"]
def model_missing(g):  # bench skips a vox graph whose model is not beside the project (docs/world.md)
    for line in open(os.path.join(sys.argv[2], g)):
        k, _, v = line.partition("=")
        if k.strip() == "file" and v.strip().endswith(".vox"):
            return not os.path.exists(os.path.join(sys.argv[2], v.strip()))
    return False
graphs = sorted(f for f in os.listdir(sys.argv[2]) if f.endswith(".ini") and not model_missing(f))
assert d["device"] and d["smoke"] is True and d["size"] == [64, 36], d
assert d["suites"] == ["rays", "graph", "memory", "terrain", "reload", "frame"], d["suites"]
for f in figs:
    assert f["samples"] >= 1 and f["min"] <= f["median"] <= f["max"], f
names = {s: [f["name"] for f in figs if f["suite"] == s] for s in d["suites"]}
# rays: time and Mrays/s of four ray types per backend
assert len(names["rays"]) in (8, 16) and all(any(k in n for n in names["rays"]) for k in ("primary", "sun shadow", "AO", "indirect")), names["rays"]
# graph: compile, runtime, baseline, the scene's share, without it, ratio, overheads
assert len(names["graph"]) == 8 and any("baseline" in n for n in names["graph"]) and any("compile" in n for n in names["graph"]), names["graph"]
# memory: naive, aliased, saved, history for every shipped graph at two sizes
assert len(names["memory"]) == 8 * len(graphs) and all(any(g in n for n in names["memory"]) for g in graphs), names["memory"]
# terrain: generation, chunks/s, integration, upload (1 and 2 threads), streaming
assert len(names["terrain"]) == 10 and any("streaming" in n for n in names["terrain"]), names["terrain"]
# reload: shader, ray pass shader, graph parameter, plugin
assert len(names["reload"]) == 4 and any("ray pass shader" in n for n in names["reload"]), names["reload"]
# frame: whole frame GPU and wall of every shipped graph, and its passes
assert all(any(g + " whole frame GPU" in n for n in names["frame"]) for g in graphs), names["frame"]
assert any("thesis.ini whole frame / its four ray passes" in n for n in names["frame"]), names["frame"]
assert any("thesis.ini pass atrous GPU" in n for n in names["frame"]), names["frame"]
PY
    then ok; else bad "bench --smoke JSON complete"; fi
}

section_gpu_timeout() { # a shader that never ends: --gpu-timeout and SIGINT
    expect_rc 2 "bad --gpu-timeout" "$voxrg" render "$tests/graphs/spin.ini" --gpu-timeout 0x10
    has "$out/stderr" "--gpu-timeout .0x10.: expected seconds > 0" "--gpu-timeout message"
    VOXRG_GPU_TIMEOUT=soon expect_rc 1 "bad VOXRG_GPU_TIMEOUT" "$voxrg" render "$tests/graphs/spin.ini"
    has "$out/stderr" "VOXRG_GPU_TIMEOUT='soon': expected seconds > 0" "VOXRG_GPU_TIMEOUT message"

    # A shader that never ends (spin.ini): the spin pass ends when its count
    # reaches stop, which by default it never does. `timeout` turns a
    # regression into a failure instead of a hang.
    expect_rc 0 "spin with an end" "$voxrg" render "$tests/graphs/spin.ini" --validate --set spin.stop=3 --out "$out/spin"
    start=$(date +%s)
    expect_rc 1 "render past --gpu-timeout" timeout -s KILL 60 "$voxrg" render "$tests/graphs/spin.ini" --validate --gpu-timeout 1 --out "$out/spin"
    [ $(($(date +%s) - start)) -le 30 ] && ok || bad "--gpu-timeout 1 took $(($(date +%s) - start)) s"
    has "$out/stderr" "frame 0: pass 'spin' \(plugin spin\) has run for more than 1 s on the GPU" "timeout names the pass"
    # without a timeout SIGINT ends it: sent once the device line is out and the
    # frame had time to reach the GPU
    timeout -s KILL 60 "$voxrg" render "$tests/graphs/spin.ini" --validate --out "$out/spin" 2>"$out/stderr" &
    spin_pid=$!
    for _ in $(seq 100); do grep -q "voxrg: device" "$out/stderr" && break; sleep 0.1; done
    sleep 3
    start=$(date +%s)
    kill -INT $spin_pid
    wait $spin_pid; rc=$?
    [ "$rc" -ne 0 ] && [ "$rc" -ne 137 ] && ok || bad "SIGINT during a GPU hang: exit $rc, want non-zero (137: killed by the watchdog)"
    [ $(($(date +%s) - start)) -le 10 ] && ok || bad "SIGINT took $(($(date +%s) - start)) s to end the run"
    has "$out/stderr" "frame 0: interrupted after .* pass 'spin' \(plugin spin\) still running" "SIGINT names the pass"
}

section_no_display() { # voxrg run without a display
    env -u DISPLAY -u WAYLAND_DISPLAY "$voxrg" run "$tests/graphs/blocks_wall.ini" --frames 2 >"$out/stdout" 2>"$out/stderr"
    [ $? -eq 1 ] && ok || bad "run without a display exits 1"
    has "$out/stderr" "no display.*voxrg render" "run without a display points to render"
}

section_window() { # voxrg run under Xvfb: screenshots through the program's own option
    # run: the window under Xvfb, a screenshot through the program's own option
    start_xvfb || return 0
    expect_rc 0 "run under Xvfb" "$voxrg" run "$tests/graphs/blocks_wall.ini" --validate --size 192x128 --frames 4 \
        --screenshot "$out/window.png"
    if python3 - "$out/window.png" "$tests/cli" <<'PY'
import sys
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, sys.argv[2])
from png_pixels import load
w, h, px = load(sys.argv[1])
assert (w, h) == (192, 128), (w, h)
# what the window showed: the scene below, the overlay's line (white text
# on a translucent band: the sky shows through, darkened) on top
colours = {px(x, y) for y in range(40, h) for x in range(w)}
assert len(colours) > 20, len(colours)
white = sum(px(x, y) == (255, 255, 255) for y in range(0, 30) for x in range(w))
band = [px(x, 1) for x in range(0, 60)] + [px(x, 23) for x in range(0, 60)]  # above and below the text (rows 4 to 19)
sky = [px(x, 30) for x in range(0, 60)]  # below the band (26 rows: a line of 18 and the padding)
assert white > 100 and max(map(max, band)) < min(map(max, sky)) and len(set(band)) > 1, (white, band[:4], sky[:4])
PY
    then ok; else bad "window screenshot shows the scene and the overlay"; fi
    # a CPU device without --scale or --size: the scale starts at 0.25 and
    # adapts (a window of 128x72 on blocks_wall is fast: it doubles); with
    # --scale it stays
    expect_rc 0 "run on a CPU device picks the scale" "$voxrg" run "$tests/graphs/blocks_wall.ini" --window 128x72 --frames 60
    if grep -q "^voxrg: device llvmpipe" "$out/stderr"; then
        has "$out/stderr" "^render scale 0\.25 \(auto: llvmpipe.* is a CPU device; it adapts towards 15 fps, --scale S or --size WxH fixes it\)" \
            "run says it picked the scale"
        has "$out/stderr" "^auto scale 0\.5 \([0-9.]+ fps at 0\.25\): graph now 64x36, history reset" "fast frames double the auto scale"
    fi
    expect_rc 0 "run --scale keeps the scale" "$voxrg" run "$tests/graphs/blocks_wall.ini" --window 128x72 --scale 0.25 --frames 30
    ! grep -q "auto" "$out/stderr" && ok || bad "--scale given: the scale changed on its own"
    # no graph: the shipped interactive graph (issue 19), at half the window
    expect_rc 0 "run without a graph" "$voxrg" run --validate --window 192x108 --frames 2 --screenshot "$out/default.png"
    has "$out/stderr" "no graph given: running .*/graphs/interactive.ini" "run without a graph opens interactive.ini"
    # render scale: the window's size, the graph at half of it, upscaled
    # nearest (2x2 blocks of one colour) or bilinear (blended)
    for filter in nearest bilinear; do
        expect_rc 0 "run --scale 0.5 --filter $filter" "$voxrg" run "$tests/graphs/blocks_wall.ini" --validate --window 192x128 --scale 0.5 \
            --filter $filter --frames 2 --screenshot "$out/scaled_$filter.png"
    done
    if python3 - "$out" "$tests/cli" <<'PY'
import sys
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[2])
from png_pixels import load
def blocks(name):  # below the overlay: how many 2x2 blocks hold one colour, of how many
    w, h, px = load(sys.argv[1] + "/scaled_%s.png" % name)
    assert (w, h) == (192, 128), (w, h)
    cells = [(x, y) for y in range(40, h, 2) for x in range(0, w, 2)]
    return sum(len({px(x + i, y + j) for i in (0, 1) for j in (0, 1)}) == 1 for x, y in cells), len(cells)
same, cells = blocks("nearest")
assert same == cells, (same, cells)
same, cells = blocks("bilinear")
assert same < cells * 0.95, (same, cells)
PY
    then ok; else bad "--scale 0.5 renders at half the window, upscaled as --filter says"; fi
    # another image than the output, through the display stage: normals as colours
    expect_rc 0 "run --show gbuffer.normal" "$voxrg" run "$tests/graphs/gbuffer_blocks.ini" --show gbuffer.normal --validate \
        --size 192x128 --frames 3 --screenshot "$out/normals.png"
    if python3 - "$out/normals.png" "$tests/cli" <<'PY'
import sys
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, sys.argv[2])
from png_pixels import load
w, h, px = load(sys.argv[1])
floor = px(96, 110)  # the floor: normal (0, 1, 0) -> (0.5, 1, 0.5)
assert all(abs(a - b) <= 3 for a, b in zip(floor, (128, 255, 128))), floor
PY
    then ok; else bad "--show gbuffer.normal shows the floor's normal"; fi
    expect_rc 1 "run --show of an unknown image" "$voxrg" run "$tests/graphs/gbuffer_blocks.ini" --show nonesuch --frames 1
    # a debug output nothing reads: --show reads it back, so it is computed (svgf_reproject's
    # reprojection, w: 1 where the history was read with bilinear taps, as on a still camera's floor, 0 on sky)
    expect_rc 0 "run --show reproject.reprojection" "$voxrg" run "$tests/graphs/svgf_ghost.ini" \
        --show reproject.reprojection --validate --size 96x64 --frames 3 --screenshot "$out/reprojection.png"
    if python3 - "$out/reprojection.png" "$tests/cli" <<'PY'
import sys
sys.dont_write_bytecode = True  # no __pycache__ in the source tree
sys.path.insert(0, sys.argv[2])
from png_pixels import load
w, h, px = load(sys.argv[1])
floor, sky = px(w // 2, h - 4), px(5, 30)  # below the overlay's line
assert all(abs(c - 64) <= 3 for c in floor[:3]), floor  # w = 1, shown as w / 4
assert sky[:3] == (0, 0, 0), sky
PY
    then ok; else bad "--show reproject.reprojection shows how the floor's history was read"; fi
    expect_rc 0 "run --ab and --record under Xvfb" "$voxrg" run "$tests/graphs/blocks_wall.ini" --ab "$tests/graphs/blocks_wall.ini" \
        --validate --size 96x64 --frames 3 --record "$out/flight.path"
    sed 's/^box = 8 1 8 23 6 8 red/box = 8 1 8 23 3 8 red/' "$tests/graphs/blocks_wall.ini" >"$out/lower_wall.ini"
    expect_rc 1 "run --ab of another world" "$voxrg" run "$tests/graphs/blocks_wall.ini" --ab "$out/lower_wall.ini" --frames 1
    has "$out/stderr" "--ab: scenes differ: .*blocks_wall.ini:[0-9]+ and .*lower_wall.ini:[0-9]+ set different text parameters" "--ab scene check"
    sed 's/^time_of_day = 10/time_of_day = 16/' "$tests/graphs/blocks_wall.ini" >"$out/late.ini"
    expect_rc 1 "run --ab at another time of day" "$voxrg" run "$tests/graphs/blocks_wall.ini" --ab "$out/late.ini" --frames 1
    has "$out/stderr" "--ab: scenes differ: .*has time_of_day = 10, .*late.ini:[0-9]+ 16" "--ab scene parameter check"
    expect_rc 0 "a recorded flight plays back" "$voxrg" render "$tests/graphs/blocks_wall.ini" --camera "$out/flight.path" --frames 3 --out "$out/flight"
}

section_window_driven() { # voxrg run under Xvfb driven by xdotool: flight, resize, the parameter panel
    # driven like a user (xdotool): the window resized (the graph follows),
    # W held (the camera flies forward), a right-button drag (it turns), P
    # (a screenshot of the new size), Esc (quits)
    command -v xdotool >/dev/null || { skip "xdotool not installed (scripts/setup.sh installs it)"; return 0; }
    start_xvfb || return 0
    cat >"$out/drive.sh" <<'SH'
#!/usr/bin/env bash
set -u
voxrg=$1 graph=$2 out=$3
cd "$out" && rm -rf shots
"$voxrg" run "$graph" --validate --window 192x128 --scale 1 --record drive.path --out shots >drive.stdout 2>drive.stderr &
pid=$!
# a failing step shows what the window said (expect_rc prints stderr)
fail() { kill $pid; echo "drive step $1 failed; voxrg's stderr:" >&2; tail -20 drive.stderr >&2; exit "$1"; }
wid=$(timeout 120 xdotool search --sync --name '^voxrg' | head -1)
[ -n "$wid" ] || fail 3
wait_for() { for _ in $(seq 600); do grep -q "$1" drive.stderr && return 0; sleep 0.1; done; return 1; }
# frames are being presented once the title shows the rates
for _ in $(seq 600); do xdotool getwindowname "$wid" | grep -q fps && break; sleep 0.1; done
xdotool windowsize "$wid" 160 100 && wait_for "window resized: graph now 160x100" || fail 4
xdotool windowfocus --sync "$wid"
xdotool keydown w && sleep 1 && xdotool keyup w
xdotool mousemove --window "$wid" 80 50 mousedown 3 && sleep 0.3
for _ in $(seq 10); do xdotool mousemove_relative -- 8 0; sleep 0.05; done
xdotool mouseup 3
xdotool key p && wait_for "wrote shots/screenshot-000.png" || fail 5
xdotool key Escape
wait $pid || { rc=$?; tail -20 drive.stderr >&2; exit $rc; }
SH
    expect_rc 0 "the window driven by xdotool" timeout 300 bash "$out/drive.sh" "$voxrg" "$tests/graphs/blocks_wall.ini" "$out"
    if python3 - "$out" "$tests/cli" <<'PY'
import math, sys
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[2])
from png_pixels import load
w, h, px = load(sys.argv[1] + "/shots/screenshot-000.png")
assert (w, h) == (160, 100), (w, h)
# below the overlay: the scene (by now the lit white floor fills it), not a black or uncleared window
bottom = [px(x, y) for y in range(h - 20, h) for x in range(w)]
assert sum(map(sum, bottom)) / (3 * len(bottom)) > 120 and (24, 24, 24) not in bottom, bottom[:4]
rows = [list(map(float, l.split())) for l in open(sys.argv[1] + "/drive.path") if l.strip() and not l.startswith("#")]
t0, x0, y0, z0, yaw0, pitch0 = rows[0]
t1, x1, y1, z1, yaw1, pitch1 = rows[-1]
assert math.dist((x0, y0, z0), (x1, y1, z1)) > 0.5, (rows[0], rows[-1])   # W flew forward
assert abs(yaw1 - yaw0) > 1, (yaw0, yaw1)                               # the drag turned the view
PY
    then ok; else bad "the driven window: resized screenshot, flight and turn in the recorded path"; fi
    # a resize keeps the scale: a window of 160x100 at 0.5 renders 80x50
    cat >"$out/scale.sh" <<'SH'
#!/usr/bin/env bash
set -u
voxrg=$1 graph=$2 out=$3
cd "$out"
"$voxrg" run "$graph" --validate --window 192x128 --scale 0.5 >scale.stdout 2>scale.stderr &
pid=$!
fail() { kill $pid; echo "scale step $1 failed; voxrg's stderr:" >&2; tail -20 scale.stderr >&2; exit "$1"; }
wid=$(timeout 120 xdotool search --sync --name '^voxrg' | head -1)
[ -n "$wid" ] || fail 3
for _ in $(seq 600); do xdotool getwindowname "$wid" | grep -q fps && break; sleep 0.1; done
xdotool windowsize "$wid" 160 100
for _ in $(seq 600); do grep -q "window resized: graph now 80x50" scale.stderr && break; sleep 0.1; done
grep -q "window resized: graph now 80x50" scale.stderr || fail 4
xdotool windowfocus --sync "$wid" && xdotool key Escape
wait $pid || { rc=$?; tail -20 scale.stderr >&2; exit $rc; }
SH
    expect_rc 0 "a resized window keeps the render scale" timeout 300 bash "$out/scale.sh" "$voxrg" "$tests/graphs/blocks_wall.ini" "$out"
    # the parameter panel driven by keys: open it (M), hide the overlay
    # (H: the screenshots show the picture alone), scene.time_of_day
    # 10 -> 12 and view.exposure (absent from the file) 0.35 -> 0.6, a
    # screenshot of the live tweak, Ctrl+S, the reload, a screenshot
    mkdir -p "$out/panel" && cp "$tests/graphs/blocks_wall.ini" "$out/panel/panel.ini"
    cat >"$out/panel.sh" <<'SH'
#!/usr/bin/env bash
set -u
voxrg=$1 out=$2
cd "$out" && rm -rf out
"$voxrg" run panel.ini --validate --window 192x128 --scale 1 --record panel.path >panel.stdout 2>panel.stderr &
pid=$!
fail() { kill $pid; echo "panel step $1 failed; voxrg's stderr:" >&2; tail -20 panel.stderr >&2; exit "$1"; }
wid=$(timeout 120 xdotool search --sync --name '^voxrg' | head -1)
[ -n "$wid" ] || fail 3
wait_for() { for _ in $(seq 600); do grep -q "$1" panel.stderr && return 0; sleep 0.1; done; return 1; }
for _ in $(seq 600); do xdotool getwindowname "$wid" | grep -q fps && break; sleep 0.1; done
xdotool windowfocus --sync "$wid"
xdotool key m h p && wait_for "wrote out/screenshot-000.png" || fail 4
# rows: scene's box, time_of_day, day_length, traversal, then view's mode, shadows, exposure
xdotool key Down Right Right Down Down Down Down Down Right Right Right Right Right p && wait_for "wrote out/screenshot-001.png" || fail 5
xdotool key ctrl+s && wait_for "saved 2 values to panel.ini" && wait_for "reloaded:" || fail 6
xdotool key p && wait_for "wrote out/screenshot-002.png" || fail 7
xdotool key Escape
wait $pid || { rc=$?; tail -20 panel.stderr >&2; exit $rc; }
SH
    expect_rc 0 "the parameter panel driven by xdotool" timeout 300 bash "$out/panel.sh" "$voxrg" "$out/panel"
    diff "$tests/graphs/blocks_wall.ini" "$out/panel/panel.ini" >"$out/panel/diff"
    printf '18c18\n< time_of_day = 10\n---\n> time_of_day = 12\n24a25\n> exposure = 0.6\n' >"$out/panel/diff.want"
    cmp -s "$out/panel/diff" "$out/panel/diff.want" && ok || { bad "the panel's save changed more than the two values"; cat "$out/panel/diff"; }
    expect_rc 0 "the saved graph renders" "$voxrg" render "$out/panel/panel.ini" --size 192x128 --out "$out/panel/render"
    if python3 - "$out/panel" "$tests/cli" <<'PY'
import sys
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[2])
from png_pixels import load
d = sys.argv[1]
before, live, reloaded, render = (load(d + f) for f in ("/out/screenshot-000.png", "/out/screenshot-001.png", "/out/screenshot-002.png", "/render/view.png"))
def diff(a, b):
    (w, h, pa), (w2, h2, pb) = a, b
    assert (w, h) == (w2, h2), ((w, h), (w2, h2))
    return max(abs(p - q) for y in range(h) for x in range(w) for p, q in zip(pa(x, y), pb(x, y)))
assert diff(before, live) > 30, "the tweak did not change the image"
assert diff(live, reloaded) == 0, "the reload after the save changed the image: %d" % diff(live, reloaded)
# the PNG writer and the swapchain each encode sRGB: a level apart at most
assert diff(live, render) <= 1, "the saved graph renders otherwise than the live tweak: %d" % diff(live, render)
PY
    then ok; else bad "the panel's tweak shows, and the saved graph renders it the same"; fi
    # with --ab, B switches the panel to B's graph: the save edits b.ini alone
    cp "$tests/graphs/blocks_wall.ini" "$out/panel/a.ini" && cp "$tests/graphs/blocks_wall.ini" "$out/panel/b.ini"
    cat >"$out/panel_ab.sh" <<'SH'
#!/usr/bin/env bash
set -u
voxrg=$1 out=$2
cd "$out"
"$voxrg" run a.ini --ab b.ini --validate --window 192x128 >ab.stdout 2>ab.stderr &
pid=$!
fail() { kill $pid; echo "--ab panel step $1 failed; voxrg's stderr:" >&2; tail -20 ab.stderr >&2; exit "$1"; }
wid=$(timeout 120 xdotool search --sync --name '^voxrg' | head -1)
[ -n "$wid" ] || fail 3
for _ in $(seq 600); do xdotool getwindowname "$wid" | grep -q fps && break; sleep 0.1; done
xdotool windowfocus --sync "$wid"
xdotool key m b Down Down Down Down Down Down Right ctrl+s
for _ in $(seq 600); do grep -q "saved 1 value to b.ini" ab.stderr && break; sleep 0.1; done
grep -q "saved 1 value to b.ini" ab.stderr || fail 4
xdotool key Escape
wait $pid || { rc=$?; tail -20 ab.stderr >&2; exit $rc; }
SH
    expect_rc 0 "the --ab panel edits B" timeout 300 bash "$out/panel_ab.sh" "$voxrg" "$out/panel"
    cmp -s "$tests/graphs/blocks_wall.ini" "$out/panel/a.ini" && ok || bad "--ab: the panel on B changed a.ini"
    diff "$tests/graphs/blocks_wall.ini" "$out/panel/b.ini" | grep -qx "> exposure = 0.4" && ok || bad "--ab: b.ini did not get B's exposure"
}

section_plugins() { # voxrg plugins
    # plugins
    expect_rc 0 "plugins" "$voxrg" plugins
    has "$out/stdout" "^pattern +pass" "plugins lists pattern"
    has "$out/stdout" "^test_scene +scene" "plugins lists the scene"
    expect_rc 0 "plugins blur" "$voxrg" plugins blur
    has "$out/stdout" "^  in\.src +image" "plugin slots"
    expect_rc 0 "plugins pingpong" "$voxrg" plugins pingpong
    has "$out/stdout" "iterations +int +default 3" "plugin parameters"
    expect_rc 1 "plugins unknown" "$voxrg" plugins nonesuch
    # a C pass's string parameters with a list of names (param_choices):
    # listed, and a value not among them is an error at its line
    expect_rc 0 "plugins bilateral_upsample" "$voxrg" plugins bilateral_upsample
    has "$out/stdout" "^  mode +text +default 'bilateral' +bilateral\|bilinear\|nearest " "a C pass's choices listed"
    expect_rc 0 "plugins tiles" "$voxrg" plugins tiles
    has "$out/stdout" "^  t8_channel +text +default 'rgb' +rgb\|r\|g\|b\|a\|luma " "the last tile's choices listed"
    # the scenes' traversal (VRG_SCENE_PARAMS's last parameter), in each scene plugin
    for scene in terrain vox blocks; do
        expect_rc 0 "plugins $scene" "$voxrg" plugins "$scene"
        has "$out/stdout" "^  traversal +text +default 'dda' +dda\|rayquery " "$scene's traversal choices listed"
    done
    sed 's/^mode             = bilinear/mode             = bicubic/' "$tests/graphs/half_res.ini" >"$out/bad_choice.ini"
    expect_rc 1 "a C pass's value not among its choices" "$voxrg" check --no-device "$out/bad_choice.ini"
    line=$(grep -n '^mode             = bicubic' "$out/bad_choice.ini" | cut -d: -f1)
    has "$out/stderr" "bad_choice\.ini:$line: error\[VRG-E047\]: mode = 'bicubic': expected bilateral, bilinear or nearest" "the bad choice at its line"
    expect_rc 1 "svgf_variance mode not a choice" "$voxrg" check --no-device "$tests/../graphs/thesis.ini" --set variance.mode=both
    has "$out/stderr" "mode = 'both': expected spatial or temporal" "svgf_variance's choices checked"
    # a parameter that needs optional slots: an error at the pass's line, not a crash
    expect_rc 1 "young_rays without the history" "$voxrg" check --no-device "$tests/../graphs/raw.ini" --set indirect.young_rays=4
    line=$(grep -n '^\[pass indirect\]' "$tests/../graphs/raw.ini" | cut -d: -f1)
    has "$out/stderr" "raw\.ini:$line: error\[VRG-E058\]: pass 'indirect' .*young_rays = 4 reads last frame's history: connect in\.history_length" "young_rays names what to connect"
    # a file on the path that does not load: reported, the rest listed, exit 1
    mkdir -p "$out/broken" && echo "not an ELF file" >"$out/broken/garbage.so"
    VOXRG_PLUGIN_PATH="$out/broken" "$voxrg" plugins >"$out/stdout" 2>"$out/stderr"
    [ $? -eq 1 ] && ok || bad "plugins with a file that does not load exits 1"
    has "$out/stdout" "^pattern +pass" "plugins lists the rest after a failure"
    has "$out/stderr" "garbage.so" "plugins names the file that does not load"
    has "$out/stderr" "error: 1 plugin file on the search path did not load" "plugins counts the failures"
}

section_new_pass() { # new-pass: names it refuses, and one it writes
    for name in all install ALL_BUILD; do
        expect_rc 2 "new-pass $name" "$voxrg" new-pass "$name" --dir "$out/$name"
        has "$out/stderr" "'$name' is a target name CMake keeps for itself" "new-pass $name says why"
        [ ! -e "$out/$name" ] && ok || bad "new-pass $name wrote $out/$name"
    done
    # a shipped C pass (NAME.so) and a shipped one-file pass (NAME.comp): each named by its file
    expect_rc 2 "new-pass gbuffer (a shipped pass)" "$voxrg" new-pass gbuffer --dir "$out/gbuffer"
    has "$out/stderr" "a plugin named 'gbuffer' is on the search path already \(.*/gbuffer\.so\)" "new-pass gbuffer names the shipped file"
    [ ! -e "$out/gbuffer" ] && ok || bad "new-pass gbuffer wrote $out/gbuffer"
    expect_rc 2 "new-pass tonemap (a shipped pass)" "$voxrg" new-pass tonemap --dir "$out/tonemap"
    has "$out/stderr" "a plugin named 'tonemap' is on the search path already \(.*/tonemap\.comp\)" "new-pass tonemap names the shipped file"
    [ ! -e "$out/tonemap" ] && ok || bad "new-pass tonemap wrote $out/tonemap"
    expect_rc 0 "new-pass tint" "$voxrg" new-pass tint --dir "$out/tint"
    [ -s "$out/tint/tint.c" ] && [ -s "$out/tint/CMakeLists.txt" ] && ok || bad "new-pass tint wrote no tint.c or CMakeLists.txt"
}

# One X server for every window test of a run: xvfb-run around each command
# raced its own clean-up now and then ("problem while cleaning up temporary
# directory", exit 5, whatever the command returned). False where there is
# none, having said why (a skip, or a failure when it is there and does not
# start).
xvfb_pid=
start_xvfb() {
    [ -n "$xvfb_pid" ] && return 0
    if ! command -v Xvfb >/dev/null; then
        skip "Xvfb not installed (scripts/setup.sh installs it)"
        return 1
    fi
    Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp 3>"$out/xvfb.display" 2>"$out/xvfb.log" &
    xvfb_pid=$!
    trap 'kill $xvfb_pid 2>/dev/null' EXIT
    for _ in $(seq 100); do [ -s "$out/xvfb.display" ] && break; sleep 0.1; done
    [ -s "$out/xvfb.display" ] || { bad "Xvfb did not start"; cat "$out/xvfb.log"; xvfb_pid=; return 1; }
    export DISPLAY=":$(head -1 "$out/xvfb.display")"
}

# in the order of the file (tests/cli/CMakeLists.txt reads them so too)
sections=$(sed -n 's/^section_\([a-z_]*\)() {.*/\1/p' "$0" | tr '\n' ' ')
case " $sections all " in
*" $only "*) ;;
*) echo "usage: $0 VOXRG TESTS_DIR OUT_DIR [SECTION]: no section '$only' (sections: $sections)" >&2; exit 2 ;;
esac
for section in $sections; do
    if [ "$only" = all ] || [ "$only" = "$section" ]; then "section_$section"; fi
done
echo "$pass passed, $fail failed${skipped:+, skipped:$skipped}"
[ "$fail" -eq 0 ] || exit 1
[ "$only" != all ] && [ -n "$skipped" ] && exit 77
exit 0
