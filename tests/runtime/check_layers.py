#!/usr/bin/env python3
"""The layers depend one way: runtime <- voxel, runtime <- tools.

Sources: no layer's code (comments aside) names a public symbol of a layer
above it: the runtime none of vrg_world*, vrg_scene*, vrg_sky*, vrg_atlas*,
vrg_frame_uniforms*, vrg_camera_path*, vrg_png*, vrg_metric*, vrg_output*
..., the voxel layer none of the tools', the tools none of the voxel
layer's. Libraries: each needs (DT_NEEDED) no library of a layer beside or
above it, and every vrg_ symbol it uses comes from itself or the layers
below (the builds link with --no-undefined; this says which layer).
Usage: check_layers.py CORE_DIR LIBVOXRG.so LIBVOXRG_VOXEL.so LIBVOXRG_TOOLS.so"""
import glob
import os
import re
import subprocess
import sys

core, runtime_lib, voxel_lib, tools_lib = sys.argv[1:5]

def code_of(path):
    text = open(path).read()
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    return re.sub(r'"(?:\\.|[^"\\\n])*"', '""', text)  # strings: messages may say "world"

def public_names(layer):
    names = set()
    for h in glob.glob(os.path.join(core, layer, "include", "voxrg", "*.h")):
        names |= set(re.findall(r"\b(vrg_\w+|VRG_\w+)\b", code_of(h)))
    return names

def symbols(lib, defined):
    out = subprocess.run(["nm", "-D", "--defined-only" if defined else "--undefined-only", lib],
                         capture_output=True, text=True, check=True).stdout
    return {line.split()[-1] for line in out.splitlines() if line.split()}

def needed(lib):
    out = subprocess.run(["readelf", "-d", lib], capture_output=True, text=True, check=True).stdout
    return set(re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", out))

failures = []
names = {layer: public_names(layer) for layer in ("runtime", "voxel", "tools")}
# an upper layer's headers also use the runtime's names (vrg_pass in world.h,
# vrg_camera in camera_path.h): those stay the runtime's
for layer in ("voxel", "tools"):
    names[layer] -= names["runtime"]
forbidden = {"runtime": names["voxel"] | names["tools"], "voxel": names["tools"], "tools": names["voxel"]}
for layer, bad in forbidden.items():
    bad = bad - names[layer]
    for path in sorted(glob.glob(os.path.join(core, layer, "**", "*.[ch]"), recursive=True)):
        used = set(re.findall(r"\b(vrg_\w+|VRG_\w+)\b", code_of(path))) & bad
        for name in sorted(used):
            failures.append("%s: the %s layer uses %s of a layer above or beside it" % (os.path.relpath(path, core), layer, name))
        for inc in re.findall(r'#include\s+"voxrg/(\w+\.h)"', open(path).read()):
            owner = [l for l in names if os.path.exists(os.path.join(core, l, "include", "voxrg", inc))]
            if owner and owner[0] != layer and owner[0] != "runtime":
                failures.append("%s: the %s layer includes voxrg/%s of the %s layer" % (os.path.relpath(path, core), layer, inc, owner[0]))

libs = {"runtime": runtime_lib, "voxel": voxel_lib, "tools": tools_lib}
below = {"runtime": [], "voxel": ["runtime"], "tools": ["runtime"]}
for layer, lib in libs.items():
    # by name without the version: DT_NEEDED holds the SONAME
    # (libvoxrg.so.MAJOR), the build names the file libvoxrg.so.VERSION
    allowed = {os.path.basename(libs[l]).split(".so")[0] for l in below[layer]}
    for dep in needed(lib):
        others = {os.path.basename(libs[l]).split(".so")[0] for l in libs if l != layer}
        if dep.split(".so")[0] in others and dep.split(".so")[0] not in allowed:
            failures.append("%s needs %s, a layer above or beside it" % (os.path.basename(lib), dep))
    provided = symbols(lib, True).union(*(symbols(libs[l], True) for l in below[layer]))
    for sym in sorted(s for s in symbols(lib, False) if s.startswith("vrg_") and s not in provided):
        failures.append("%s uses %s, which no layer below it provides" % (os.path.basename(lib), sym))

for f in failures:
    print(f)
print("layers: %s" % ("ok" if not failures else "%d problems" % len(failures)))
sys.exit(1 if failures else 0)
