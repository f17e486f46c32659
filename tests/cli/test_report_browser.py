#!/usr/bin/env python3
"""Opens voxrg compare's report.html in headless Chromium and checks the
screenshot: the page renders, with its plots (the candidates' line colours),
the summary's best-value marks and the frame images (many colours).
Exit 77 (skipped) when Chromium is not installed (scripts/setup.sh installs it).
Usage: test_report_browser.py REPORT.html OUT_DIR"""
import os
import shutil
import subprocess
import sys

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from png_pixels import load  # noqa: E402

report, out = os.path.abspath(sys.argv[1]), sys.argv[2]
browser = shutil.which("chromium") or shutil.which("chromium-browser")
if not browser:
    print("skip: chromium is not installed (scripts/setup.sh installs it)")
    sys.exit(77)
os.makedirs(out, exist_ok=True)
shot = os.path.join(out, "report.png")
if os.path.exists(shot):
    os.remove(shot)
profile = os.path.join(out, "profile")  # not $HOME: CI's may be read-only
p = subprocess.run([browser, "--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars", "--user-data-dir=" + profile,
                    "--window-size=1400,3200", "--screenshot=" + shot, "file://" + report], capture_output=True, text=True, timeout=300)
if p.returncode != 0 or not os.path.exists(shot):
    print("FAIL: chromium exit %d, no screenshot\n%s" % (p.returncode, p.stderr[-2000:]))
    sys.exit(1)
w, h, px = load(shot)
count = {}
for y in range(0, h, 2):
    for x in range(0, w, 2):
        c = px(x, y)
        count[c] = count.get(c, 0) + 1
want = {"plot line, first candidate": (31, 119, 180), "plot line, second candidate": (255, 127, 14), "best-value mark": (230, 244, 230),
        "warm-up band": (240, 240, 240)}
fails = [name for name, c in want.items() if count.get(c, 0) < 20]
if len(count) < 2000:
    fails.append("frame images (only %d colours)" % len(count))
for f in fails:
    print("FAIL: the screenshot shows no", f)
print("report in chromium: %s (%d colours)" % ("FAILED" if fails else "ok", len(count)))
sys.exit(1 if fails else 0)
