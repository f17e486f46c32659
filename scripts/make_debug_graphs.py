#!/usr/bin/env python3
"""Writes graphs/debug-svgf.ini, graphs/debug-clamped.ini and
graphs/debug-surface-cache.ini: one shipped graph of each denoiser family
(thesis.ini, penumbra-clamped-4ray.ini, surface-cache-4ray.ini), unchanged,
plus a `tiles` pass that shows its temporal passes' debug outputs side by
side with the images they explain, as NRD's validation layer does, and
made the output. Reading them makes the passes compute those outputs
(passes/*/README.md, "Debug outputs"). Each debug graph is its base graph's
text with a new opening comment, name and output and the tiles pass
appended, so that the two cannot drift apart: edit the base graph, then
rerun this (test debug_graphs compares).
usage: make_debug_graphs.py [OUT_DIR]   (default: the graphs/ folder beside this script)"""
import os
import sys

# (debug graph, base graph, what it shows, tiles: (input, channel, min, max, heat, what))
GRAPHS = [
    ("debug-svgf", "thesis", "SVGF (svgf_reproject, svgf_variance)", [
        ("illumination", "rgb", 0, 4, 0, "this frame's noisy illumination"),
        ("reproject.color", "rgb", 0, 4, 0, "the temporal accumulation"),
        ("reproject.length", "r", 0, 32, 1, "history length, 0 to max_length 32"),
        ("reproject.disocclusion", "r", 0, 1, 0, "disocclusion: white where the history restarted"),
        ("reproject.reprojection", "a", 0, 6, 1, "how the history was read: black none, blue bilinear, cyan the 3x3 fallback"),
        ("reproject.reprojection", "b", 0, 1, 0, "weight of the history taps that passed"),
        ("variance.variance", "r", 0, 0.25, 1, "the luminance variance steering the a-trous filter"),
        ("atrous.color", "rgb", 0, 4, 0, "the filtered illumination"),
        ("ldr", "rgb", 0, 1, 0, "the final image"),
    ]),
    ("debug-clamped", "penumbra-clamped-4ray", "the clamped temporal stages (clamped_reproject, mean_variance) on the indirect light", [
        ("indirect", "rgb", 0, 1, 0, "this frame's noisy indirect light"),
        ("indirect_reproject.color", "rgb", 0, 1, 0, "its temporal accumulation"),
        ("indirect_reproject.length", "r", 0, 32, 1, "history length after anti-lag, 0 to max_length 32"),
        ("indirect_reproject.disocclusion", "r", 0, 1, 0, "disocclusion: white where the history restarted"),
        ("indirect_reproject.clamp", "r", 0, 0.05, 1, "how far the neighbourhood clamp moved the history"),
        ("indirect_reproject.clamp", "g", 0, 1, 1, "anti-lag's share of the way to the fast history"),
        ("indirect_reproject.reprojection", "a", 0, 6, 1, "how the history was read: black none, blue bilinear, cyan 3x3, green cubic, yellow nearest"),
        ("indirect_variance.variance", "r", 0, 0.01, 1, "the variance of the accumulated mean"),
        ("ldr", "rgb", 0, 1, 0, "the final image"),
    ]),
    ("debug-surface-cache", "surface-cache-4ray", "the surface caches (surface_cache) of the sun and the indirect light", [
        ("indirect", "rgb", 0, 1, 0, "this frame's noisy indirect light"),
        ("indirect_cache.color", "rgb", 0, 1, 0, "its cached value"),
        ("indirect_cache.occupancy", "r", 0, 128, 1, "samples its cells hold"),
        ("indirect_cache.occupancy", "b", 0, 1, 0, "share of the colour from the fine cells (the rest: the coarse level)"),
        ("indirect_cache.occupancy", "a", 0, 8, 1, "frames since the cells last had samples (evict_frames 8)"),
        ("sun", "r", 0, 1, 0, "this frame's noisy sun visibility"),
        ("sun_cache.color", "r", 0, 1, 0, "its cached value"),
        ("sun_cache.occupancy", "r", 0, 16, 1, "samples the sun's cells hold"),
        ("ldr", "rgb", 0, 1, 0, "the final image"),
    ]),
]


def number(v):
    return f"{v:g}"


def debug_graph(root, name, base, what, tiles):
    text = open(os.path.join(root, f"{base}.ini"), encoding="utf-8").read()
    lines = text.split("\n")
    start = next(i for i, line in enumerate(lines) if line.startswith("["))
    body = lines[start:]
    out, replaced = [], set()
    section = None
    for line in body:
        if line.startswith("["):
            section = line.strip()
        key = line.split("=")[0].strip() if "=" in line and not line.startswith(";") else None
        if section == "[graph]" and key == "name":
            line = f"name   = {name}"
            replaced.add("name")
        elif section == "[graph]" and key == "output":
            line = "output = tiles"
            replaced.add("output")
        out.append(line)
    if replaced != {"name", "output"}:
        raise SystemExit(f"{base}.ini: no [graph] name or output to replace")
    while out and out[-1] == "":
        out.pop()
    head = [f"; Debug view of {what}: graphs/{base}.ini, unchanged, and a",
            "; `tiles` pass that shows the temporal passes' debug outputs side by side",
            "; (passes/*/README.md, \"Debug outputs\"), as NRD's validation layer does;",
            "; reading them makes those passes compute them. Left to right, top to",
            "; bottom:"]
    for i, (res, channel, lo, hi, heat, say) in enumerate(tiles):
        head.append(f";   {i}  {res}{'' if channel == 'rgb' else ' (' + channel + ')'}: {say}"
                    f" [{number(lo)}, {number(hi)}{', false colour' if heat else ''}]")
    head += [f"; Written by scripts/make_debug_graphs.py from graphs/{base}.ini: edit",
             "; that, then rerun the script (test debug_graphs compares). Every image is",
             "; also in voxrg run's Tab and render --dump."]
    tail = ["", "[pass tiles]", "plugin  = tiles"]
    for i, (res, *_rest) in enumerate(tiles):
        tail.append(f"in.t{i}   = {res}")
    tail.append("out.view = tiles")
    for i, (res, channel, lo, hi, heat, _say) in enumerate(tiles):
        if channel != "rgb":
            tail.append(f"t{i}_channel = {channel}")
        if lo != 0:
            tail.append(f"t{i}_min = {number(lo)}")
        if hi != 1:
            tail.append(f"t{i}_max = {number(hi)}")
        if heat:
            tail.append(f"t{i}_heat = 1")
    return "\n".join(head + out + tail) + "\n"


def main():
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "graphs")
    out_dir = sys.argv[1] if len(sys.argv) > 1 else root
    for name, base, what, tiles in GRAPHS:
        text = debug_graph(root, name, base, what, tiles)
        path = os.path.join(out_dir, f"{name}.ini")
        tmp = path + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)


if __name__ == "__main__":
    main()
