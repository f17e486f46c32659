#!/usr/bin/env python3
"""Shader-only passes (docs/plugin-abi.md, "A pass in one file"): the
height fog cut out of the page is one file of at most 40 lines; its graph
checks, lists, renders under --validate, and --set changes the picture;
`voxrg plugins NAME` shows its slots and parameters; float, int, uint and
bool members are packed at their offsets (a pass writes them); each broken
interface is an error at the shader's FILE:LINE (a push member without or
with a malformed annotation, a binding neither in_ nor out_, a push block
past the 128 bytes the values are packed into, a default, min or max its
type cannot hold, a format qualifier no graph allocates, a member named as
a graph key), a member on the block's brace lines or a block comment with
braces does not confuse the block's reading, a listing skips a C plugin's
helper shader (no in_/out_ binding), a graph that
wires a buffer to its image slot or a format its declaration forbids, or
sets a parameter it does not declare, is an error at the graph's line; a
folder with NAME.so and NAME.comp loads the .so; `new-pass
--shader` writes a pass that renders; and under `render --watch` an edit
of the file shows within BOUND frames, an interface change re-validates
the graph (one it no longer fits is an error at the graph's line), and a
broken edit keeps the last good version, said with FILE:LINE (an emptied
file, said with its name); a change to the include holding the push
block re-reads the members' offsets. A choices= list with an empty name
(leading, trailing or doubled comma) is an error at its line; a long list
is listed and quoted whole.
Usage: test_shader_pass.py VOXRG SOURCE_DIR OUT_DIR"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

VOXRG, SRC, OUT = sys.argv[1:4]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import png_pixels  # noqa: E402

BOUND = 10
WAIT_S = 180
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what, flush=True)
    return cond


def block(after):
    """The fenced block after the line of docs/plugin-abi.md starting with `after`."""
    lines = open(os.path.join(SRC, "docs", "plugin-abi.md")).read().split("\n")
    i = next(k for k, l in enumerate(lines) if l.startswith(after))
    start = next(k for k in range(i + 1, len(lines)) if lines[k].startswith("```"))
    end = next(k for k in range(start + 1, len(lines)) if lines[k].startswith("```"))
    return "\n".join(lines[start + 1:end]) + "\n"


def save(path, text):
    with open(path, "w") as f:
        f.write(text)


def run(*args, env=None):
    p = subprocess.run([VOXRG, *args], capture_output=True, text=True, cwd=OUT, timeout=300,
                       env=dict(os.environ, **(env or {})))
    out = p.stdout + p.stderr
    # a sanitizer build's report fails the case even where an error exit is wanted
    check(not re.search(r"Sanitizer|runtime error:", out), "voxrg %s: a sanitizer report\n%s" % (" ".join(args), out))
    return p.returncode, out


def line_of(text, needle):
    return next(k + 1 for k, l in enumerate(text.split("\n")) if needle in l)


shutil.rmtree(OUT, ignore_errors=True)
os.makedirs(OUT)
FOG = block("Height fog, the whole pass")
GRAPH = block("Its graph, `plugin_path")
comp = os.path.join(OUT, "heightfog.comp")
graph = os.path.join(OUT, "heightfog.ini")
save(comp, FOG)
save(graph, GRAPH)
check(len(FOG.rstrip("\n").split("\n")) <= 40, "the page's height fog is %d lines, more than 40" % len(FOG.split("\n")))

# it works: check, plugins, render, --set
rc, out = run("check", "heightfog.ini", "--no-device")
check(rc == 0 and "heightfog.comp" in out, "check of the page's graph: exit %d\n%s" % (rc, out))
rc, out = run("plugins", "heightfog", env={"VOXRG_PLUGIN_PATH": OUT})
check(rc == 0 and re.search(r"in\.position\s+image", out) and re.search(r"out\.color\s+image\s+rgba16f", out)
      and re.search(r"density\s+float default 0\.02", out) and "heightfog: fog toward" in out and "(shader-only pass, ABI" in out,
      "voxrg plugins heightfog: exit %d\n%s" % (rc, out))
rc, out = run("render", "heightfog.ini", "--size", "160x90", "--validate", "--out", "a")
check(rc == 0, "render: exit %d\n%s" % (rc, out))
rc, out = run("render", "heightfog.ini", "--size", "160x90", "--validate", "--out", "b", "--set", "fog.density=0.5")
check(rc == 0, "render --set: exit %d\n%s" % (rc, out))
rc, out = run("render", "heightfog.ini", "--size", "160x90", "--validate", "--out", "c", "--set", "fog.density=0")
a, b, c = (open(os.path.join(OUT, d, "ldr.png"), "rb").read() for d in "abc")
check(a != b and a != c and b != c, "--set fog.density changes nothing in the picture")

# each scalar type packed at its member's offset: a pass that writes its parameters
PACK = """#version 460
#include "frame.glsl"
// pack: each parameter in a channel
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform writeonly image2D out_color;
layout(push_constant) uniform Params {
    float a; // @param default=0.5 min=0 max=1 help="red, or 1 - red when d is false"
    int b;   // @param default=3 min=-10 max=10 help="green, tenths"
    uint c;  // @param default=7 help="blue, tenths"
    bool d;  // @param default=true help="whether red is a"
} params;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(out_color))))
        return;
    imageStore(out_color, p, vec4(params.d ? params.a : 1.0 - params.a, float(params.b + 5) / 10.0, float(params.c) / 10.0, 1.0));
}
""".replace('#include "frame.glsl"\n', "")
save(os.path.join(OUT, "pack.comp"), PACK)
save(os.path.join(OUT, "pack.ini"), "[graph]\noutput = color\nwidth = 16\nheight = 8\nplugin_path = .\n\n[pass pack]\nplugin = pack\nout.color = color\n")
for sets, want in (((), (128, 204, 178)), (("a=0.25", "b=-4", "c=9", "d=false"), (191, 26, 230))):
    args = [x for kv in sets for x in ("--set", "pack." + kv)]
    rc, out = run("render", "pack.ini", "--validate", "--out", "pack", *args)
    px = png_pixels.load(os.path.join(OUT, "pack", "color.png"))[2](1, 1) if rc == 0 else None
    check(px is not None and all(abs(x - y) <= 1 for x, y in zip(px, want)), "pack %s: exit %d, pixel %s, want %s\n%s" % (sets, rc, px, want, out))
rc, out = run("plugins", "pack", env={"VOXRG_PLUGIN_PATH": OUT})
check(re.search(r"b\s+int\s+default 3\s+\[-10, 10\]", out) and re.search(r"d\s+bool\s+default 1", out) and re.search(r"c\s+int\s+default 7\s+\[0, ", out),
      "voxrg plugins pack: the parameters' types and ranges\n" + out)


# optional slots, choices and variants (docs/plugin-abi.md, "A pass in one file"): opt.comp reads its
# optional in_extra only where HAS_EXTRA says it is connected, gets mode's index among its names, and is
# compiled once per shape (SHAPE=0, 1); src.comp, a second one-file pass, is what in.extra connects to
OPT = """#version 460
// opt: an optional input, a choice and a variant choice
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform writeonly image2D out_color;
layout(binding = 1) uniform sampler2D in_extra; // @optional help="any image: red is its red, else 0"
layout(push_constant) uniform Params {
    int mode;   // @param choices=zero,half,full default=half help="green: 0, 0.5 or 1"
    uint shape; // @param choices=dark,bright default=dark variant help="blue: 0 or 1, compiled in"
} params;
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(out_color))))
        return;
#ifdef HAS_EXTRA
    float r = texelFetch(in_extra, ivec2(0), 0).r;
#else
    float r = 0.0;
#endif
    imageStore(out_color, p, vec4(r, 0.5 * float(params.mode), float(SHAPE), 1.0));
}
"""
SRC_COMP = """#version 460
// src: white
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform writeonly image2D out_color;
void main() { imageStore(out_color, ivec2(gl_GlobalInvocationID.xy), vec4(1.0)); }
"""
opt_comp = os.path.join(OUT, "opt.comp")
save(opt_comp, OPT)
save(os.path.join(OUT, "src.comp"), SRC_COMP)
OPT_GRAPH = "[graph]\noutput = color\nwidth = 16\nheight = 8\nplugin_path = .\n\n[pass opt]\nplugin = opt\nout.color = color\n"
save(os.path.join(OUT, "opt.ini"), OPT_GRAPH)
save(os.path.join(OUT, "opt_extra.ini"), OPT_GRAPH.replace("[pass opt]", "[pass src]\nplugin = src\nout.color = white\n\n[pass opt]") + "in.extra = white\n")
for graph_name, sets, want in (("opt", (), (0, 128, 0)), ("opt", ("mode=full", "shape=bright"), (0, 255, 255)), ("opt", ("mode=zero",), (0, 0, 0)),
                               ("opt_extra", (), (255, 128, 0)), ("opt_extra", ("shape=bright",), (255, 128, 255))):
    args = [x for kv in sets for x in ("--set", "opt." + kv)]
    rc, out = run("render", graph_name + ".ini", "--validate", "--out", "opt", *args)
    px = png_pixels.load(os.path.join(OUT, "opt", "color.png"))[2](1, 1) if rc == 0 else None
    check(px is not None and all(abs(x - y) <= 1 for x, y in zip(px, want)), "%s %s: exit %d, pixel %s, want %s\n%s" % (graph_name, sets, rc, px, want, out))
rc, out = run("plugins", "opt", env={"VOXRG_PLUGIN_PATH": OUT})
check(rc == 0 and re.search(r"in\.extra\s+image .* optional\s+any image: red is its red", out) and re.search(r"mode\s+text\s+default 'half'\s+zero\|half\|full", out)
      and re.search(r"shape\s+text\s+default 'dark'\s+dark\|bright", out), "voxrg plugins opt: the optional slot and the choices\n" + out)
# a name it does not take: at the graph's line, naming the parameter and the names; from --set too
save(os.path.join(OUT, "opt_bad.ini"), OPT_GRAPH + "mode = most\n")
rc, out = run("check", "opt_bad.ini", "--no-device")
check(rc != 0 and "opt_bad.ini:%d: error[VRG-E047]: mode = 'most': expected zero, half or full" % (OPT_GRAPH.count("\n") + 1) in out,
      "a choice the parameter does not take: exit %d\n%s" % (rc, out))
rc, out = run("render", "opt.ini", "--out", "opt", "--set", "opt.shape=grey")
check(rc != 0 and "shape = 'grey': expected dark or bright" in out, "--set a choice the parameter does not take: exit %d\n%s" % (rc, out))


def broken_opt(what, old, new, where, pattern):
    """opt.comp with old replaced by new: check fails at where's line of the shader."""
    src = OPT.replace(old, new)
    assert src != OPT, what
    save(opt_comp, src)
    rc, out = run("check", "opt.ini", "--no-device")
    want = "%s:%d: error[VRG-E080]" % (opt_comp, line_of(src, where))
    check(rc != 0 and want in out and re.search(pattern, out), "%s: exit %d, want '%s' and /%s/ in\n%s" % (what, rc, want, pattern, out))


broken_opt("a misspelt @optional", "// @optional", "// @optinal", "in_extra;", r"binding 'in_extra': unknown annotation '@optinal'")
broken_opt("@optional with another key", "@optional help=", "@optional why=", "in_extra;", r"expected help=")
broken_opt("a default that is no choice", "default=half", "default=most", "int mode;", r"'mode': @param has default 'most', which is none of its choices zero,half,full")
broken_opt("a choice named twice", "choices=zero,half,full", "choices=zero,half,zero", "int mode;", r"names choice 'zero' twice")
# an empty name, wherever it is, is no choice (a trailing comma would have made a fourth, compiled as a variant)
broken_opt("a trailing comma in choices", "choices=zero,half,full", "choices=zero,half,full,", "int mode;", r"choice 3 of 'zero,half,full,' is empty")
broken_opt("a leading comma in choices", "choices=zero,half,full", "choices=,zero,half,full", "int mode;", r"choice 0 of ',zero,half,full' is empty")
broken_opt("two commas in choices", "choices=zero,half,full", "choices=zero,,half,full", "int mode;", r"choice 1 of 'zero,,half,full' is empty")
broken_opt("a trailing comma in variant choices", "choices=dark,bright", "choices=dark,bright,", "uint shape;", r"choice 2 of 'dark,bright,' is empty")
broken_opt("choices on a float", "int mode;", "float mode;", "float mode;", r"'mode' has choices=, but it is a float")
broken_opt("choices with a range", "choices=zero,half,full", "choices=zero,half,full min=0 max=2", "int mode;", r"with choices= has no min= or max=")
broken_opt("variant on a number", "int mode;   // @param choices=zero,half,full default=half", "int mode;   // @param default=1 min=0 max=2 variant",
           "int mode;", r"variant picks a compiled variant per choice: give choices= too")
broken_opt("an optional acceleration structure before another binding", "layout(binding = 1) uniform sampler2D in_extra;",
           "layout(binding = 2) uniform sampler2D in_extra;\n#extension GL_EXT_ray_query : require\n"
           "layout(binding = 1) uniform accelerationStructureEXT in_tlas; // @optional", "in_tlas;",
           r"binding 'in_tlas': an optional acceleration structure is the last binding")
broken_opt("every image output optional", "image2D out_color;", "image2D out_color; // @optional", "out_color;", r"every image output is @optional")
save(opt_comp, OPT)
# an empty file (an editor truncates it before writing): an error naming it, not a silent failure
save(opt_comp, "")
rc, out = run("check", "opt.ini", "--no-device")
check(rc != 0 and "%s: error[VRG-E063]: the shader is empty" % opt_comp in out, "an empty shader-only pass: exit %d\n%s" % (rc, out))
save(opt_comp, OPT)

# a long list of choices: listed whole by `voxrg plugins`, and whole in the message of a value it does not take
NAMES = ["c%03d" % i for i in range(100)]
save(os.path.join(OUT, "many.comp"), OPT.replace("choices=zero,half,full default=half", "choices=%s default=c001" % ",".join(NAMES)))
save(os.path.join(OUT, "many.ini"), OPT_GRAPH.replace("plugin = opt", "plugin = many") + "mode = c100\n")
rc, out = run("plugins", "many", env={"VOXRG_PLUGIN_PATH": OUT})
check(rc == 0 and re.search(r"mode\s+text\s+default 'c001'\s+%s\s" % re.escape("|".join(NAMES)), out), "voxrg plugins many: the 100 choices whole\n" + out)
rc, out = run("check", "many.ini", "--no-device")
check(rc != 0 and "mode = 'c100': expected %s or c099\n" % ", ".join(NAMES[:-1]) in out, "a value none of 100 choices: the message lists them whole: exit %d\n%s" % (rc, out))

# a C pass with no execute: the runtime records its listed dispatches in order (listed_probe: red from the
# first, blue from the second, which reads the first's), and packs its choice's index by name
save(os.path.join(OUT, "listed.ini"), "[graph]\noutput = color\nwidth = 16\nheight = 8\n\n[pass probe]\nplugin = listed_probe\nout.color = color\n")
for sets, want in (((), (128, 64, 64)), (("level=high",), (128, 128, 64)), (("level=low",), (128, 0, 64))):
    args = [x for kv in sets for x in ("--set", "probe." + kv)]
    rc, out = run("render", "listed.ini", "--validate", "--out", "listed", *args)
    px = png_pixels.load(os.path.join(OUT, "listed", "color.png"))[2](1, 1) if rc == 0 else None
    check(px is not None and all(abs(x - y) <= 1 for x, y in zip(px, want)), "listed_probe %s: exit %d, pixel %s, want %s\n%s" % (sets, rc, px, want, out))
rc, out = run("render", "listed.ini", "--out", "listed", "--set", "probe.level=top")
check(rc != 0 and "level = 'top': expected low, mid or high" in out, "listed_probe with a level it does not take: exit %d\n%s" % (rc, out))


def broken(what, old, new, where, pattern, fog=FOG):
    """The page's fog with old replaced by new: check fails at where's line."""
    src = fog.replace(old, new)
    assert src != fog, what
    save(comp, src)
    rc, out = run("check", "heightfog.ini", "--no-device")
    want = "%s:%d: error[%s]" % (comp, line_of(src, where), "VRG-E080")
    check(rc != 0 and want in out and re.search(pattern, out), "%s: exit %d, want '%s' and /%s/ in\n%s" % (what, rc, want, pattern, out))


density = next(l for l in FOG.split("\n") if "float density;" in l)
broken("a member without an annotation", density, "    float density;", "float density;", r"'density' has no @param annotation")
broken("an unknown annotation key", "help=\"fog per", "hlp=\"fog per", "float density;", r"unknown key 'hlp'")
broken("an annotation without a default", "default=0.02 ", "", "float density;", r"no default=")
broken("a help without its closing quote", 'base height"', 'base height', "float density;", r"no closing")
broken("min without max", "min=0 max=1 help=\"fog per", "min=0 help=\"fog per", "float density;", r"both min= and max=")
broken("a vector member", "    float density;", "    vec2 density;", "vec2 density;", r"'density' is not a scalar", fog=FOG.replace("params.density", "params.density.x"))
broken("a default outside the range", "default=0.02", "default=2", "float density;", r"default 2 lies outside \[0, 1\]")
broken("a binding neither in_ nor out_", "in_position", "gpos", "sampler2D gpos", r"'gpos' is neither in_NAME nor out_NAME")
# the parameters are packed into 128 bytes (the push-constant size every device has): a block past them
# is refused at each member that lies past, before anything packs it
pads = "".join("\n    float pad%d; // @param default=0 help=\"padding\"" % i for i in range(40))
falloff = next(l for l in FOG.split("\n") if "float falloff;" in l)
broken("a push block of 43 floats", falloff, falloff + pads, "float pad29;", r"'pad29' lies at bytes 128 to 131 of block 'Params', past the 128 bytes")
broken("a member at offset 200", "    float falloff;", "    layout(offset = 200) float falloff;", "float falloff;", r"'falloff' lies at bytes 200 to 203 .* past the 128 bytes")
# a range or default outside what the member's type holds (the value is cast to it when packed)
height = next(l for l in FOG.split("\n") if "float height;" in l)
broken("an int's min below -2^31", height, height.replace("float", "int  ").replace("min=-256", "min=-1e12"), "int   height;",
       r"'height' is an int: its min= is -1e\+12, outside \[-2147483648, 2147483647\]")
broken("a uint's max above 2^32-1", height, height.replace("float", "uint ").replace("min=-256 max=256", "min=0 max=1e10"), "uint  height;",
       r"'height' is a uint: its max= is 1e\+10, outside \[0, 4294967295\]")
broken("a float's max above FLT_MAX", "min=0 max=1 help=\"fog per", "min=0 max=1e39 help=\"fog per", "float density;", r"'density' is a float: its max= is 1e\+39, outside")
# a format qualifier no graph allocates: an error at the binding, not "no format qualifier" nor any format
broken("an output format voxrg does not allocate", "binding = 3, rgba16f", "binding = 3, rgba8_snorm", "out_color;",
       r"'out_color': format qualifier rgba8_snorm is not one voxrg allocates \(one of r8, ")
broken("an input format voxrg does not allocate", "layout(binding = 2) uniform sampler2D in_position;", "layout(binding = 2, rg16_snorm) uniform readonly image2D in_position;",
       "in_position;", r"'in_position': format qualifier rg16_snorm is not one voxrg allocates",
       fog=FOG.replace("texelFetch(in_position, vrg_pixel_in(p, size, textureSize(in_position, 0)), 0)", "imageLoad(in_position, vrg_pixel_in(p, size, imageSize(in_position)))"))
# a member with a name the graph's [pass] section keeps for itself: at the member's line
broken("a member named plugin", "float falloff;", "float plugin; ", "float plugin;", r"'plugin' has a name the graph file keeps for itself",
       fog=FOG.replace("params.falloff", "params.plugin"))
broken("a member named output_scale", "float falloff;", "float output_scale;", "float output_scale;", r"'output_scale' has a name the graph file keeps for itself",
       fog=FOG.replace("params.falloff", "params.output_scale"))
save(comp, FOG)


def fine(what, old, new):
    """The page's fog with old replaced by new still checks, and lists its three parameters."""
    src = FOG.replace(old, new)
    assert src != FOG, what
    save(comp, src)
    rc, out = run("check", "heightfog.ini", "--no-device")
    rc2, out2 = run("plugins", "heightfog", env={"VOXRG_PLUGIN_PATH": OUT})
    check(rc == 0 and rc2 == 0 and all(re.search(r"%s\s+float default" % m, out2) for m in ("density", "height", "falloff")),
          "%s: exit %d, %d\n%s%s" % (what, rc, rc2, out, out2))


# the block's lines: a member on the brace's line, a comment holding braces or push_constant
fine("a member on the closing brace's line", falloff + "\n} params;", falloff.replace("float falloff;", "float falloff; } params;"))
fine("a member on the opening brace's line", "uniform Params {\n    float density;", "uniform Params { float density;")
fine("a block comment with a brace inside the block", density, "    /* a } closes nothing here */\n" + density)
fine("a block comment naming push_constant and a brace before the block", "layout(push_constant)",
     "/* layout(push_constant) uniform Old {\n   float density; */\nlayout(push_constant)")
save(comp, FOG)

# a C plugin's helper shader on the search path (no in_/out_ binding, compiles only with its plugin's
# defines) is no shader-only pass: a listing skips it; a graph naming it is told why
helper = os.path.join(OUT, "heightfog_pass2.comp")
save(helper, "#version 460\n// a C plugin's second dispatch\nlayout(local_size_x = 8) in;\n"
             "layout(binding = 0, r32f) uniform image2D accum;\nvoid main() { imageStore(accum, ivec2(0), vec4(HELPER_SCALE)); }\n")
rc, out = run("plugins", env={"VOXRG_PLUGIN_PATH": OUT})
check(rc == 0 and "heightfog_pass2" not in out and re.search(r"\bheightfog\b", out), "voxrg plugins lists (or fails on) a helper shader: exit %d\n%s" % (rc, out))
rc, out = run("plugins", "heightfog_pass2", env={"VOXRG_PLUGIN_PATH": OUT})
check(rc != 0 and "heightfog_pass2.comp" in out, "voxrg plugins heightfog_pass2 (named): exit %d\n%s" % (rc, out))
os.remove(helper)


def graph_error(what, old, new, pattern):
    g = GRAPH.replace(old, new)
    assert g != GRAPH, what
    save(graph, g)
    rc, out = run("check", "heightfog.ini", "--no-device")
    check(rc != 0 and re.search(r"heightfog\.ini:%d: error\[VRG-E0\d\d\]" % line_of(g, new.split("\n")[0]), out) and re.search(pattern, out),
          "%s: exit %d, want heightfog.ini:%d and /%s/ in\n%s" % (what, rc, line_of(g, new.split("\n")[0]), pattern, out))


graph_error("a buffer wired to an image slot", "in.position = gbuffer.position", "in.position = world",
            r"resource 'world' is a buffer, slot 'position' of pass 'fog' takes an image, declared at \S*heightfog\.comp:%d" % line_of(FOG, "in_position;"))
graph_error("a parameter the shader does not declare", "density     = 0.05", "densty      = 0.05", r"unknown key 'densty'.*\n.*parameters: density height falloff")
save(graph, GRAPH)
# a format the declaration forbids: position read as a readonly rgba16f image (the G-buffer's is rgba32f)
save(comp, FOG.replace("layout(binding = 2) uniform sampler2D in_position;", "layout(binding = 2, rgba16f) uniform readonly image2D in_position;")
     .replace("texelFetch(in_position, vrg_pixel_in(p, size, textureSize(in_position, 0)), 0)", "imageLoad(in_position, vrg_pixel_in(p, size, imageSize(in_position)))"))
rc, out = run("check", "heightfog.ini", "--no-device")
check(rc != 0 and re.search(r"heightfog\.ini:%d: error\[VRG-E0\d\d\]: format mismatch: resource 'gbuffer.position' is rgba32f, slot 'position' "
                            r"of pass 'fog' needs rgba16f, declared at \S*heightfog\.comp:%d" % (line_of(GRAPH, "in.position"), line_of(FOG, "in_position;")), out),
      "a format the declaration forbids: exit %d\n%s" % (rc, out))
save(comp, FOG)

# NAME.so beside NAME.comp: the .so is the pass (a C plugin's shader is often NAME.comp beside it)
save(os.path.join(OUT, "heightfog.so"), "not a plugin")
rc, out = run("check", "heightfog.ini", "--no-device")
check(rc != 0 and re.search(r"cannot load plugin 'heightfog' from \S*heightfog\.so", out), "NAME.so beside NAME.comp is not the one loaded: exit %d\n%s" % (rc, out))
os.remove(os.path.join(OUT, "heightfog.so"))

# the scaffold
rc, out = run("new-pass", "tinted", "--shader", "--dir", "scaffold")
files = sorted(os.listdir(os.path.join(OUT, "scaffold"))) if rc == 0 else []
check(files == ["README.md", "tinted.comp", "tinted.ini"], "new-pass --shader: exit %d, files %s\n%s" % (rc, files, out))
rc, out = run("render", os.path.join("scaffold", "tinted.ini"), "--size", "160x90", "--validate", "--out", "scaffold/out")
check(rc == 0, "the scaffold's graph: exit %d\n%s" % (rc, out))
# its commented examples of an @optional binding and a choices= member, uncommented, are what they say
scaffold = open(os.path.join(OUT, "scaffold", "tinted.comp")).read()
examples = re.sub(r"^(\s*)// (layout\(binding = 3\)|int look;)", r"\1\2", scaffold, flags=re.M)
check(examples.count("\n") == scaffold.count("\n") and examples != scaffold, "the scaffold has no commented @optional or choices= example:\n" + scaffold)
save(os.path.join(OUT, "scaffold", "tinted.comp"), examples)
rc, out = run("plugins", "tinted", env={"VOXRG_PLUGIN_PATH": os.path.join(OUT, "scaffold")})
check(rc == 0 and re.search(r"in\.mask\s+image .* optional\s+read it under #ifdef HAS_MASK", out) and re.search(r"look\s+text\s+default 'plain'\s+plain\|warm", out),
      "the scaffold's examples uncommented: exit %d\n%s" % (rc, out))


# hot reload under render --watch
class Render:
    def __init__(self, ini=graph, out="watch", output="ldr", size="160x90"):
        self.dir = os.path.join(OUT, out)
        self.output = output
        os.makedirs(self.dir)
        self.err_path = os.path.join(self.dir, "stderr.txt")
        self.err = open(self.err_path, "w")
        self.proc = subprocess.Popen([VOXRG, "render", ini, "--size", size, "--watch", "--validate", "--frames", "0", "--interval", "30",
                                      "--sequence", "--out", self.dir], stdout=subprocess.DEVNULL, stderr=self.err)

    def path(self, k):
        return os.path.join(self.dir, "%s-%05d.png" % (self.output, k))

    def latest(self):
        ks = [int(m.group(1)) for m in map(re.compile(r"%s-(\d{5})\.png$" % self.output).match, os.listdir(self.dir)) if m]
        return max(ks, default=-1)

    def frame(self, k):
        end = time.time() + WAIT_S
        while not os.path.exists(self.path(k)):
            if self.proc.poll() is not None or time.time() > end:
                raise RuntimeError("frame %d never came (exit %s):\n%s" % (k, self.proc.poll(), open(self.err_path).read()))
            time.sleep(0.01)
        time.sleep(0.05)  # each file is complete when it appears; read once it has settled
        return open(self.path(k), "rb").read()

    def differs(self, after, than):
        """The first frame within BOUND after `after` whose pixels differ from `than`."""
        for k in range(after + 1, after + BOUND + 1):
            if self.frame(k) != than:
                return k
        return None

    def stderr_has(self, pattern, seconds=60, count=1):
        end = time.time() + seconds
        while time.time() < end:
            if len(re.findall(pattern, open(self.err_path).read())) >= count:
                return True
            time.sleep(0.05)
        return False


r = Render()
try:
    r.frame(2)
    k = r.latest()
    before = r.frame(k)
    # a new default for height, which the graph does not set: the picture changes
    save(comp, FOG.replace("default=40", "default=-20"))
    k1 = r.differs(k, before)
    check(k1 is not None, "an edited default did not show within %d frames" % BOUND)
    check(r.stderr_has(r"reloaded", count=1), "the edited default was not reloaded:\n" + open(r.err_path).read())
    if k1 is not None:
        # an interface change: a new parameter (and height's default as it was)
        grown = FOG.replace(density, density + "\n    float unused; // @param default=1 min=0 max=2 help=\"nothing yet\"")
        save(comp, grown)
        check(r.stderr_has(r"reloaded", count=2), "the interface change was not reloaded:\n" + open(r.err_path).read())
        # emptied, as an editor does before writing: said, naming the file; the last good version keeps running
        save(comp, "")
        check(r.stderr_has(re.escape("%s: error[VRG-E063]: the shader is empty" % comp)), "an emptied shader is not reported:\n" + open(r.err_path).read())
        k2 = r.latest()
        r.frame(k2 + 3)
        check(r.proc.poll() is None, "render --watch died on an emptied shader-only pass")
        # broken: reported at the member's line, the last good version keeps running
        bad = grown.replace("    float unused; // @param default=1", "    float unused; // default=1")
        save(comp, bad)
        want = re.escape("%s:%d: error[VRG-E080]" % (comp, line_of(bad, "float unused;")))
        check(r.stderr_has(want), "a broken reload is not reported with FILE:LINE:\n" + open(r.err_path).read())
        time.sleep(0.5)
        k2 = r.latest()
        r.frame(k2 + 3)
        check(r.proc.poll() is None, "render --watch died on a broken shader-only pass")
        save(comp, grown.replace("default=40", "default=-20"))  # fixed, and height's new default: the picture changes
        k3 = r.latest()
        last = r.frame(k3)
        check(r.differs(k3, last) is not None, "the fixed file did not show within %d frames" % BOUND)
        check(r.stderr_has(r"reloaded", count=3), "the fixed file was not reloaded:\n" + open(r.err_path).read())
        # an interface the graph no longer fits: density renamed, which the graph sets; the
        # graph is checked again, the error is at its line, the last good version keeps running
        renamed = FOG.replace("float density;", "float thickness;").replace("params.density", "params.thickness")
        save(comp, renamed)
        want = re.escape("%s:%d: error[VRG-E012]: unknown key 'density'" % (graph, line_of(GRAPH, "density")))
        check(r.stderr_has(want), "a reload the graph does not fit is not reported at the graph's line:\n" + open(r.err_path).read())
        k4 = r.latest()
        r.frame(k4 + 3)
        check(r.proc.poll() is None, "render --watch died on an interface the graph does not fit")
        save(comp, FOG)
        check(r.stderr_has(r"reloaded", count=4), "the file the graph fits again was not reloaded:\n" + open(r.err_path).read())
finally:
    r.proc.send_signal(signal.SIGTERM)
    rc = r.proc.wait(timeout=120)
    check(rc == 0, "render --watch under --validate: exit %d\n%s" % (rc, open(r.err_path).read()))

# the push block in an include: its change re-reads the interface (the members' offsets), so the
# values are packed where the recompiled shader reads them
INC_DIR = os.path.join(OUT, "inc")
os.makedirs(INC_DIR)
save(os.path.join(INC_DIR, "incpass.comp"), """#version 460
// incpass: its parameters declared in an include
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform writeonly image2D out_color;
#include "incparams.glsl"
void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(out_color))))
        return;
    imageStore(out_color, p, vec4(params.a, params.b, 0.0, 1.0));
}
""")
A = '    float a; // @param default=%s min=0 max=1 help="red"\n'
B = '    float b; // @param default=0.8 min=0 max=1 help="green"\n'
params_h = os.path.join(INC_DIR, "incparams.glsl")
save(params_h, "layout(push_constant) uniform Params {\n" + A % "0.2" + B + "} params;\n")
inc_graph = os.path.join(INC_DIR, "inc.ini")
save(inc_graph, "[graph]\noutput = color\nwidth = 16\nheight = 8\nplugin_path = .\n\n[pass inc]\nplugin = incpass\nout.color = color\n")
r = Render(inc_graph, "inc_watch", "color", "16x8")
try:
    r.frame(2)
    first = png_pixels.load(r.path(2))[2](1, 1)
    check(all(abs(x - y) <= 1 for x, y in zip(first, (51, 204, 0))), "incpass before the edit: pixel %s, want (51, 204, 0)" % (first,))
    k = r.latest()
    # the members swapped (their offsets too), and a's default new
    save(params_h, "layout(push_constant) uniform Params {\n" + B + A % "0.6" + "} params;\n")
    end, px = time.time() + WAIT_S, first
    while px == first and time.time() < end and r.proc.poll() is None:
        k += 1
        r.frame(k)
        px = png_pixels.load(r.path(k))[2](1, 1)
    check(all(abs(x - y) <= 1 for x, y in zip(px, (153, 204, 0))), "an include's push block changed: pixel %s, want (153, 204, 0)\n%s" % (px, open(r.err_path).read()))
finally:
    r.proc.send_signal(signal.SIGTERM)
    rc = r.proc.wait(timeout=120)
    check(rc == 0, "render --watch of incpass under --validate: exit %d\n%s" % (rc, open(r.err_path).read()))

if failures:
    print("%d failure(s)" % len(failures))
    sys.exit(1)
print("ok")
