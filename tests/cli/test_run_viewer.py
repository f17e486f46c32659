#!/usr/bin/env python3
"""The image viewer and the inspector of `voxrg run`, driven like a user
(xdotool under Xvfb), their words read back from screenshots: the overlay's
text is decoded with the overlay's own font (parsed from core/cli/overlay.c),
so each check reads what a user reads. On tests/graphs/chain.ini, whose
gradient has a closed form (pattern: (x/39, y/23, 0.5, 1) as halves):
- value: Tab shows the gradient; the value under the cursor is the
  gradient's at that texel, exactly, and follows the cursor; 0 and V show
  the output through the viewer, its value 2x the gradient's inside (a
  3x3 box blur of a linear ramp is the ramp);
- scale_bar: C and V show channel r in false colour; the bar's colour at
  t is the image's colour where r = t (the auto range is 0..1), and its
  words say what is mapped and the ends' values;
- keys_before_switch: C and V pressed after Tab but before the gradient
  is shown (the frame frozen, F, until G renders one) are the gradient's:
  its bar's caption says so (they were the old image's, then lost to the
  new image's own view);
- range_keys_before_switch: the same with C, V, . (exposure) and R: the
  gradient's alpha range is held where its own figures put it, and
  exposed;
- inspector: I shows every image at the pixel in schedule order (gen's
  gradient, smooth's blurred, sum's final), the gradient's values exact; a
  click pins the pixel (the cursor moves, the table stays); F freezes: the
  frame number stays; G steps it by one;
- read_twice: on tests/graphs/gbuffer_blocks.ini, an integer image (ids)
  and a float32 one (position): the value under the cursor is the
  inspector's row of that image;
- ab: --ab (B's gradient with blue 0.25): Tab shows both sides' gradient,
  the value under the cursor on B is B's; the divider is drawn.
Usage: test_run_viewer.py VOXRG TESTS_DIR OUT_DIR"""
import os
import re
import struct
import sys
import time

sys.dont_write_bytecode = True
voxrg, tests, out = sys.argv[1:4]
sys.path.insert(0, os.path.join(tests, "cli"))
from window import Window, run_cases, xdo  # noqa: E402

GRAPH = os.path.join(tests, "graphs", "chain.ini")
SOURCE = os.path.join(os.path.dirname(os.path.abspath(tests)), "core", "cli", "overlay.c")
# the window: 40x24 render pixels shown 12x12 each
ARGS = ("--window", "480x288", "--size", "40x24", "--filter", "nearest")
CELL = 12
# overlay.h: glyphs 5x8 doubled in cells 12 wide, lines 18 high, boxes padded 4
GLYPH_W, GLYPH_H, SCALE, CELL_W, LINE_H, PAD = 5, 8, 2, 12, 18, 4


def font():
    """overlay.c's glyphs: their rows -> the character."""
    glyphs = {}
    for rows, code in re.findall(r"\{((?:0x[0-9a-f]{2}, ){7}0x[0-9a-f]{2})\}, /\* (\d+) ", open(SOURCE).read()):
        glyphs[tuple(int(r, 16) for r in rows.split(", "))] = chr(int(code))
    assert len(glyphs) == 95, f"{len(glyphs)} glyphs parsed from {SOURCE}"
    return glyphs


GLYPHS = font()


def text_at(shot, x0, y0):
    """The line of overlay text whose first cell's top-left is (x0, y0):
    white pixels are the text (the boxes under it are translucent black), up
    to the first cell that is no glyph."""
    w, h, px = shot
    chars = []
    for c in range((w - x0) // CELL_W):
        rows = []
        for gy in range(GLYPH_H):
            bits = 0
            for gx in range(GLYPH_W):
                x, y = x0 + c * CELL_W + gx * SCALE, y0 + gy * SCALE
                bits = bits << 1 | (y < h and px(x, y) == (255, 255, 255))
            rows.append(bits)
        if tuple(rows) not in GLYPHS:  # not text: the picture beside or below a box
            break
        chars.append(GLYPHS[tuple(rows)])
    return "".join(chars).rstrip(" ")


def overlay_text(shot, top=0):
    """The top-left box's lines, joined (wrapped lines go on where they
    broke); with --ab the box is under the sides' labels, at top."""
    lines = []
    for i in range((shot[1] - top) // LINE_H):
        line = text_at(shot, PAD, top + PAD + i * LINE_H)
        if not line.strip():
            break
        lines.append(line)
    return " ".join(" ".join(lines).split())


def half(v):
    return struct.unpack("e", struct.pack("e", v))[0]


def halves(v):
    """v as a half: rounded to the nearest, or towards zero (as lavapipe's
    imageStore does): the exact value is one of them."""
    near = half(v)
    if abs(near) <= abs(v):
        return {near}
    bits = struct.unpack("<H", struct.pack("e", near))[0]
    return {near, struct.unpack("e", struct.pack("<H", bits - 1))[0]}


def gradient(x, y, blue=0.5):
    return [half(x / 39), half(y / 23), blue, 1.0]


def printed(v):
    """v as the overlay prints it (%.6g)."""
    return float(f"{v:.6g}")


def is_gradient(got, x, y, blue=0.5):
    """got is the gradient's texel (x, y) as stored, as printed."""
    return got[0] in map(printed, halves(x / 39)) and got[1] in map(printed, halves(y / 23)) and got[2:] == [blue, 1.0]


def near(got, want, rel=1e-5):
    return all(abs(float(g) - w) <= rel * max(1.0, abs(w)) for g, w in zip(got, want)) and len(got) == len(want)


def shown_value(shot, name, top=0):
    """The viewer's line 'NAME X,Y: r R g G b B a A' as ((X, Y), [R, G, B, A])."""
    text = overlay_text(shot, top)
    m = re.search(re.escape(name) + r" (\d+),(\d+): r (\S+) g (\S+) b (\S+) a (\S+)", text)
    assert m, f"no value of {name} in the overlay: {text!r}"
    return (int(m.group(1)), int(m.group(2))), [float(v) for v in m.groups()[2:]]


def point(win, tx, ty):
    """The cursor on the middle of texel (tx, ty)."""
    xdo("mousemove", "--window", win.wid, str(tx * CELL + CELL // 2), str(ty * CELL + CELL // 2))


def settle(win, test, what, tries=40):
    """A screenshot that passes test (the viewer's figures are the last
    frame's: the first after a key may still show the one before)."""
    for _ in range(tries):
        shot = win.screenshot()
        try:
            if test(shot):
                return shot
        except AssertionError:
            pass
        time.sleep(0.1)
    sys.exit(f"FAIL: {what}: overlay said {overlay_text(shot)!r} / {overlay_text(shot, LINE_H + 8)!r}")


def value(d):
    win = Window(voxrg, GRAPH, d, args=ARGS)
    xdo("key", "Tab")  # the first image: the gradient
    for tx, ty in ((12, 8), (31, 3)):
        point(win, tx, ty)
        settle(win, lambda s: shown_value(s, "gradient")[0] == (tx, ty) and is_gradient(shown_value(s, "gradient")[1], tx, ty),
               f"gradient's value at {tx},{ty}")
    xdo("key", "0")  # the output, as it is: no value line
    point(win, 20, 12)
    settle(win, lambda s: "final" in overlay_text(s) and ": r " not in overlay_text(s), "the output as it is, without values")
    xdo("key", "v")  # the output through the viewer: its value, 2x the gradient's inside
    settle(win, lambda s: shown_value(s, "final")[0] == (20, 12) and near(shown_value(s, "final")[1], [2 * v for v in gradient(20, 12)], 1e-3),
           "final's value at 20,12")
    win.close()


# run.c's scale_bar_rect for a 480x288 window: 320 wide, 10 high, at (12, 252)
BAR_X, BAR_Y, BAR_W = 12, 252, 320


def red_false_colour(shot):
    """The scale bar's caption says: the gradient's r in false colour."""
    return text_at(shot, BAR_X - 8 + PAD, BAR_Y - 4 - LINE_H) == "gradient: false colour of r, auto"


def scale_bar(d):
    win = Window(voxrg, GRAPH, d, args=ARGS)
    xdo("key", "Tab")
    xdo("key", "c")  # channel r
    xdo("key", "v")  # colour -> range
    xdo("key", "v")  # range -> false colour
    point(win, 5, 1)
    bar_x, bar_y, bar_w = BAR_X, BAR_Y, BAR_W
    shot = settle(win, red_false_colour, "the bar's caption")
    assert text_at(shot, bar_x, bar_y + 10 + 3).split(" ")[0] == "0", text_at(shot, bar_x, bar_y + 10 + 3)
    w, h, px = shot
    row = 12 * CELL + CELL // 2  # below the text, above the bar
    colours = set()
    for tx in (0, 10, 20, 30, 39):
        t = half(tx / 39)
        image = px(tx * CELL + CELL // 2, row)
        bar = px(bar_x + min(bar_w - 1, int(t * bar_w)), bar_y + 5)
        assert max(abs(a - b) for a, b in zip(image, bar)) <= 6, f"r = {t}: the image shows {image}, the bar {bar}"
        colours.add(image)
    assert len(colours) == 5, f"false colour of r: {colours}"
    win.close()


def keys_before_switch(d):
    win = Window(voxrg, GRAPH, d, args=ARGS)
    xdo("key", "f")  # frozen: the image Tab asks for comes with the next frame
    xdo("key", "Tab", "c", "v", "v")
    xdo("key", "g")  # that frame
    point(win, 5, 1)
    settle(win, red_false_colour, "C and V pressed before the gradient was shown")
    win.close()


def range_keys_before_switch(d):
    """Exposure (.) and R pressed with C and V before the gradient is shown:
    the gradient's caption says its alpha's range is held and exposed, and
    the held range is where the gradient's figures put it (alpha is 1
    everywhere, a single value the viewer centres: 0.5..1.5, so the bar
    starts at 0.5), not 0..1 (R applied before the gradient's first
    figures)."""
    win = Window(voxrg, GRAPH, d, args=ARGS)
    xdo("key", "f")
    xdo("key", "Tab", "c", "c", "c", "c", "v", "v", "period", "r")
    xdo("key", "g")
    point(win, 5, 1)

    def held_alpha(shot):
        # the caption wraps at this window's width: its two lines
        lines = (text_at(shot, BAR_X - 8 + PAD, BAR_Y - 4 - k * LINE_H).strip() for k in (2, 1))
        caption = " ".join(line for line in lines if line)
        assert caption == "gradient: false colour of a, held, +0.5 EV", caption
        return text_at(shot, BAR_X, BAR_Y + 10 + 3).split(" ")[0] == "0.5"

    settle(win, held_alpha, "C, V, . and R pressed before the gradient was shown")
    win.close()


def table(shot):
    """The inspector's title and rows: (title, [(pass, resource, [values])])."""
    lines = []
    for i in range(shot[1] // LINE_H):
        line = text_at(shot, PAD, PAD + i * LINE_H)
        if not line.strip():
            break
        if line.startswith("  ") and lines:  # a wrapped line's rest
            lines[-1] += " " + line.strip()
        else:
            lines.append(line)
    at = [i for i, l in enumerate(lines) if l.startswith("inspect")]
    assert at, f"no inspector in the overlay: {lines}"
    rows = []
    for l in lines[at[0] + 1:]:
        p = l.split()
        values = []
        for v in p[2:]:  # up to a note: the motion row's "(last frame at X,Y)"
            if v.startswith("("):
                break
            values.append(float(v))
        rows.append((p[0], p[1], values))
    return lines[at[0]], rows


def inspector(d):
    win = Window(voxrg, GRAPH, d, args=ARGS)
    xdo("key", "i")
    point(win, 9, 15)

    def has(s, x, y):
        title, rows = table(s)
        assert f"inspect {x},{y} " in title, title
        assert [r[:2] for r in rows] == [("gen", "gradient"), ("smooth", "blurred"), ("sum", "final")], rows
        assert is_gradient(rows[0][2], x, y), rows[0]
        assert near(rows[2][2], [2 * v for v in gradient(x, y)], 1e-3), rows[2]
        return True

    settle(win, lambda s: has(s, 9, 15), "the table at 9,15")
    xdo("click", "1")  # pinned
    point(win, 30, 4)
    shot = settle(win, lambda s: "pinned" in table(s)[0] and has(s, 9, 15), "the pinned pixel's table")
    xdo("key", "f")  # frozen
    frame = lambda s: int(re.search(r"frame (\d+)", table(s)[0]).group(1))
    shot = settle(win, lambda s: "frozen" in table(s)[0], "frozen")
    first = frame(shot)
    assert frame(win.screenshot()) == first, "a frozen frame moved on"
    xdo("key", "g")
    settle(win, lambda s: frame(s) == first + 1, f"g: frame {first + 1}")
    assert frame(win.screenshot()) == first + 1, "g stepped more than a frame"
    xdo("click", "1")  # following the cursor again
    settle(win, lambda s: has(s, 30, 4), "the table at the cursor again")
    win.close()


def read_twice(d):
    """An integer image and a float32 one: the value under the cursor (the
    display stage's copy of the texel) is the inspector's for that image
    (vrg_graph_read_pixels), read apart."""
    graph = os.path.join(tests, "graphs", "gbuffer_blocks.ini")
    for name, channels in (("gbuffer.ids", 2), ("gbuffer.position", 4)):
        win = Window(voxrg, graph, d, args=("--window", "640x470", "--size", "320x235", "--filter", "nearest", "--show", name))
        xdo("key", "i")
        xdo("mousemove", "--window", win.wid, "301", "301")  # texel 150,150

        def same(s):
            m = re.search(re.escape(name) + r" 150,150: ((?:[rgba] \S+ ?)+)", overlay_text(s))
            assert m, overlay_text(s)
            viewer = [float(v) for v in m.group(1).split()[1::2]]
            rows = {(p, r): v for p, r, v in table(s)[1]}
            return viewer == rows[("gbuffer", name)] and len(viewer) == channels and any(viewer)

        settle(win, same, f"{name}: the value under the cursor and the inspector's")
        win.close()


def ab(d):
    top = LINE_H + 8  # run.c: the box under the labels
    b = os.path.join(d, "b.ini")
    with open(b, "w") as f:  # B: blue 0.25
        f.write(open(GRAPH).read().replace("out.color = gradient", "out.color = gradient\nvalue     = 0.25"))
    win = Window(voxrg, GRAPH, d, args=(*ARGS, "--ab", b))
    xdo("key", "Tab")  # both sides: the gradient
    point(win, 30, 8)  # right of the divider (at 240): B's
    settle(win, lambda s: shown_value(s, "B gradient", top)[0] == (30, 8) and is_gradient(shown_value(s, "B gradient", top)[1], 30, 8, 0.25),
           "B's gradient under the cursor")
    point(win, 6, 8)
    shot = settle(win, lambda s: shown_value(s, "A gradient", top)[0] == (6, 8) and is_gradient(shown_value(s, "A gradient", top)[1], 6, 8),
                  "A's gradient under the cursor")
    w, h, px = shot
    row = 14 * CELL
    assert [px(x, row) for x in range(238, 242)] == [(0, 0, 0), (255, 255, 255), (255, 255, 255), (0, 0, 0)], \
        [px(x, row) for x in range(236, 244)]
    # the same view on both: blue 0.5 on A, 0.25 on B, red and green alike at the same texel
    left, right = px(19 * CELL + 6, row), px(21 * CELL + 6, row)
    assert left[2] > right[2] + 20, (left, right)
    win.close()


def main():
    return run_cases(out, (value, scale_bar, keys_before_switch, range_keys_before_switch, inspector, read_twice, ab))


if __name__ == "__main__":
    sys.exit(main())
