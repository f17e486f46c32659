#!/usr/bin/env python3
"""--dump's files and `voxrg inspect`, end to end on tests/graphs/nan_pixel.ini
(pattern -> nan_pixel, one NaN at 5,3 channel B -> blur):
 - exr_roundtrip: the EXR dumps, read by exr_pixel (OpenEXR's own C library,
   none of voxrg's code), hold exactly what `inspect --json` prints (stored
   bits) at several pixels; the NaN is kept; rg32ui is a uint EXR; an rgba8
   image (unorm8.ini) is the float32 of byte / 255, which inspect prints
   with the byte;
 - dump_png: --dump-format png writes PNGs as before (no .exr);
 - buffer_sidecar: a buffer dump is NAME.bin plus NAME.json saying its size,
   texel format and writer;
 - check_finite_clean: inspect's motion target is, of the previous frame's
   pixels around it, the one nearest this frame's surface point;
 - inspect_errors: a pixel outside the image, bad --pixel syntax, no --pixel,
   render's options: a clear error, non-zero exit, nothing printed as values.
Usage: test_dump_inspect.py VOXRG EXR_PIXEL TESTS_DIR OUT_DIR CASE"""
import json
import math
import os
import shutil
import struct
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import png_pixels  # noqa: E402

VOXRG, EXR_PIXEL, TESTS, OUT, CASE = sys.argv[1:6]
GRAPH = os.path.join(TESTS, "graphs", "nan_pixel.ini")
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what, flush=True)
    return cond


def run(args, timeout=300):
    p = subprocess.run([VOXRG] + args, capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout, p.stderr


def exr_pixel(path, x, y):
    """{channel name: (type, bits)} as OpenEXR reads the file. Every channel
    is linear light or data: its pLinear (perceptually linear) must be 0."""
    p = subprocess.run([EXR_PIXEL, path, str(x), str(y)], capture_output=True, text=True, timeout=60)
    if not check(p.returncode == 0, f"exr_pixel {path} {x} {y}: {p.stderr.strip()}"):
        return {}
    out = {}
    for line in p.stdout.splitlines()[1:]:
        name, kind, bits, plinear = line.split()
        check(plinear == "0", f"{path}: channel {name} has pLinear {plinear}, not 0")
        out[name] = (kind, int(bits))
    return out


def names(n):
    return ["Y"] if n == 1 else ["R", "G", "B", "A"][:n]


def half_value(bits):
    return struct.unpack("<e", struct.pack("<H", bits))[0]


def exr_roundtrip():
    dumps = "gradient,poisoned,depth,ids,final"
    # not under --validate, which checks for NaN (check_finite) and stops at this one
    rc, _, err = run(["render", GRAPH, "--out", OUT, "--dump", dumps])
    if not check(rc == 0, f"render --dump exited {rc}: {err}"):
        return
    for res in dumps.split(","):
        check(os.path.isfile(os.path.join(OUT, res + ".exr")), f"{res}.exr not written")
    check(os.path.isfile(os.path.join(OUT, "final.png")), "the output is not final.png")
    want_type = {"rgba16f": "half", "r32f": "float", "rg32ui": "uint"}
    for x, y in ((5, 3), (0, 0), (39, 23), (17, 11)):
        js = os.path.join(OUT, f"inspect-{x}-{y}.json")
        rc, text, err = run(["inspect", GRAPH, "--pixel", f"{x},{y}", "--json", js])
        if not check(rc == 0, f"inspect --pixel {x},{y} exited {rc}: {err}"):
            continue
        images = json.load(open(js))["images"]
        check([i["resource"] for i in images] == ["gradient", "poisoned", "depth", "ids", "final"],
              f"inspect lists {[i['resource'] for i in images]}")
        for img in images:
            stored = exr_pixel(os.path.join(OUT, img["resource"] + ".exr"), x, y)
            chans = names(len(img["bits"]))
            check(sorted(stored) == sorted(chans), f"{img['resource']}: EXR channels {sorted(stored)}, inspect has {chans}")
            for c, name in enumerate(chans):
                kind, bits = stored.get(name, (None, None))
                check(kind == want_type[img["format"]], f"{img['resource']}.{name} is {kind} in the EXR ({img['format']})")
                check(bits == img["bits"][c],
                      f"{img['resource']}.{name} at {x},{y}: EXR bits {bits}, inspect {img['bits'][c]} ({img['values'][c]})")
            if img["resource"] == "ids":
                check(img["values"] == [x, y * 65536 + 7], f"ids at {x},{y}: {img['values']}")
            if img["resource"] == "depth":
                check(img["values"] == [x + y / 1024], f"depth at {x},{y}: {img['values']}")
        # the NaN, and the value printed as JSON can hold it
        poisoned = images[1]
        if (x, y) == (5, 3):
            check(poisoned["values"][2] == "nan" and math.isnan(half_value(poisoned["bits"][2])),
                  f"the NaN at 5,3: inspect says {poisoned['values'][2]} (bits {poisoned['bits'][2]})")
            kind, bits = exr_pixel(os.path.join(OUT, "poisoned.exr"), 5, 3).get("B", (None, 0))
            check(math.isnan(half_value(bits)), f"poisoned.exr at 5,3 channel B is {half_value(bits)}, not NaN")
            check("nan" in text.split("poisoned")[1].splitlines()[0], f"the table does not show the NaN: {text}")
        else:
            check(all(isinstance(v, float) or isinstance(v, int) for v in poisoned["values"]), f"{x},{y}: {poisoned['values']}")
    unorm8_roundtrip()
    # +Inf too
    rc, _, err = run(["render", GRAPH, "--out", OUT, "--dump", "poisoned", "--set", "poison.value=1"])
    kind, bits = exr_pixel(os.path.join(OUT, "poisoned.exr"), 5, 3).get("B", (None, 0))
    check(rc == 0 and half_value(bits) == math.inf, f"poisoned.exr with value=1 at 5,3 channel B: {half_value(bits)} ({err})")


def float_bits(v):
    return struct.unpack("<I", struct.pack("<f", v))[0]


def unorm8_roundtrip():
    """rgba8 (tonemap's ldr): the EXR holds the float32 of byte / 255, and
    inspect prints that float exactly and the stored byte."""
    graph = os.path.join(TESTS, "graphs", "unorm8.ini")
    rc, _, err = run(["render", graph, "--out", OUT, "--dump", "ldr"])
    if not check(rc == 0, f"render unorm8.ini --dump ldr exited {rc}: {err}"):
        return
    for x, y in ((0, 0), (39, 23), (17, 11)):
        js = os.path.join(OUT, f"inspect-ldr-{x}-{y}.json")
        rc, text, err = run(["inspect", graph, "--pixel", f"{x},{y}", "--json", js])
        if not check(rc == 0, f"inspect unorm8.ini --pixel {x},{y} exited {rc}: {err}"):
            continue
        ldr = [i for i in json.load(open(js))["images"] if i["resource"] == "ldr"]
        if not check(len(ldr) == 1 and ldr[0]["format"] == "rgba8", f"inspect unorm8.ini lists {ldr}"):
            continue
        img = ldr[0]
        stored = exr_pixel(os.path.join(OUT, "ldr.exr"), x, y)
        for c, name in enumerate(names(4)):
            kind, bits = stored.get(name, (None, None))
            byte, value = img["bits"][c], img["values"][c]
            check(kind == "float" and 0 <= byte <= 255, f"ldr.{name} at {x},{y}: {kind} in the EXR, byte {byte}")
            # independent of both: the float32 of the byte / 255
            want = float_bits(byte / 255)
            check(bits == want and float_bits(value) == want and struct.unpack("<f", struct.pack("<I", want))[0] == value,
                  f"ldr.{name} at {x},{y}: EXR bits {bits}, inspect {value} (byte {byte}), float32 of byte/255 has bits {want}")
        row = [l for l in text.splitlines() if " ldr " in l]
        bytes_text = "bytes (" + ", ".join(str(b) for b in img["bits"]) + ")"
        check(len(row) == 1 and bytes_text in row[0], f"the table's ldr line does not say {bytes_text!r}: {row}")
    # the pattern's closed form at 39,0 through the linear curve, sRGB-encoded: (1, 0, 0.5) -> bytes 255, 0, 188
    rc, _, _ = run(["inspect", graph, "--pixel", "39,0", "--json", os.path.join(OUT, "ldr-39-0.json")])
    ldr = [i for i in json.load(open(os.path.join(OUT, "ldr-39-0.json")))["images"] if i["resource"] == "ldr"] if rc == 0 else []
    check(ldr and ldr[0]["bits"][:3] == [255, 0, 188], f"ldr at 39,0: {ldr}")


def dump_png():
    rc, _, err = run(["render", GRAPH, "--out", OUT, "--dump", "gradient,final", "--dump-format", "png"])
    if not check(rc == 0, f"render --dump-format png exited {rc}: {err}"):
        return
    check(not [f for f in os.listdir(OUT) if f.endswith(".exr")], f"--dump-format png wrote EXR files: {os.listdir(OUT)}")
    w, h, px = png_pixels.load(os.path.join(OUT, "gradient.png"))
    check((w, h) == (40, 24), f"gradient.png is {w}x{h}")
    # the gradient's closed form (x/39, y/23, 0.5), sRGB-encoded as the PNG maps colour
    r, g, b = px(39, 0)
    check(r == 255 and g == 0 and b == 188, f"gradient.png at 39,0 is {(r, g, b)}, not (255, 0, 188)")
    rc, _, err = run(["render", GRAPH, "--out", OUT, "--dump-format", "tiff"])
    check(rc == 2 and "--dump-format 'tiff'" in err, f"--dump-format tiff: exit {rc}, {err}")


def buffer_sidecar():
    rc, _, err = run(["render", os.path.join(TESTS, "graphs", "buffer.ini"), "--out", OUT, "--dump", "numbers"])
    if not check(rc == 0, f"render --dump numbers exited {rc}: {err}"):
        return
    data = open(os.path.join(OUT, "numbers.bin"), "rb").read()
    check(len(data) == 4096 and struct.unpack_from("<3I", data, 0) == (0, 7, 14), f"numbers.bin: {len(data)} bytes")
    meta = json.load(open(os.path.join(OUT, "numbers.json")))
    check(meta == {"resource": "numbers", "kind": "buffer", "file": "numbers.bin", "bytes": 4096, "texel_format": "rgba32ui",
                   "written_by": "fill", "frames_rendered": 1}, f"numbers.json: {meta}")


def inspect_errors():
    for bad in ("5", "5,", ",3", "a,b", "-1,2", "5,3,1", "5 ,3", "1e3,2", "99999999999,1"):
        rc, text, err = run(["inspect", GRAPH, "--pixel", bad])
        check(rc == 2 and f"--pixel '{bad}': expected X,Y" in err and not text, f"--pixel {bad!r}: exit {rc}, stdout {text!r}, {err}")
    for x, y in ((40, 0), (0, 24), (1000, 1000)):
        rc, text, err = run(["inspect", GRAPH, "--pixel", f"{x},{y}"])
        check(rc == 2 and "outside the graph's 40x24" in err and not text, f"--pixel {x},{y}: exit {rc}, {err}")
    rc, text, err = run(["inspect", GRAPH, "--pixel", "39,23", "--size", "20x12"])
    check(rc == 2 and "outside the graph's 20x12" in err, f"--pixel 39,23 at --size 20x12: exit {rc}, {err}")
    rc, _, err = run(["inspect", GRAPH])
    check(rc == 2 and "--pixel X,Y is missing" in err, f"no --pixel: exit {rc}, {err}")
    for opt in (["--frames", "2"], ["--dump", "final"], ["--out", OUT]):
        rc, _, err = run(["inspect", GRAPH, "--pixel", "1,1"] + opt)
        check(rc == 2 and f"{opt[0]} is not an option of `voxrg inspect`" in err, f"inspect {opt}: exit {rc}, {err}")
    rc, _, err = run(["render", GRAPH, "--pixel", "1,1"])
    check(rc == 2 and "--pixel is an option of `voxrg inspect`" in err, f"render --pixel: exit {rc}, {err}")


def check_finite():
    # the NaN at 5,3 (channel B) of poisoned: named at nan_pixel's pass, not at blur (smooth), which spreads it
    rc, _, err = run(["render", GRAPH, "--check-finite", "--validate", "--frames", "3", "--out", OUT])
    check(rc == 1, f"render --check-finite of a NaN exited {rc}")
    for want in ("error[VRG-E081]: frame 0: pass 'poison' (plugin nan_pixel) wrote NaN to 'poisoned' (rgba16f), channel 2 (B) of pixel 5,3",
                 "Its inputs there: gradient (rgba16f) at 5,3: (0.128173828125, 0.13037109375, 0.5, 1)"):
        check(want in err, f"--check-finite does not say {want!r}: {err}")
    check("'smooth'" not in err and "'final'" not in err and "validation message" not in err, f"--check-finite blames more: {err}")
    check(err.count("VRG-E081") == 1, f"the NaN is reported {err.count('VRG-E081')} times: {err}")
    # +Inf elsewhere, in another channel; then -Inf is not what nan_pixel writes, so only these two
    rc, _, err = run(["render", GRAPH, "--check-finite", "--out", OUT, "--set", "poison.x=17", "--set", "poison.y=11",
                      "--set", "poison.channel=0", "--set", "poison.value=1"])
    check(rc == 1 and "wrote +Inf to 'poisoned' (rgba16f), channel 0 (R) of pixel 17,11" in err, f"+Inf at 17,11: exit {rc}, {err}")
    # --validate alone checks too (the frames in flight and memory as loaded), without the inputs
    rc, _, err = run(["render", GRAPH, "--validate", "--out", OUT])
    check(rc == 1 and "pass 'poison' (plugin nan_pixel) wrote NaN to 'poisoned' (rgba16f), channel 2 (B) of pixel 5,3" in err
          and "Its inputs" not in err, f"--validate alone: exit {rc}, {err}")
    # the inspect of that pixel agrees
    rc, text, _ = run(["inspect", GRAPH, "--pixel", "5,3"])
    check(rc == 0 and "(0.128173828125, 0.13037109375, nan, 1)" in text, f"inspect 5,3: {text}")


def check_finite_clean():
    # no NaN: the checks pass, under validation, and change no image
    rc, _, err = run(["render", GRAPH, "--check-finite", "--validate", "--frames", "2", "--set", "poison.x=-1", "--out", OUT])
    check(rc == 0, f"render --check-finite without a NaN exited {rc}: {err}")
    graph = os.path.join(TESTS, "..", "graphs", "thesis.ini")
    for name, extra in (("plain", []), ("checked", ["--check-finite", "--validate"])):
        rc, _, err = run(["render", graph, "--frames", "3", "--size", "96x54", "--out", os.path.join(OUT, name)] + extra, timeout=600)
        check(rc == 0, f"thesis.ini {name} exited {rc}: {err}")
    a, b = (open(os.path.join(OUT, n, "ldr.png"), "rb").read() for n in ("plain", "checked"))
    check(a == b, "thesis.ini renders other bytes with --check-finite")
    # inspect of a graph with a motion image: the vector's target pixel, the camera turning 10 degrees a
    # frame (at 60 fps) over the ground, so that the vector is several pixels long
    turn = os.path.join(OUT, "turn.path")
    with open(turn, "w") as f:
        f.write("0.0  0.0 35.0 0.0 -90.0 -25.0\n0.1  0.0 35.0 0.0 -30.0 -25.0\n")
    js = os.path.join(OUT, "thesis.json")
    rc, text, err = run(["inspect", graph, "--pixel", "40,45", "--frame", "2", "--size", "96x54", "--camera", turn, "--json", js], timeout=600)
    if check(rc == 0, f"inspect thesis.ini exited {rc}: {err}"):
        d = json.load(open(js))
        m = d.get("motion", {})
        motion = [i for i in d["images"] if i["resource"] == "gbuffer.motion"]
        check(m.get("resource") == "gbuffer.motion" and motion and m["vector"] == motion[0]["values"],
              f"inspect's motion {m} is not gbuffer.motion's value {motion}")
        if m.get("previous_pixel"):
            tx, ty = m["previous_pixel"]
            check(f"motion (gbuffer.motion): the previous frame's pixel {tx},{ty}" in text, f"the table's motion line: {text}")
            check(math.hypot(*m["vector"]) > 3, f"the motion vector {m['vector']} is too short to tell a sign error")
            motion_target(graph, turn, d, tx, ty)
        names = [i["resource"] + ("@prev" if i["prev"] else "") for i in d["images"]]
        check(names.index("gbuffer.position") < names.index("ldr") and "reproject.length@prev" in names,
              f"inspect's order or @prev copies: {names}")
        # thesis.ini reads no depth: gbuffer's is an unread stand-in, not computed, not listed
        check("gbuffer.depth" not in names, f"inspect lists gbuffer.depth, which nothing in thesis.ini reads: {names}")


def motion_target(graph, path, d, tx, ty):
    """Independent of the vector's arithmetic: the world is static, so where
    this frame's surface point at 40,45 was in the previous frame follows
    from the previous frame's gbuffer.position (dumped after frames 0 and 1)
    around the target: fitted linearly there (the ground is flat), it puts
    that point within half a pixel of the target, and the vector is 40,45
    minus that place. A sign or half-pixel error misses both."""
    pos = [i for i in d["images"] if i["resource"] == "gbuffer.position" and not i["prev"]]
    if not check(pos and pos[0]["values"][3] != 0, f"gbuffer.position at 40,45 is not a surface: {pos}"):
        return
    here = pos[0]["values"][:3]
    prev_dir = os.path.join(OUT, "prev")
    rc, _, err = run(["render", graph, "--frames", "2", "--size", "96x54", "--camera", path, "--out", prev_dir, "--dump", "gbuffer.position"],
                     timeout=600)
    if not check(rc == 0, f"render thesis.ini --frames 2 --dump gbuffer.position exited {rc}: {err}"):
        return

    def at(x, y):
        px = exr_pixel(os.path.join(prev_dir, "gbuffer.position.exr"), x, y)
        v = [struct.unpack("<f", struct.pack("<I", px.get(c, ("", 0))[1]))[0] for c in "RGBA"]
        check(v[3] != 0, f"the previous frame's gbuffer.position at {x},{y} is not a surface: {v}")
        return v[:3]

    if not check(0 < tx < 95 and 0 < ty < 53, f"motion target {tx},{ty} is not inside the image"):
        return
    p0 = at(tx, ty)
    dx = [(a - b) / 2 for a, b in zip(at(tx + 1, ty), at(tx - 1, ty))]
    dy = [(a - b) / 2 for a, b in zip(at(tx, ty + 1), at(tx, ty - 1))]
    r = [a - b for a, b in zip(here, p0)]
    # least squares: r = u dx + v dy
    xx, xy, yy = (sum(a * b for a, b in zip(p, q)) for p, q in ((dx, dx), (dx, dy), (dy, dy)))
    rx, ry = sum(a * b for a, b in zip(r, dx)), sum(a * b for a, b in zip(r, dy))
    det = xx * yy - xy * xy
    if not check(det > 0, f"the previous frame's positions around {tx},{ty} do not span a surface"):
        return
    u, v = (rx * yy - ry * xy) / det, (ry * xx - rx * xy) / det
    check(abs(u) <= 0.55 and abs(v) <= 0.55, f"motion target {tx},{ty}: the surface point was at {tx + u:.3f},{ty + v:.3f}")
    vec = d["motion"]["vector"]
    check(abs(vec[0] - (40 - tx - u)) < 0.15 and abs(vec[1] - (45 - ty - v)) < 0.15,
          f"motion vector {vec}: the surface point moved from {tx + u:.3f},{ty + v:.3f} to 40,45")


CASES = (exr_roundtrip, dump_png, buffer_sidecar, inspect_errors, check_finite, check_finite_clean)


def main():
    cases = {c.__name__: c for c in CASES}
    if CASE not in cases:
        sys.exit(f"usage: test_dump_inspect.py VOXRG EXR_PIXEL TESTS_DIR OUT_DIR {'|'.join(cases)}")
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    cases[CASE]()
    print("FAILED" if failures else "ok")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
