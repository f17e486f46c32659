#!/usr/bin/env python3
"""The parameter panel of `voxrg run`, driven like a user (xdotool under
Xvfb), each step checked in the graph file the save writes:
- PgDn jumps to the next pass, PgUp back; Right steps max_distance
  (1..4096) by a twentieth of its range rounded to 200, Shift+Right by 20;
- a value changed and set back is not written: the save writes only what
  differs, and a 0600 graph stays 0600;
- / filters the rows by what is typed (the letters do not fly, open or
  quit), Enter keeps the filter;
- a read-only (0444) graph is refused, unchanged; Ctrl+Shift+S writes
  GRAPH-edited.ini beside it (an existing one is refused; a typed name is
  taken);
- a graph with another hard link is replaced under its own name, said,
  the other name keeps the old text;
- a shader-only pass (NAME.comp beside the graph) has its @param rows:
  Right steps one, the save writes it.
Usage: test_run_panel.py VOXRG TESTS_DIR OUT_DIR"""
import os
import stat
import sys

sys.dont_write_bytecode = True
voxrg, tests, out = sys.argv[1:4]
sys.path.insert(0, os.path.join(tests, "cli"))
from window import Window, run_cases, xdo  # noqa: E402

GRAPH = os.path.join(tests, "graphs", "blocks_wall.ini")
ORIGINAL = open(GRAPH).read()


def added(path):
    """The lines of path that blocks_wall.ini lacks, and those it lost."""
    new, old = open(path).read().splitlines(), ORIGINAL.splitlines()
    return [l for l in new if l not in old], [l for l in old if l not in new]


def graph(d, name, mode=0o644):
    path = os.path.join(d, name)
    with open(path, "w") as f:
        f.write(ORIGINAL)
    os.chmod(path, mode)
    return path


def keys(*names):
    for k in names:
        xdo("key", k)


def jump_step_set_back(d):
    """rows: scene's box, time_of_day, day_length, traversal; view's mode, shadows, exposure, max_distance"""
    path = graph(d, "private.ini", 0o600)
    win = Window(voxrg, "private.ini", d)
    keys("m", "Next", "Down", "Down", "Down", "Right", "shift+Right")  # view.max_distance 512 -> 712 -> 732
    keys("Prior", "Down", "Right", "Right", "Left", "Left")  # scene.time_of_day 10 -> 12 -> 10: as before
    keys("ctrl+s")
    win.stderr_has("saved 1 value to private.ini")
    win.stderr_has("reloaded:")
    win.close()
    assert added(path) == (["max_distance = 732"], []), added(path)
    assert stat.S_IMODE(os.stat(path).st_mode) == 0o600, oct(os.stat(path).st_mode)


def filter_read_only_save_as(d):
    path = graph(d, "shipped.ini", 0o444)
    win = Window(voxrg, "shipped.ini", d)
    keys("m", "slash")
    xdo("type", "expo")  # e would cycle the block type, m close the panel, o nothing
    keys("Return", "Right")  # view.exposure 0.35 -> 0.4 (a fifth of its default: 0..100 bounds it, no scale)
    keys("ctrl+s")
    win.stderr_has(r"error: save shipped\.ini: the file is read-only \(mode 0444\): not replaced; save a copy with ctrl\+shift\+s")
    keys("ctrl+shift+s", "Return")
    win.stderr_has(r"saved 1 value to shipped-edited\.ini \(a copy of shipped\.ini, which stays as it is\)")
    keys("ctrl+shift+s", "Return")
    win.stderr_has(r"error: save as 'shipped-edited\.ini': the file exists: not written")
    keys("ctrl+shift+s", "BackSpace", "BackSpace", "BackSpace")
    xdo("type", "conf")
    keys("Return")
    win.stderr_has(r"saved 1 value to shipped-edited\.conf")
    win.close()
    assert open(path).read() == ORIGINAL and stat.S_IMODE(os.stat(path).st_mode) == 0o444, "the read-only graph changed"
    for copy in ("shipped-edited.ini", "shipped-edited.conf"):
        assert added(os.path.join(d, copy)) == (["exposure = 0.4"], []), (copy, added(os.path.join(d, copy)))


def hard_link(d):
    path = graph(d, "linked.ini")
    os.link(path, os.path.join(d, "other-name.ini"))
    win = Window(voxrg, "linked.ini", d)
    keys("m", "Down", "Right", "ctrl+s")  # scene.time_of_day 10 -> 11
    win.stderr_has(r"warning: save linked\.ini: the file has 1 other hard link: it is replaced under this name only, "
                   r"the other names keep the old text")
    win.stderr_has("saved 1 value to linked.ini")
    win.close()
    assert added(path) == (["time_of_day = 11"], ["time_of_day = 10"]), added(path)
    assert open(os.path.join(d, "other-name.ini")).read() == ORIGINAL, "the other link changed"


SHADER = """#version 460
// gain: the colour times a gain
#include "pixel.glsl"
layout(local_size_x = VRG_GROUP_X, local_size_y = VRG_GROUP_Y) in;
layout(binding = 0) uniform sampler2D in_color;
layout(binding = 1, rgba16f) uniform writeonly image2D out_color;
layout(push_constant) uniform Params {
    float gain; // @param default=1 min=0 max=4 help="multiplies the colour"
} params;
void shade(ivec2 p)
{
    ivec2 size = imageSize(out_color);
    if (any(greaterThanEqual(p, size)))
        return;
    imageStore(out_color, p, params.gain * texelFetch(in_color, vrg_pixel_in(p, size, textureSize(in_color, 0)), 0));
}
void main() { for (uint k = 0u; k < VRG_PIXEL_ROWS; k++) shade(vrg_pixel(k)); }
"""


def shader_pass(d):
    """rows after the view's: the shader-only pass gain's one parameter"""
    with open(os.path.join(d, "gain.comp"), "w") as f:
        f.write(SHADER)
    path = os.path.join(d, "shader.ini")
    with open(path, "w") as f:
        f.write(ORIGINAL.replace("[graph]\n", "[graph]\nplugin_path = .\n").replace("output = view", "output = bright")
                + "\n[pass gain]\nplugin    = gain\nin.color  = view\nout.color = bright\n")
    before = open(path).read().splitlines()
    win = Window(voxrg, "shader.ini", d)
    keys("m", "Next", "Next", "Right", "ctrl+s")  # gain.gain 1 -> 1.2
    win.stderr_has("saved 1 value to shader.ini")
    win.close()
    added = [l for l in open(path).read().splitlines() if l not in before]
    assert added == ["gain = 1.2"], added


def main():
    return run_cases(out, (jump_step_set_back, filter_read_only_save_as, hard_link, shader_pass))


if __name__ == "__main__":
    sys.exit(main())
