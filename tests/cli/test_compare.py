#!/usr/bin/env python3
"""voxrg compare end to end, at small sizes:
- raw.ini against thesis.ini on the walk path against a (cheaper) reference:
  the denoised graph scores better on PSNR and FLIP; report.html is valid
  HTML (parsed, tags balanced) whose summary numbers equal metrics.json's,
  with its images (decodable PNGs) and plots; metrics.csv agrees; every
  frame's PNG is there; a second run takes every reference frame from the
  cache and gives the same numbers.
- a candidate identical to the reference: PSNR at the cap, SSIM 1, FLIP 0,
  temporal error 0.
- errors: another scene, another size, a missing reference, a variant with
  an unknown parameter, a variant that changes the scene: exit 1, a clear
  message, no report left behind.
- names: variant names outside the safe set refused; graph names that
  would overwrite the reference's frames or break metrics.csv handled.
- --score device: the metrics computed on the rendering device agree with
  the CPU's (the tolerances of docs/compare.md) frame by frame, with
  validation on, also over cases of two sizes; only the frames the report
  shows are written; --score with another value is a usage error.
- variants of a named graph (NAME@GRAPH:...): a variant of the second graph
  renders that graph, not the first; the report says which; a GRAPH not
  listed, or listed twice, is a usage error (exit 2) naming the candidates.
- the reference cache: a vox scene's model is in the key by content; a
  replaced, altered or cut-short entry is named in a warning and rendered
  again; processes filling one cache at once leave whole entries.
- scenes that read different data files (an edit journal beside the
  reference only, another model under one name): an error.
- shards: --shard 0/3, 1/3 (as auto/3 from SLURM_ARRAY_TASK_ID), 2/3 as
  separate processes, then --merge: metrics.csv and metrics.json (but its
  timings) equal one process's exactly, scored on the CPU or on the device;
  a missing, duplicated, cut-short or foreign shard (other settings, other
  scoring), --shard 3/3 and --shard with --merge are errors.
Usage: test_compare.py VOXRG SOURCE_DIR OUT_DIR [CASE]
The cases (CASES below) are independent: ctest runs each as its own test
(compare_CASE, each with its own OUT_DIR) so that they spread over the cores;
without CASE all run in order."""
import base64
import html.parser
import json
import os
import re
import shutil
import subprocess
import sys

VOXRG, SRC, OUT = sys.argv[1:4]
ONLY = sys.argv[4] if len(sys.argv) > 4 else None
GRAPHS = os.path.join(SRC, "graphs")
CACHE = os.path.join(OUT, "cache")
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print("FAIL:", what, flush=True)
    return cond


def compare(*args, out):
    cmd = [VOXRG, "compare", *args, "--out", out, "--cache", CACHE, "--validate"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


class Page(html.parser.HTMLParser):
    """Checks nesting and collects what the tests read."""
    VOID = {"meta", "img", "br", "hr", "input", "link", "source", "col", "area", "base", "wbr"}
    SVG_LEAVES = {"line", "rect", "polyline", "path", "circle"}  # may be self-closed

    def __init__(self):
        super().__init__()
        self.stack, self.errors, self.cells, self.images, self.polylines, self.svgs = [], [], [], [], 0, 0
        self.row = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "tr" and "data-candidate" in a:
            self.row = a["data-candidate"]
        if tag == "td" and "data-metric" in a:
            self.cells.append([self.row, a["data-metric"], a["data-value"], ""])
        if tag == "img":
            self.images.append(a.get("src", ""))
        self.polylines += tag == "polyline"
        self.svgs += tag == "svg"
        if tag not in self.VOID:
            self.stack.append(tag)

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag not in self.VOID:
            self.stack.pop()

    def handle_endtag(self, tag):
        if tag in self.VOID:
            return
        if not self.stack or self.stack[-1] != tag:
            self.errors.append("</%s> closes <%s> at %s" % (tag, self.stack[-1] if self.stack else "nothing", self.getpos()))
            return
        self.stack.pop()

    def handle_data(self, data):
        if self.cells and self.stack and self.stack[-1] == "td" and self.cells[-1][3] == "":
            self.cells[-1][3] = data.strip()


def e2e():
    out = os.path.join(OUT, "e2e")
    args = [os.path.join(GRAPHS, "raw.ini"), os.path.join(GRAPHS, "thesis.ini"), "--reference", os.path.join(GRAPHS, "reference.ini"),
            "--ref-set", "converge.samples_per_frame=16", "--camera", os.path.join(GRAPHS, "paths", "walk.path"),
            "--size", "160x90", "--frames", "10", "--warmup", "4"]
    rc, stdout, stderr = compare(*args, out=out)
    if not check(rc == 0, "compare raw thesis: exit %d\n%s" % (rc, stderr[-3000:])):
        return
    check(re.search(r"^thesis .*\*", stdout, re.M) is not None, "no summary table on stdout:\n" + stdout)
    j = json.load(open(os.path.join(out, "metrics.json")))
    c = {x["name"]: x for x in j["candidates"]}
    raw, thesis = c["raw"]["summary"], c["thesis"]["summary"]
    check(thesis["psnr"] > raw["psnr"], "PSNR: thesis %.3f, raw %.3f" % (thesis["psnr"], raw["psnr"]))
    check(thesis["flip"] < raw["flip"], "FLIP: thesis %.4f, raw %.4f" % (thesis["flip"], raw["flip"]))
    check(j["frames"] == 10 and j["warmup"] == 4 and j["width"] == 160 and len(c["raw"]["frames"]) == 10, "metrics.json header")
    check(c["raw"]["frames"][0]["temporal"] is None and c["raw"]["frames"][1]["temporal"] is not None, "temporal error starts at frame 1")
    check(all(p["mean_ms"] >= 0 and p["p95_ms"] >= p["mean_ms"] * 0.5 for p in c["thesis"]["passes"]) and
          {"gbuffer", "reproject", "atrous"} <= {p["name"] for p in c["thesis"]["passes"]}, "per-pass timings of thesis")
    # summary = mean of the frames from warmup on
    for name, cand in c.items():
        for m in ("psnr", "ssim", "flip", "temporal"):
            vals = [f[m] for f in cand["frames"][4:]]
            check(abs(sum(vals) / len(vals) - cand["summary"][m]) < 1e-6 * max(1, abs(cand["summary"][m])), "%s %s summary" % (name, m))
    # the report: valid, numbers equal metrics.json's
    page = Page()
    page.feed(open(os.path.join(out, "report.html")).read())
    page.close()
    check(not page.errors and not page.stack, "report.html nesting: %s, unclosed %s" % (page.errors[:3], page.stack))
    fmt = {"psnr": "%.2f", "ssim": "%.4f", "flip": "%.4f", "temporal": "%.5f", "gpu_ms_mean": "%.2f", "gpu_ms_p95": "%.2f"}
    check(len(page.cells) == 2 * 6, "summary cells: %d" % len(page.cells))
    for row, metric, value, text in page.cells:
        want = c[row]["summary"].get(metric, c[row]["summary"].get(metric.replace("gpu_ms_", "gpu_ms_")))
        check(float(value) == want, "report %s %s = %s, metrics.json %s" % (row, metric, value, want))
        check(text.split()[0] == fmt[metric] % want, "report %s %s shows '%s', want %s" % (row, metric, text, fmt[metric] % want))
    best = re.findall(r'<td class="num best" data-metric="(\w+)"', open(os.path.join(out, "report.html")).read())
    check(sorted(best) == sorted(["psnr", "ssim", "flip", "temporal", "gpu_ms_mean"]), "one best mark per column: %s" % best)
    pngs = [s for s in page.images if s.startswith("data:image/png;base64,")]
    # per shown frame: reference + 2 candidates, a colour bar + 2 FLIP maps, a colour bar + 2 signed differences, 3 crops
    check(len(pngs) == len(page.images) == 3 * 12, "report images: %d inline of %d" % (len(pngs), len(page.images)))
    # the maps' scales: the 99th percentile of the errors, which for these denoisers is far below 1
    text = open(os.path.join(out, "report.html")).read()
    ranges = [float(x) for x in re.findall(r"FLIP error: 0 \(left\) to ([0-9.e+-]+) and above", text)]
    signed = re.findall(r"candidate &#8722; reference, luma: &#8722;([0-9.e+-]+) \(blue\) to \+([0-9.e+-]+) \(red\)", text)
    check(len(ranges) == 3 and all(0.001 <= x < 1 for x in ranges), "FLIP map ranges: %s" % ranges)
    check(len(signed) == 3 and all(a == b and 0.001 <= float(a) <= 1 for a, b in signed), "signed difference ranges: %s" % signed)
    check(all(base64.b64decode(s.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n" for s in pngs), "an inline image is not a PNG")
    # every image zooms where clicked: focusable, and the style scales a focused one
    check(text.count('<img tabindex="0" ') == len(page.images) and ".frames img:focus{transform:scale(3)" in text,
          "report images are not zoomable (tabindex and :focus style)")
    check(page.svgs == 5 and page.polylines == 4 * 2, "plots: %d svg, %d polylines" % (page.svgs, page.polylines))
    # csv = json
    rows = [l.split(",") for l in open(os.path.join(out, "metrics.csv")).read().split("\n")[1:] if l]
    check(len(rows) == 20, "metrics.csv rows: %d" % len(rows))
    for r in rows:
        f = c[r[0]]["frames"][int(r[1])]
        check(all((r[3 + i] == "" and f[m] is None) or float(r[3 + i]) == f[m] for i, m in enumerate(("psnr", "ssim", "flip", "temporal"))),
              "csv row %s differs from metrics.json" % r)
    names = set(os.listdir(os.path.join(out, "frames")))
    check(all("%s-%05d.png" % (n, k) in names for n in ("reference", "raw", "thesis") for k in range(10)), "frames/ misses PNGs")
    # again: the reference from the cache, the same numbers
    rc, _, stderr = compare(*args, out=out + "-again")
    j2 = json.load(open(os.path.join(out + "-again", "metrics.json"))) if rc == 0 else None
    if check(j2 is not None, "second run failed: " + stderr[-2000:]):
        check(j2["reference"]["frames_from_cache"] == 10, "cache: %d of 10 frames" % j2["reference"]["frames_from_cache"])
        check([x["summary"][m] for x in j2["candidates"] for m in ("psnr", "ssim", "flip", "temporal")] ==
              [x["summary"][m] for x in j["candidates"] for m in ("psnr", "ssim", "flip", "temporal")], "a rerun gave other numbers")


def identical():
    """The reference graph as its own candidate: a graph with 8 samples per
    frame, the camera moving every frame (so its accumulation restarts as
    the reference's does)."""
    out = os.path.join(OUT, "identical")
    text = open(os.path.join(GRAPHS, "reference.ini")).read().replace("samples_per_frame = 256", "samples_per_frame = 8")
    os.makedirs(out, exist_ok=True)
    graph = os.path.join(out, "converged.ini")
    open(graph, "w").write(text)
    rc, _, stderr = compare(graph, "--reference", graph, "--camera", os.path.join(GRAPHS, "paths", "walk.path"), "--size", "96x54",
                            "--frames", "3", "--warmup", "0", out=out)
    if not check(rc == 0, "identical: exit %d\n%s" % (rc, stderr[-3000:])):
        return
    s = json.load(open(os.path.join(out, "metrics.json")))["candidates"][0]["summary"]
    check(s["psnr"] == 100 and s["ssim"] == 1 and s["flip"] == 0 and s["temporal"] == 0, "identical candidate: %s" % s)


def errors():
    out = os.path.join(OUT, "errors")
    os.makedirs(out, exist_ok=True)
    raw = os.path.join(GRAPHS, "raw.ini")
    ref = os.path.join(GRAPHS, "reference.ini")
    other = os.path.join(out, "other-world.ini")
    open(other, "w").write(open(raw).read().replace("seed        = 1337", "seed        = 7"))
    small = os.path.join(out, "small.ini")
    open(small, "w").write(open(raw).read().replace("width  = 640", "width  = 320"))
    cases = [
        ("another scene", [raw, other, "--reference", ref], r"scenes differ: .*raw\.ini:\d+ has seed = 1337, .*other-world\.ini:\d+ 7"),
        ("another size", [raw, small, "--reference", ref], r"sizes differ: .*raw\.ini is 640x360, .*small\.ini 320x360"),
        ("a missing reference", [raw, "--reference", os.path.join(out, "nope.ini")], r"reference graph .*nope\.ini: No such file"),
        ("an unknown parameter", [raw, "--variant", "x:ao.nope=1", "--reference", ref], r"has no parameter 'nope'.*\n.*candidate 'x'"),
        # the variant named once, with the value it replaces (not the graph's [scene] line twice)
        ("a variant of the scene", [raw, "--variant", "v:ao.rays=2,scene.radius=2", "--reference", ref],
         r"(?m)^error: --variant v:ao\.rays=2,scene\.radius=2: scene\.radius=2 changes the scene \(raw has 13\): candidates must render the same frames"),
    ]
    open(os.path.join(out, "report.html"), "w").write("<!-- an earlier run's -->")
    for what, args, pattern in cases:
        rc, _, stderr = compare(*args, "--frames", "2", out=out)
        check(rc == 1, "%s: exit %d, want 1" % (what, rc))
        check(re.search(pattern, stderr) is not None, "%s: no /%s/ in:\n%s" % (what, pattern, stderr[-2000:]))
        check(not any(os.path.exists(os.path.join(out, f)) for f in ("report.html", "metrics.json", "metrics.csv")),
              "%s: a report was left behind" % what)

    # only warnings are shown once: two errors that share a hint keep it both
    two = os.path.join(out, "two-errors.ini")
    open(two, "w").write("a = 1\nb = 2\n" + open(raw).read())
    rc, _, stderr = compare(two, "--reference", ref, "--frames", "2", out=out)
    hints = re.findall(r"(?m)^two-errors\.ini:[12]: error\[VRG-E005\].*\n  hint: put every key under a \[section\] header$",
                       stderr.replace(out + os.sep, ""))
    check(rc == 1 and len(hints) == 2, "two errors with one hint: exit %d, %d with their hint in:\n%s" % (rc, len(hints), stderr[-2000:]))


def names():
    """Candidate names become file names under --out and CSV fields: a
    variant's name outside the safe set is refused before any work; a
    graph's name that is the reference's frames' is numbered, one with a
    comma or a quote is quoted in metrics.csv."""
    out = os.path.join(OUT, "names")
    os.makedirs(out, exist_ok=True)
    raw = os.path.join(GRAPHS, "raw.ini")
    ref = os.path.join(GRAPHS, "reference.ini")
    escape = os.path.join(OUT, "escaped")
    for bad in ("reference", "../../escaped", 'a,"b', ".hidden", "x" * 64, "a b"):
        rc, _, stderr = compare(raw, "--variant", bad + ":ao.rays=1", "--reference", ref, "--frames", "2", out=out)
        check(rc == 2, "variant name %r: exit %d, want 2" % (bad, rc))
        check(("--variant '%s:ao.rays=1': a name is 1 to 63 of A-Z a-z 0-9 _ - and dots" % bad) in stderr,
              "variant name %r: message:\n%s" % (bad, stderr[-1000:]))
    check(not os.path.exists(escape + "-00000.png") and not os.path.exists(os.path.join(out, "frames")), "a refused variant wrote frames")
    graphs, small_world = [], lambda text: text.replace("radius      = 13", "radius      = 2")  # cheap to generate
    for name in ("reference.ini", 'a,"b.ini'):
        os.makedirs(os.path.join(out, str(len(graphs))), exist_ok=True)
        graphs.append(os.path.join(out, str(len(graphs)), name))
        open(graphs[-1], "w").write(small_world(open(raw).read()))
    small_ref = os.path.join(out, "converged.ini")
    open(small_ref, "w").write(small_world(open(ref).read()))
    rc, _, stderr = compare(*graphs, "--variant", "v-1.b_2:ao.rays=1", "--reference", small_ref, "--ref-set", "converge.samples_per_frame=2",
                            "--size", "32x18", "--frames", "2", "--warmup", "0", out=out)
    if not check(rc == 0, "compare with odd graph names: exit %d\n%s" % (rc, stderr[-3000:])):
        return
    got = [c["name"] for c in json.load(open(os.path.join(out, "metrics.json")))["candidates"]]
    check(got == ["reference-1", 'a,"b', "v-1.b_2"], "candidate names: %s" % got)
    import csv
    rows = list(csv.reader(open(os.path.join(out, "metrics.csv"), newline="")))
    check(rows[0][0] == "candidate" and [r[0] for r in rows[1:]] == [n for n in got for _ in range(2)] and
          all(len(r) == 7 for r in rows), "metrics.csv: %s" % rows)
    frames = set(os.listdir(os.path.join(out, "frames")))
    check({"reference-00000.png", "reference-1-00000.png", 'a,"b-00000.png', "v-1.b_2-00001.png"} <= frames, "frames/: %s" % sorted(frames))


def small_world(text):
    """A graph's text with a world cheap to generate: radius 2 is all haze
    from the graphs' camera (the haze pass fades it out by its edge), so
    tonemap skips haze."""
    m = re.search(r"\[pass haze\][^\[]*?in\.color\s*=\s*(\S+)", text)
    text = text.replace("radius      = 13", "radius      = 2")
    return text.replace("in.color = hazed", "in.color = " + m.group(1)) if m else text


def small_graphs(out, edit=lambda text: text):
    """raw.ini, thesis.ini and reference.ini (as converged.ini) in out, small_world and edit applied."""
    os.makedirs(out, exist_ok=True)
    paths = [os.path.join(out, n) for n in ("raw.ini", "thesis.ini", "converged.ini")]
    for src, dst in zip(("raw.ini", "thesis.ini", "reference.ini"), paths):
        open(dst, "w").write(edit(small_world(open(os.path.join(GRAPHS, src)).read())))
    return paths


def variant_graph():
    out = os.path.join(OUT, "variant-graph")
    raw, thesis, ref = small_graphs(out)
    run = ["--reference", ref, "--ref-set", "converge.samples_per_frame=2", "--size", "32x18", "--frames", "2", "--warmup", "0"]
    # not listed, or listed twice: refused before any work, the candidates named
    for graphs, want, pattern in (([raw, thesis], "svgf", r"'svgf' is not a listed graph; the listed graphs are raw \(.*raw\.ini\), thesis \("),
                                  ([raw, raw], "raw.ini", r"'raw\.ini' is more than one listed graph.*raw \(.*\), raw-2 \(")):
        rc, _, stderr = compare(*graphs, "--variant", "v@%s:ao.rays=1" % want, *run, out=out)
        check(rc == 2, "variant of %s: exit %d, want 2" % (want, rc))
        check(re.search(pattern, stderr) is not None, "variant of %s: no /%s/ in:\n%s" % (want, pattern, stderr[-1000:]))
        check(not os.path.exists(os.path.join(out, "frames")), "variant of %s: frames written" % want)
    # the same overrides on each graph, the second named by its file name:
    # were it the first graph, its numbers would equal r1's
    rc, _, stderr = compare(raw, thesis, "--variant", "r1:tonemap.exposure=2", "--variant", "t1@thesis.ini:tonemap.exposure=2", *run, out=out)
    if not check(rc == 0, "variants of two graphs: exit %d\n%s" % (rc, stderr[-3000:])):
        return
    c = {x["name"]: x for x in json.load(open(os.path.join(out, "metrics.json")))["candidates"]}
    numbers = lambda name: [f[m] for f in c[name]["frames"] for m in ("psnr", "ssim", "flip")]
    check(c["t1"]["graph"] == thesis and c["t1"]["variant_of"] == "thesis" and c["r1"]["graph"] == raw and c["r1"]["variant_of"] == "raw" and
          c["thesis"]["variant_of"] is None, "metrics.json graphs: %s" % {n: (x["graph"], x["variant_of"]) for n, x in c.items()})
    check(numbers("t1") != numbers("r1"), "t1 (thesis, exposure 2) has r1's (raw, exposure 2) numbers: %s" % numbers("t1"))
    check(numbers("t1") != numbers("thesis"), "t1 (thesis, exposure 2) has thesis's numbers: %s" % numbers("t1"))
    check({"atrous", "reproject"} <= {p["name"] for p in c["t1"]["passes"]}, "t1's passes are not thesis's: %s" % c["t1"]["passes"])
    page = open(os.path.join(out, "report.html")).read()
    check(re.search(r'data-candidate="t1">.*?</td><td>[^<]*thesis\.ini \(variant of thesis\) with tonemap\.exposure=2</td>', page) is not None,
          "report.html: t1's row does not say it is a variant of thesis")


METRICS = ("psnr", "ssim", "flip", "temporal")
SMALL = ["--ref-set", "converge.samples_per_frame=2"]


def frame_numbers(candidate):
    return [f[m] for f in candidate["frames"] for m in METRICS]


def cases():
    """A case file of 2 cases x 2 candidates (and a variant identical to
    the baseline) gives the matrix that separate runs with the same
    settings give, number for number; the verdict counts the cases each
    candidate wins, loses and ties; metrics.csv has a row per case x
    candidate x frame; each case's frames have their own folder."""
    out = os.path.join(OUT, "cases")
    raw, thesis, ref = small_graphs(out)
    walk = os.path.join(GRAPHS, "paths", "walk.path")
    case_file = os.path.join(out, "two.cases")
    open(case_file, "w").write("; two small cases\n[case walk]\ncamera = %s\nstart = 10\nframes = 3\nwarmup = 1\nsize = 32x18\n\n"
                               "[case dusk]\nframes = 2\nwarmup = 0\nsize = 33x19\nscene.time_of_day = 17.5\n" % os.path.relpath(walk, out))
    # same:ao.rays=4 is raw itself (raw.ini has rays = 4): it ties with raw on every case
    check("rays        = 4" in open(raw).read(), "raw.ini's ao.rays is no longer 4: change the variant")
    rc, stdout, stderr = compare(raw, thesis, "--variant", "same:ao.rays=4", "--reference", ref, *SMALL, "--cases", case_file, out=out)
    if not check(rc == 0, "compare --cases: exit %d\n%s" % (rc, stderr[-3000:])):
        return
    # each graph is loaded once per case (and once before, to check it), its
    # warnings shown once: small_world leaves raw.ini's haze pass culled
    culled = [l for l in stderr.splitlines() if l.startswith(raw + ":") and "warning[VRG-W008]" in l]
    check(len(culled) == 1, "raw.ini's culled-pass warning shown %d times over 2 cases, want once:\n%s" % (len(culled), stderr[-3000:]))
    j = json.load(open(os.path.join(out, "metrics.json")))
    check([c["name"] for c in j["cases"]] == ["walk", "dusk"] and j["baseline"] == "raw", "cases, baseline: %s" % j.get("baseline"))
    # the same settings as separate runs: the walk from the options, the dusk from graphs whose time of day is 17.5
    sep = os.path.join(out, "separate")
    rc1, _, e1 = compare(raw, thesis, "--reference", ref, *SMALL, "--camera", walk, "--start", "10", "--frames", "3", "--warmup", "1",
                         "--size", "32x18", out=os.path.join(sep, "walk"))
    dusk = small_graphs(os.path.join(sep, "dusk-graphs"), lambda text: text.replace("time_of_day = 15", "time_of_day = 17.5"))
    rc2, _, e2 = compare(dusk[0], dusk[1], "--reference", dusk[2], *SMALL, "--frames", "2", "--warmup", "0", "--size", "33x19",
                         out=os.path.join(sep, "dusk"))
    if not check(rc1 == 0 and rc2 == 0, "separate runs: exit %d, %d\n%s%s" % (rc1, rc2, e1[-2000:], e2[-2000:])):
        return
    for k, name in enumerate(("walk", "dusk")):
        alone = {c["name"]: c for c in json.load(open(os.path.join(sep, name, "metrics.json")))["candidates"]}
        mine = {c["name"]: c for c in j["cases"][k]["candidates"]}
        for cand in ("raw", "thesis"):
            check(frame_numbers(mine[cand]) == frame_numbers(alone[cand]) and
                  [mine[cand]["summary"][m] for m in METRICS] == [alone[cand]["summary"][m] for m in METRICS],
                  "case %s, %s: %s, alone %s" % (name, cand, mine[cand]["summary"], alone[cand]["summary"]))
        check(frame_numbers(mine["same"]) == frame_numbers(mine["raw"]), "case %s: same (raw itself) has other numbers" % name)
    check(j["cases"][1]["scene"] == "scene.time_of_day=17.5" and j["cases"][1]["width"] == 33, "dusk's settings: %s" % j["cases"][1]["scene"])
    # the verdict: wins counted from the summaries; the identical variant ties everywhere
    verdict = {v["candidate"]: v for v in j["verdict"]}
    for m in METRICS:
        sign = 1 if m in ("psnr", "ssim") else -1
        diffs = [sign * (c["candidates"][1]["summary"][m] - c["candidates"][0]["summary"][m]) for c in j["cases"]]
        got = verdict["thesis"]
        check((got["wins"][m], got["losses"][m], got["ties"][m]) == (sum(d > 0 for d in diffs), sum(d < 0 for d in diffs), sum(d == 0 for d in diffs)),
              "thesis %s: wins/losses/ties %s %s %s, differences %s" % (m, got["wins"][m], got["losses"][m], got["ties"][m], diffs))
        check((verdict["same"]["wins"][m], verdict["same"]["losses"][m], verdict["same"]["ties"][m]) == (0, 0, 2), "same %s: %s" % (m, verdict["same"]))
    wins = verdict["thesis"]["wins"]
    want = "thesis: beats raw on %d of 2 cases in PSNR and %d in FLIP" % (wins["psnr"], wins["flip"])
    check(verdict["thesis"]["sentence"].startswith(want) and want in stdout, "sentence: %r, want %r" % (verdict["thesis"]["sentence"], want))
    check(verdict["same"]["sentence"].startswith("same: beats raw on 0 of 2 cases in PSNR and 0 in FLIP (worse on 0 and 0, equal on 2 and 2)"),
          "same's sentence: %r" % verdict["same"]["sentence"])
    rows = [l.split(",") for l in open(os.path.join(out, "metrics.csv")).read().split("\n") if l]
    check(rows[0][:2] == ["case", "candidate"] and len(rows) == 1 + 3 * 3 + 3 * 2, "metrics.csv: %d rows, header %s" % (len(rows), rows[0]))
    check(all(os.path.exists(os.path.join(out, "frames", c, "%s-%05d.png" % (n, k))) for c, f in (("walk", 3), ("dusk", 2))
              for n in ("reference", "raw", "thesis", "same") for k in range(f)), "frames/CASE/ misses PNGs")
    page_text = open(os.path.join(out, "report.html")).read()
    page = Page()
    page.feed(page_text)
    page.close()
    check(not page.errors and not page.stack, "report.html nesting: %s, unclosed %s" % (page.errors[:3], page.stack))
    cells = re.findall(r'data-cell="(\w+)" data-case="([^"]*)" data-candidate-name="([^"]*)" data-value="([^"]*)"', page_text)
    check(len(cells) == 3 * 2 * 3, "matrix cells: %d" % len(cells))
    # per case its last frame: reference + 3 candidates, 2 colour bars + 3 FLIP maps + 3 differences, 4 crops
    check(len(page.images) == 2 * 16 and re.findall(r"<h3>frame (\d+)</h3>", page_text) == ["2", "1"],
          "case frames shown: %d images, %s" % (len(page.images), re.findall(r"<h3>frame (\d+)</h3>", page_text)))
    by_case = {c["name"]: {x["name"]: x for x in c["candidates"]} for c in j["cases"]}
    check(all(float(v) == by_case[case][cand]["summary"][m] for m, case, cand, v in cells), "a matrix cell differs from metrics.json")
    check(all(v["sentence"].replace("&", "&amp;") in page_text for v in j["verdict"]), "report.html lacks a verdict sentence")
    # --baseline picks another candidate
    rc, _, stderr = compare(raw, thesis, "--reference", ref, *SMALL, "--cases", case_file, "--baseline", "thesis", out=out + "-b")
    if check(rc == 0, "--baseline thesis: exit %d\n%s" % (rc, stderr[-2000:])):
        jb = json.load(open(os.path.join(out + "-b", "metrics.json")))
        check(jb["baseline"] == "thesis" and jb["verdict"][0]["sentence"].startswith("raw: beats thesis on ") and
              jb["verdict"][1]["sentence"] == "thesis: the baseline", "--baseline thesis: %s" % jb["verdict"])
    rc, _, stderr = compare(raw, "--reference", ref, "--cases", case_file, "--baseline", "nobody", out=out + "-b")
    check(rc == 2 and "--baseline nobody: no candidate of that name; the candidates are raw" in stderr, "--baseline nobody: %d\n%s" % (rc, stderr))


def case_errors():
    """A bad case file: every mistake named by file:line, exit 1, before any
    work; the case options beside --cases are a usage error."""
    out = os.path.join(OUT, "case-errors")
    raw, thesis, ref = small_graphs(out)
    bad = os.path.join(out, "bad.cases")
    open(bad, "w").write("; comment\nframes = 3\n[case a]\nsize = 8x8\nframs = 3\nscene.time_of_day = 3\nscene.time_of_day = 4\n"
                         "[cas b]\n[case c d]\n[case e]\nwarmup = 9\nframes = 2\nstart = -1\njunk\ncamera =\n[case a]\n")
    rc, _, stderr = compare(raw, "--reference", ref, "--cases", bad, out=out)
    want = ["bad.cases:2: error: 'frames' is outside a [case NAME] section",
            "bad.cases:4: error: size = 8x8: compare needs at least 11x11 pixels",
            "bad.cases:5: error: unknown key 'frams' in [case a]",
            "bad.cases:7: error: 'scene.time_of_day' is given twice in [case a]",
            "bad.cases:8: error: unknown section '[cas b]'",
            "bad.cases:9: error: [case c d]: not a usable case name",
            "bad.cases:13: error: start = -1: not a frame number",
            "bad.cases:14: error: 'junk': expected KEY = VALUE",
            "bad.cases:15: error: 'camera' has no value",
            "bad.cases:10: error: [case e]: warmup must be below frames",
            "bad.cases:16: error: [case a] is given twice (first at line 3)"]
    check(rc == 1 and all(w in stderr for w in want), "bad case file: exit %d, missing %s in:\n%s" % (rc, [w for w in want if w not in stderr], stderr))
    check(not os.path.exists(os.path.join(out, "frames")), "a bad case file wrote frames")
    # a scene parameter the scene does not have: the case's line and the parameter
    open(bad, "w").write("[case a]\nsize = 32x18\n\n[case b]\nsize = 32x18\nscene.sunniness = 3\n")
    rc, _, stderr = compare(raw, "--reference", ref, "--cases", bad, out=out)
    check(rc == 1 and "'scene.sunniness=3': pass 'scene' has no parameter 'sunniness'" in stderr and
          "bad.cases:4: error: [case b]:" in stderr, "unknown scene parameter: exit %d\n%s" % (rc, stderr))
    for empty in ("", "; nothing\n"):
        open(bad, "w").write(empty)
        rc, _, stderr = compare(raw, "--reference", ref, "--cases", bad, out=out)
        check(rc == 1 and "bad.cases: error: no [case NAME] section" in stderr, "empty case file: exit %d\n%s" % (rc, stderr))
    rc, _, stderr = compare(raw, "--reference", ref, "--cases", os.path.join(out, "none.cases"), out=out)
    check(rc == 1 and "none.cases: error: cannot read the case file" in stderr, "missing case file: exit %d\n%s" % (rc, stderr))
    rc, _, stderr = compare(raw, "--reference", ref, "--cases", bad, "--size", "32x18", out=out)
    check(rc == 2 and "--cases with --size: --camera, --start, --frames, --warmup and --size are the case file's keys" in stderr, "--cases with --size: exit %d\n%s" % (rc, stderr))


def shipped_cases():
    """The shipped case files load and pass every check (graphs, scene
    overrides, sizes, paths) with the graphs they are for: the run stops
    only at the device, which comes after every check."""
    out = os.path.join(OUT, "shipped")
    for graphs, ref, cases_file in ((["raw.ini", "thesis.ini"], "reference.ini", "terrain.cases"),
                                    (["vox-knight.ini"], "reference-vox.ini", "vox.cases")):
        path = os.path.join(GRAPHS, "cases", cases_file)
        names = re.findall(r"^\[case (\S+)\]", open(path).read(), re.M)
        rc, _, stderr = compare(*[os.path.join(GRAPHS, g) for g in graphs], "--reference", os.path.join(GRAPHS, ref), "--cases", path,
                                "--device", "no-such-device", out=out)
        check(rc == 1 and re.match(r"error: device 'no-such-device'[^\n]*matches no device", stderr), "%s: exit %d\n%s" % (cases_file, rc, stderr[-3000:]))
        check(len(names) == len(set(names)), "%s: case names repeat" % cases_file)
    terrain = open(os.path.join(GRAPHS, "cases", "terrain.cases")).read()
    check(len(re.findall(r"^\[case ", terrain, re.M)) >= 12, "terrain.cases has fewer than 12 cases")


def grid():
    """--grid: the product of one graph's lists, named deterministically,
    of the first graph or of @GRAPH; more than 16 candidates run."""
    out = os.path.join(OUT, "grid")
    raw, thesis, ref = small_graphs(out)
    run = ["--reference", ref, *SMALL, "--size", "32x18", "--frames", "2", "--warmup", "0"]
    rc, _, stderr = compare(raw, thesis, "--grid", "ao.rays=1,2", "--grid", "tonemap.exposure=0.5,2", "--grid", "@thesis:atrous.iterations=1",
                            *run, out=out)
    if check(rc == 0, "grid: exit %d\n%s" % (rc, stderr[-3000:])):
        c = json.load(open(os.path.join(out, "metrics.json")))["candidates"]
        got = [(x["name"], x["overrides"], x["variant_of"]) for x in c]
        check(got == [("raw", "", None), ("thesis", "", None),
                      ("raw-rays1-exposure0.5", "ao.rays=1,tonemap.exposure=0.5", "raw"), ("raw-rays1-exposure2", "ao.rays=1,tonemap.exposure=2", "raw"),
                      ("raw-rays2-exposure0.5", "ao.rays=2,tonemap.exposure=0.5", "raw"), ("raw-rays2-exposure2", "ao.rays=2,tonemap.exposure=2", "raw"),
                      ("thesis-iterations1", "atrous.iterations=1", "thesis")], "grid candidates: %s" % got)
    values = ",".join("%.1f" % (0.5 + 0.1 * i) for i in range(17))
    rc, stdout, stderr = compare(raw, "--grid", "tonemap.exposure=" + values, *run, out=out + "-17")
    if check(rc == 0, "a grid of 17: exit %d\n%s" % (rc, stderr[-3000:])):
        c = json.load(open(os.path.join(out + "-17", "metrics.json")))["candidates"]
        check(len(c) == 18 and c[-1]["name"] == "raw-exposure2.1" and len(c[-1]["frames"]) == 2, "a grid of 17: %d candidates" % len(c))
        check(len(set(tuple(frame_numbers(x)) for x in c[1:])) == 17, "the grid's 17 exposures do not all differ")
    for bad, why in (("ao.rays", "expected [@GRAPH:]PASS.PARAM=VALUE"), ("@:ao.rays=1", "expected"), ("rays=1", "expected")):
        rc, _, stderr = compare(raw, "--grid", bad, *run, out=out + "-bad")
        check(rc == 2 and why in stderr, "--grid %s: exit %d\n%s" % (bad, rc, stderr[-1000:]))
    rc, _, stderr = compare(raw, "--grid", "tonemap.exposure=1,x y", *run, out=out + "-bad")
    check(rc == 1 and "tonemap.exposure=x y" in stderr, "--grid with a bad value: exit %d\n%s" % (rc, stderr[-1000:]))


def moving_sun():
    """A moving sun: the reference (whose clock runs samples_per_frame
    times as fast) shows the sun where the candidates see it. Frame 6 of a
    day of 2.4 s from 15:00 is 16:00: the same frames as a still sun at
    16:00."""
    out = os.path.join(OUT, "moving-sun")
    raw, thesis, ref = small_graphs(out)
    case_file = os.path.join(out, "sun.cases")
    open(case_file, "w").write("[case moving]\nstart = 6\nframes = 1\nwarmup = 0\nsize = 32x18\nscene.day_length = 2.4\n\n"
                               "[case still]\nstart = 6\nframes = 1\nwarmup = 0\nsize = 32x18\nscene.time_of_day = 16\n")
    rc, _, stderr = compare(raw, "--reference", ref, *SMALL, "--cases", case_file, out=out)
    if not check(rc == 0, "moving sun: exit %d\n%s" % (rc, stderr[-3000:])):
        return
    frame = lambda case, name: open(os.path.join(out, "frames", case, name + "-00000.png"), "rb").read()
    check(frame("moving", "raw") == frame("still", "raw"), "the candidate's sun at frame 6 is not 16:00")
    check(frame("moving", "reference") == frame("still", "reference"), "the reference's sun at frame 6 is not the candidates'")


def score_device():
    args = [os.path.join(GRAPHS, "raw.ini"), os.path.join(GRAPHS, "thesis.ini"), "--reference", os.path.join(GRAPHS, "reference.ini"),
            "--ref-set", "converge.samples_per_frame=4", "--camera", os.path.join(GRAPHS, "paths", "walk.path"),
            "--size", "96x54", "--frames", "6", "--warmup", "2"]
    runs = {}
    for mode in ("cpu", "device"):
        out = os.path.join(OUT, "score-" + mode)
        rc, _, stderr = compare(*args, "--score", mode, out=out)
        if not check(rc == 0, "--score %s: exit %d\n%s" % (mode, rc, stderr[-3000:])):
            return
        runs[mode] = {x["name"]: x for x in json.load(open(os.path.join(out, "metrics.json")))["candidates"]}
    tolerance = {"psnr": 1e-5, "ssim": 2e-5, "flip": 1e-5, "temporal": 1e-7}
    for name, cand in runs["cpu"].items():
        for k, (a, b) in enumerate(zip(cand["frames"], runs["device"][name]["frames"])):
            for m, tol in tolerance.items():
                check((a[m] is None and b[m] is None) or abs(a[m] - b[m]) <= tol, "%s frame %d %s: cpu %s, device %s" % (name, k, m, a[m], b[m]))
    # shown: the first frame after warm-up, the middle, the last
    frames = set(os.listdir(os.path.join(OUT, "score-device", "frames")))
    want = {"%s-%05d.png" % (n, k) for n in ("raw", "thesis") for k in (2, 3, 5)} | {"reference-%05d.png" % k for k in range(6)}
    check(frames == want, "--score device wrote frames %s, want %s" % (sorted(frames), sorted(want)))
    rc, _, stderr = compare(*args, "--score", "gpu", out=os.path.join(OUT, "score-gpu"))
    check(rc == 2 and "--score 'gpu': expected cpu or device" in stderr, "--score gpu: exit %d\n%s" % (rc, stderr[-1000:]))
    # cases of two sizes: a scorer for each
    out = os.path.join(OUT, "score-cases")
    raw, thesis, ref = small_graphs(out)
    case_file = os.path.join(out, "two.cases")
    open(case_file, "w").write("[case a]\nframes = 3\nwarmup = 1\nsize = 32x18\n\n[case b]\nframes = 2\nwarmup = 0\nsize = 33x19\n")
    cases = {}
    for mode in ("cpu", "device"):
        rc, _, stderr = compare(raw, thesis, "--reference", ref, *SMALL, "--cases", case_file, "--score", mode, out=os.path.join(out, mode))
        if not check(rc == 0, "--cases --score %s: exit %d\n%s" % (mode, rc, stderr[-3000:])):
            return
        cases[mode] = json.load(open(os.path.join(out, mode, "metrics.json")))["cases"]
    for a_case, b_case in zip(cases["cpu"], cases["device"]):
        for a_cand, b_cand in zip(a_case["candidates"], b_case["candidates"]):
            for k, (a, b) in enumerate(zip(a_cand["frames"], b_cand["frames"])):
                for m, tol in tolerance.items():
                    check((a[m] is None and b[m] is None) or abs(a[m] - b[m]) <= tol,
                          "case %s, %s frame %d %s: cpu %s, device %s" % (a_case["name"], a_cand["name"], k, m, a[m], b[m]))


def vox_bytes(size, voxels):
    """A MagicaVoxel file: SIZE and XYZI chunks under MAIN, the default palette."""
    import struct
    def chunk(tag, content, children=b""):
        return tag + struct.pack("<ii", len(content), len(children)) + content + children
    xyzi = struct.pack("<i", len(voxels)) + b"".join(struct.pack("<4B", *v) for v in voxels)
    return b"VOX " + struct.pack("<i", 150) + chunk(b"MAIN", b"", chunk(b"SIZE", struct.pack("<3i", *size)) + chunk(b"XYZI", xyzi))


def vox_world(out, name, voxels):
    """A vox scene graph (tests/graphs/vox_knight.ini) whose model is
    model.vox beside it, holding voxels of a 4x4x4 model."""
    os.makedirs(out, exist_ok=True)
    graph = os.path.join(out, name)
    open(graph, "w").write(open(os.path.join(SRC, "tests", "graphs", "vox_knight.ini")).read().replace("chr_knight.vox", "model.vox"))
    open(os.path.join(out, "model.vox"), "wb").write(vox_bytes((4, 4, 4), voxels))
    return graph


TOWER = [(1, 1, z, 10) for z in range(4)]
SLAB = [(x, y, 0, 80) for x in range(4) for y in range(4)]
TINY = ["--size", "32x18", "--frames", "2", "--warmup", "0"]


def summary_psnr(out):
    return [x["summary"]["psnr"] for x in json.load(open(os.path.join(out, "metrics.json")))["candidates"]]


def cache_vox():
    """The cache key covers a vox scene's model by content: another model
    under the same name renders the reference again, and the candidate (the
    same graph) then equals it."""
    out = os.path.join(OUT, "cache-vox")
    graph = vox_world(out, "knight.ini", TOWER)
    cache = os.path.join(out, "cache")
    run = lambda: subprocess.run([VOXRG, "compare", graph, "--reference", graph, *TINY, "--out", os.path.join(out, "out"), "--cache", cache,
                                  "--validate"], capture_output=True, text=True)
    for want in (0, 2):
        p = run()
        if not check(p.returncode == 0, "vox compare: exit %d\n%s" % (p.returncode, p.stderr[-2000:])):
            return
        got = json.load(open(os.path.join(out, "out", "metrics.json")))["reference"]["frames_from_cache"]
        check(got == want, "vox compare: %d frames from the cache, want %d" % (got, want))
    open(os.path.join(out, "model.vox"), "wb").write(vox_bytes((4, 4, 4), SLAB))
    p = run()
    if check(p.returncode == 0, "vox compare, another model: exit %d\n%s" % (p.returncode, p.stderr[-2000:])):
        j = json.load(open(os.path.join(out, "out", "metrics.json")))
        check(j["reference"]["frames_from_cache"] == 0, "another model: %d frames taken from the cache" % j["reference"]["frames_from_cache"])
        check(summary_psnr(os.path.join(out, "out")) == [100], "another model: PSNR %s against the reference, want 100 (the same graph)" %
              summary_psnr(os.path.join(out, "out")))


def world_files():
    """Candidates and the reference whose scenes read different data files
    render different worlds: an error before any work, naming the files.
    An edit journal beside the reference graph only; a model of another
    content under the same name in another folder."""
    out = os.path.join(OUT, "world-files")
    os.makedirs(out, exist_ok=True)
    small = lambda text: text.replace("radius      = 13", "radius      = 2")
    cand, ref = os.path.join(out, "cand.ini"), os.path.join(out, "ref.ini")
    open(cand, "w").write(small(open(os.path.join(GRAPHS, "raw.ini")).read()))
    open(ref, "w").write(small(open(os.path.join(GRAPHS, "reference.ini")).read()))
    open(ref + ".edits", "wb").write(b"an edit journal of the reference's world only\n")
    a = vox_world(os.path.join(out, "a"), "knight.ini", TOWER)
    b = vox_world(os.path.join(out, "b"), "knight.ini", SLAB)
    cases = [
        ("a journal beside the reference", [cand, "--reference", ref],
         r"scenes differ: .*cand\.ini:\d+ reads .*cand\.ini\.edits \(absent\), .*ref\.ini:\d+ reads .*ref\.ini\.edits \(\d+ bytes\)"
         r".*the reference must render the candidates' frames"),
        ("another model of the same name", [a, b, "--reference", a],
         r"scenes differ: .*a/knight\.ini:\d+ reads .*a/model\.vox \(\d+ bytes\), .*b/knight\.ini:\d+ reads .*b/model\.vox \(\d+ bytes"
         r"(, other content)?\).*candidates must render the same frames"),
    ]
    for what, args, pattern in cases:
        rc, _, stderr = compare(*args, *TINY, out=os.path.join(out, "out"))
        check(rc == 1, "%s: exit %d, want 1" % (what, rc))
        check(re.search(pattern, stderr) is not None, "%s: no /%s/ in:\n%s" % (what, pattern, stderr[-2000:]))
        check(not os.path.exists(os.path.join(out, "out", "frames")), "%s: frames written" % what)
    # the same journal beside both: the same world
    shutil.copy(ref + ".edits", cand + ".edits")
    rc, _, stderr = compare(cand, "--reference", ref, "--ref-set", "converge.samples_per_frame=1", *TINY, out=os.path.join(out, "out"))
    check("scenes differ" not in stderr, "the same journal beside both: %s" % stderr[-2000:])


def cache_entries(cache):
    """The cache's entries (not side files), oldest first."""
    names = [n for n in os.listdir(cache) if not n.endswith(".deps") and not n.startswith(".")]
    return sorted((os.path.join(cache, n) for n in names), key=os.path.getmtime)


def cache_damage():
    """A cached frame replaced by another valid one (frame 1's over frame
    0's), one whose pixels changed, one cut short: each named in a warning
    and rendered again, never used (the candidate, the reference's own
    graph, keeps PSNR 100 on every frame)."""
    out = os.path.join(OUT, "cache-damage")
    os.makedirs(out, exist_ok=True)
    graph = os.path.join(out, "wall.ini")
    shutil.copy(os.path.join(SRC, "tests", "graphs", "blocks_wall.ini"), graph)
    path = os.path.join(out, "turn.path")
    open(path, "w").write("0.0  0 2 12  0 0\n0.1  6 4 8  40 -20\n")
    cache = os.path.join(out, "cache")
    def run(frames):
        p = subprocess.run([VOXRG, "compare", graph, "--reference", graph, "--camera", path, "--size", "32x18", "--frames", str(frames),
                            "--warmup", "0", "--out", os.path.join(out, "out"), "--cache", cache, "--validate"], capture_output=True, text=True)
        check(p.returncode == 0, "compare: exit %d\n%s" % (p.returncode, p.stderr[-2000:]))
        j = json.load(open(os.path.join(out, "out", "metrics.json"))) if p.returncode == 0 else None
        return p.stderr, j
    run(1)
    first = cache_entries(cache)
    run(2)
    second = [e for e in cache_entries(cache) if e not in first]
    if not check(len(first) == 1 and len(second) == 1, "cache entries: %s then %s" % (first, second)):
        return
    frame0, frame1 = first[0], second[0]
    check(open(frame0, "rb").read() != open(frame1, "rb").read(), "frames 0 and 1 are alike: the test shows nothing")

    def damaged(what, damage, reason):
        damage()
        stderr, j = run(2)
        if not j:
            return
        frames = [f["psnr"] for f in j["candidates"][0]["frames"]]
        check(frames == [100, 100], "%s: used (PSNR per frame %s, want 100 100)" % (what, frames))
        check(j["reference"]["frames_from_cache"] == 1, "%s: %d frames from the cache, want 1" % (what, j["reference"]["frames_from_cache"]))
        pattern = r"warning: the reference cache's .*%s %s.*rendering the frame again" % (re.escape(os.path.basename(frame0)), reason)
        check(re.search(pattern, stderr) is not None, "%s: no /%s/ in:\n%s" % (what, pattern, stderr[-2000:]))
        stderr, j = run(2)  # written again, whole
        check(j and j["reference"]["frames_from_cache"] == 2 and "warning" not in stderr, "%s: not cached again: %s" % (what, stderr[-1000:]))

    damaged("frame 1's entry copied over frame 0's", lambda: shutil.copy(frame1, frame0), "holds another frame")
    def flip_pixel():
        data = bytearray(open(frame0, "rb").read())
        data[-40] ^= 0x55
        open(frame0, "wb").write(bytes(data))
    damaged("a changed pixel", flip_pixel, "has pixels that do not match their checksum")
    damaged("an entry cut short", lambda: os.truncate(frame0, os.path.getsize(frame0) - 100), "is truncated")


def cache_shared():
    """Several compare processes filling one cache folder at once all
    succeed; the entries they leave are whole (a run after them takes every
    frame from the cache, without a warning) and no temporary file is left."""
    out = os.path.join(OUT, "cache-shared")
    os.makedirs(out, exist_ok=True)
    graph = os.path.join(out, "wall.ini")
    shutil.copy(os.path.join(SRC, "tests", "graphs", "blocks_wall.ini"), graph)
    cache = os.path.join(out, "cache")
    args = lambda i: [VOXRG, "compare", graph, "--reference", graph, "--camera", os.path.join(GRAPHS, "paths", "walk.path"), "--size", "32x18",
                      "--frames", "6", "--warmup", "0", "--out", os.path.join(out, "out%d" % i), "--cache", cache]
    procs = [subprocess.Popen(args(i), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for i in range(4)]
    for i, p in enumerate(procs):
        stdout, stderr = p.communicate()
        check(p.returncode == 0, "writer %d: exit %d\n%s" % (i, p.returncode, stderr[-2000:]))
        check("warning" not in stderr, "writer %d warned:\n%s" % (i, stderr[-2000:]))
    p = subprocess.run(args(9), capture_output=True, text=True)
    if check(p.returncode == 0, "the reader: exit %d\n%s" % (p.returncode, p.stderr[-2000:])):
        j = json.load(open(os.path.join(out, "out9", "metrics.json")))
        check(j["reference"]["frames_from_cache"] == 6 and "warning" not in p.stderr,
              "after the writers: %d of 6 frames from the cache\n%s" % (j["reference"]["frames_from_cache"], p.stderr[-2000:]))
    check(not [n for n in os.listdir(cache) if n.startswith(".")], "temporary files left: %s" % os.listdir(cache))


def without_timing(metrics):
    """metrics.json less what differs between runs of the same work: GPU
    times, and how many reference frames came from the cache."""
    for case in metrics.get("cases", [metrics]):
        case["reference"].pop("frames_from_cache")
        for c in case["candidates"]:
            c["summary"].pop("gpu_ms_mean"), c["summary"].pop("gpu_ms_p95")
            c["passes"] = [p["name"] for p in c["passes"]]
    return metrics


def merge(out, *dirs):
    p = subprocess.run([VOXRG, "compare", "--merge", out, *dirs], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def shards():
    """Three shards of a 2 cases x 2 candidates run, each its own process,
    merged: the merge's metrics equal one process's, but for timings."""
    out = os.path.join(OUT, "shards")
    raw, thesis, ref = small_graphs(out)
    case_file = os.path.join(out, "two.cases")
    open(case_file, "w").write("[case walk]\ncamera = %s\nstart = 10\nframes = 3\nwarmup = 1\nsize = 32x18\n\n"
                               "[case dusk]\nframes = 2\nwarmup = 0\nsize = 33x19\nscene.time_of_day = 17.5\n" %
                               os.path.join(GRAPHS, "paths", "walk.path"))
    run = [raw, thesis, "--reference", ref, *SMALL, "--cases", case_file]
    single = os.path.join(out, "single")
    rc, _, stderr = compare(*run, out=single)
    if not check(rc == 0, "one process: exit %d\n%s" % (rc, stderr[-2000:])):
        return
    dirs = [os.path.join(out, "shard%d" % i) for i in range(3)]
    env = dict(os.environ, SLURM_ARRAY_TASK_ID="1")
    procs = [subprocess.Popen([VOXRG, "compare", *run, "--shard", "auto/3" if i == 1 else "%d/3" % i, "--out", d, "--cache", CACHE, "--validate"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env) for i, d in enumerate(dirs)]
    ok = True
    for i, p in enumerate(procs):
        _, stderr = p.communicate()
        ok &= check(p.returncode == 0, "shard %d: exit %d\n%s" % (i, p.returncode, stderr[-2000:]))
    if not ok:
        return
    check(open(os.path.join(dirs[1], "shard.txt")).read().split("\n")[1] == "shard 1 3", "auto/3 with SLURM_ARRAY_TASK_ID=1 is not shard 1")
    check(not os.path.exists(os.path.join(dirs[0], "metrics.json")), "a shard wrote metrics.json")
    merged = os.path.join(out, "merged")
    rc, stdout, stderr = merge(merged, *dirs)
    if not check(rc == 0, "--merge: exit %d\n%s" % (rc, stderr[-2000:])):
        return
    files = lambda d, name: open(os.path.join(d, name)).read()
    check(files(merged, "metrics.csv") == files(single, "metrics.csv"), "merged metrics.csv differs from one process's")
    mine, alone = (without_timing(json.loads(files(d, "metrics.json"))) for d in (merged, single))
    check(mine == alone, "merged metrics.json differs from one process's:\n%s\n%s" % (json.dumps(mine)[:1500], json.dumps(alone)[:1500]))
    check(all(v["sentence"].replace("&", "&amp;") in files(merged, "report.html") for v in mine["verdict"]), "merged report.html lacks a verdict")
    check(sorted(os.listdir(os.path.join(merged, "frames", "walk"))) == sorted(n for n in os.listdir(os.path.join(single, "frames", "walk"))),
          "merged frames/walk/: %s" % os.listdir(os.path.join(merged, "frames", "walk")))
    # errors: each exit 1 (2 for usage) with the cause named, no report left
    foreign = os.path.join(out, "foreign")
    rc, _, stderr = compare(*run, "--baseline", "thesis", "--shard", "1/3", out=foreign)
    check(rc == 0, "the foreign shard: exit %d\n%s" % (rc, stderr[-2000:]))
    cut = os.path.join(out, "cut")
    shutil.copytree(dirs[2], cut, dirs_exist_ok=True)
    text = files(cut, "shard.txt")
    open(os.path.join(cut, "shard.txt"), "w").write(text[:text.rindex("end")])
    for what, args, want_rc, pattern in (
            ("a missing shard", [dirs[0], dirs[2]], 1, r"shard 1 of 3 is missing"),
            ("a shard twice", [*dirs, dirs[1]], 1, r"shard1/shard\.txt and .*shard1/shard\.txt are both shard 1 of 3"),
            ("a shard of another run", [dirs[0], foreign, dirs[2]], 1, r"foreign/shard\.txt:\d+: a shard of another run"),
            ("a shard cut short", [dirs[0], dirs[1], cut], 1, r"cut/shard\.txt:\d+: error: the file ends before its 'end' line"),
            ("not a shard", [dirs[0], dirs[1], single], 1, r"single/shard\.txt: No such file"),
            ("--shard with --merge", [*dirs, "--shard", "0/3"], 2, r"--shard with --merge")):
        rc, _, stderr = merge(merged, *args)
        check(rc == want_rc and re.search(pattern, stderr), "%s: exit %d (want %d), no /%s/ in:\n%s" % (what, rc, want_rc, pattern, stderr[-1500:]))
        check(not os.path.exists(os.path.join(merged, "metrics.json")), "%s: a report left behind" % what)
    rc, _, stderr = compare(*run, "--shard", "3/3", out=os.path.join(out, "bad"))
    check(rc == 2 and "--shard 3/3: the index '3' is not a whole number from 0 to 2" in stderr, "--shard 3/3: exit %d\n%s" % (rc, stderr[-1000:]))
    # scored on the device: the same equality, of the candidates only the shown frames; a shard scored on the CPU is of another run
    device = [*run, "--score", "device"]
    rc, _, stderr = compare(*device, out=os.path.join(out, "device"))
    check(rc == 0, "--score device in one process: exit %d\n%s" % (rc, stderr[-2000:]))
    for i in range(3):
        rc, _, stderr = compare(*device, "--shard", "%d/3" % i, out=os.path.join(out, "device%d" % i))
        check(rc == 0, "--score device, shard %d/3: exit %d\n%s" % (i, rc, stderr[-2000:]))
    rc, _, stderr = merge(os.path.join(out, "device-merged"), *(os.path.join(out, "device%d" % i) for i in range(3)))
    if check(rc == 0, "--score device, --merge: exit %d\n%s" % (rc, stderr[-2000:])):
        check(files(os.path.join(out, "device-merged"), "metrics.csv") == files(os.path.join(out, "device"), "metrics.csv"),
              "--score device: merged metrics.csv differs from one process's")
        check(sorted(os.listdir(os.path.join(out, "device-merged", "frames", "walk"))) == sorted(os.listdir(os.path.join(out, "device", "frames", "walk"))),
              "--score device: merged frames/walk/: %s" % os.listdir(os.path.join(out, "device-merged", "frames", "walk")))
    rc, _, stderr = merge(os.path.join(out, "device-merged"), *dirs[:2], os.path.join(out, "device2"))
    check(rc == 1 and "a shard of another run" in stderr, "a shard scored on the device with shards scored on the CPU: exit %d\n%s" % (rc, stderr[-1000:]))


# one line: tests/cli/CMakeLists.txt reads the names from it
CASES = (errors, names, variant_graph, identical, e2e, cases, case_errors, shipped_cases, grid, moving_sun, cache_vox, world_files, cache_damage, cache_shared, score_device, shards)


def main():
    cases = [c for c in CASES if ONLY in (None, c.__name__)]
    if not cases:
        print("usage: test_compare.py VOXRG SOURCE_DIR OUT_DIR [CASE]: no case %r (cases: %s)" %
              (ONLY, " ".join(c.__name__ for c in CASES)), file=sys.stderr)
        return 2
    shutil.rmtree(OUT, ignore_errors=True)
    os.makedirs(OUT)
    for case in cases:
        case()
        print("%s: done" % case.__name__, flush=True)
    print("compare: %s" % ("FAILED (%d)" % len(failures) if failures else "ok"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
