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
- variants of a named graph (NAME@GRAPH:...): a variant of the second graph
  renders that graph, not the first; the report says which; a GRAPH not
  listed, or listed twice, is a usage error (exit 2) naming the candidates.
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
    # per shown frame: reference + 2 candidates, the ramp + 2 maps, 3 crops
    check(len(pngs) == len(page.images) == 3 * 9, "report images: %d inline of %d" % (len(pngs), len(page.images)))
    check(all(base64.b64decode(s.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n" for s in pngs), "an inline image is not a PNG")
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


def variant_graph():
    out = os.path.join(OUT, "variant-graph")
    os.makedirs(out, exist_ok=True)
    # cheap to generate; a world of radius 2 is all haze from the graphs'
    # camera (the haze pass fades it out by its edge): tonemap skips haze
    def small_world(text):
        m = re.search(r"\[pass haze\][^\[]*?in\.color\s*=\s*(\S+)", text)
        text = text.replace("radius      = 13", "radius      = 2")
        return text.replace("in.color = hazed", "in.color = " + m.group(1)) if m else text
    raw, thesis, ref = (os.path.join(out, n) for n in ("raw.ini", "thesis.ini", "converged.ini"))
    for src, dst in (("raw.ini", raw), ("thesis.ini", thesis), ("reference.ini", ref)):
        open(dst, "w").write(small_world(open(os.path.join(GRAPHS, src)).read()))
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


# one line: tests/cli/CMakeLists.txt reads the names from it
CASES = (errors, names, variant_graph, identical, e2e)


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
