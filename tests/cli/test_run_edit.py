#!/usr/bin/env python3
"""Block editing in `voxrg run`, driven like a user (xdotool under Xvfb):
the cursor over the terrain, a left click removes the block (the journal
beside the graph gains a record, the picture changes), Ctrl+Z restores the
picture, a right click places the selected type against the face hit (the
block beside the restored one), a right drag still turns the view and
places nothing; a graph without a journal edits in memory and says so; the
next run says that it replays the journal; screenshots go to out/,
numbered on from those there.
Usage: test_run_edit.py VOXRG TESTS_DIR OUT_DIR"""
import os
import struct
import sys
import time

sys.dont_write_bytecode = True
voxrg, tests, out = sys.argv[1:4]
sys.path.insert(0, os.path.join(tests, "cli"))
from window import Window, changed, run_cases, xdo  # noqa: E402

TERRAIN = """[graph]
name   = edit_terrain
output = view
width  = 160
height = 100

[camera]
position = 8 44 8
yaw      = 30
pitch    = -50

[scene]
plugin     = terrain
seed       = 7
radius     = 1
threads    = 2

[pass view]
plugin    = world_debug
in.world  = world
in.frame  = frame
out.color = view
mode      = 0
"""


def records(journal):
    data = open(journal, "rb").read()
    n = struct.unpack("<I", data[8:12])[0]
    body = data[8 + 4 + n + 4:]
    assert len(body) % 20 == 0, len(body)
    return [(chr(body[i]), body[i + 1], body[i + 2], struct.unpack("<iii", body[i + 4:i + 16])) for i in range(0, len(body), 20)]


def main():
    return run_cases(out, (terrain, no_journal))


def terrain(d):
    with open(os.path.join(d, "terrain.ini"), "w") as f:
        f.write(TERRAIN)
    journal = os.path.join(d, "terrain.ini.edits")
    win = Window(voxrg, "terrain.ini", d)
    xdo("key", "h")  # the picture alone (the overlay's rates change every frame)
    xdo("mousemove", "--window", win.wid, "80", "50")
    win.settled()
    # the block under the cursor is outlined (edit.c's colour) around the cursor
    xdo("key", "h")
    w, h, px = win.screenshot()
    outline = [(x, y) for y in range(20, 80) for x in range(50, 110) if max(abs(a - b) for a, b in zip(px(x, y), (255, 230, 60))) < 12]
    assert len(outline) >= 8, f"no outline near the cursor: {len(outline)} pixels"
    xdo("key", "h")  # the picture alone again
    before = win.screenshot()
    xdo("click", "1")
    removed = win.stderr_has(r"edit: removed (?!air)\w+ at (-?\d+) (-?\d+) (-?\d+)\n")
    removed = tuple(map(int, removed))
    assert records(journal) == [("E", records(journal)[0][1], 0, removed)], records(journal)
    assert records(journal)[0][1] != 0, "the removed block was air"
    after = win.screenshot()
    assert changed(before, after) > 0, "the removal did not change the picture"
    xdo("key", "ctrl+z")
    win.stderr_has("edit: undo done")
    undone = win.screenshot()
    assert changed(before, undone) == 0, f"undo left {changed(before, undone)} pixels changed"
    xdo("click", "3")
    placed = tuple(map(int, win.stderr_has(r"edit: placed stone at (-?\d+) (-?\d+) (-?\d+)\n")))
    assert sum(abs(a - b) for a, b in zip(placed, removed)) == 1, (placed, removed)
    rec = records(journal)
    assert [r[0] for r in rec] == ["E", "U", "E"] and rec[2][1:] == (0, 3, placed), rec
    assert changed(before, win.screenshot()) > 0, "the placed block is not drawn"
    # a right drag turns the view and places nothing
    xdo("mousedown", "3")
    for _ in range(8):
        xdo("mousemove_relative", "--", "8", "0")
        time.sleep(0.05)
    xdo("mouseup", "3")
    win.screenshot()
    assert len(records(journal)) == 3, records(journal)
    win.close()
    assert "edits: replayed" not in win.said(), "a new journal was said to be replayed"
    # screenshots went to out/, none beside the graph
    assert not [f for f in os.listdir(d) if f.endswith(".png")], os.listdir(d)
    taken = sorted(os.listdir(os.path.join(d, "out")))
    assert taken[0] == "screenshot-000.png" and len(taken) == win.shots, taken
    # the next run replays the journal and says so; its screenshots follow the earlier ones
    win = Window(voxrg, "terrain.ini", d)
    win.stderr_has(r"edits: replayed 3 edit records from terrain\.ini\.edits \(remove it to start from the unedited world\)")
    win.screenshot()
    assert os.path.exists(os.path.join(d, "out", f"screenshot-{len(taken):03d}.png")), sorted(os.listdir(os.path.join(d, "out")))
    win.close()


def no_journal(d):
    """blocks has no journal: the click edits the world in memory, undo says why it cannot."""
    win = Window(voxrg, os.path.join(tests, "graphs", "blocks_wall.ini"), d)
    xdo("key", "h")
    xdo("mousemove", "--window", win.wid, "80", "50")
    before = win.settled()
    xdo("click", "1")
    win.stderr_has(r"edit: removed (?!air)\w+ at -?\d+ -?\d+ -?\d+ \(no journal: in memory only, no undo\)")
    assert changed(before, win.screenshot()) > 0, "the in-memory removal did not change the picture"
    xdo("key", "ctrl+z")
    win.stderr_has(r"edit: no journal \(a graph from text, or edits = none\): nothing to undo")
    win.close()
    assert not [f for f in os.listdir(os.path.join(tests, "graphs")) if f.endswith(".edits")], "a journal appeared beside blocks_wall.ini"


if __name__ == "__main__":
    sys.exit(main())
