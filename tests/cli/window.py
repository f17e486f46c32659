"""`voxrg run` driven like a user: an X server of its own (Xvfb), keys and
the mouse through xdotool, what the window says read from its stderr, and
screenshots (P) from its --out folder. Shared by the window tests."""
import os
import re
import shutil
import subprocess
import sys
import time

from png_pixels import load


def available():
    """None, or why the window tests cannot run here."""
    if not shutil.which("Xvfb") or not shutil.which("xdotool"):
        return "Xvfb or xdotool not installed (scripts/setup.sh installs them)"
    return None


class Xvfb:
    """An X server on a free display, set as $DISPLAY while in use."""

    def __init__(self, folder):
        display_file = os.path.join(folder, "xvfb.display")
        with open(display_file, "w") as f:
            self.proc = subprocess.Popen(["Xvfb", "-displayfd", str(f.fileno()), "-screen", "0", "640x480x24", "-nolisten", "tcp"],
                                         pass_fds=(f.fileno(),), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        for _ in range(100):
            if open(display_file).read().strip():
                break
            time.sleep(0.1)
        os.environ["DISPLAY"] = ":" + open(display_file).read().split()[0]

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.proc.kill()
        self.proc.wait()


def run_cases(out, cases):
    """Each case(folder) in out/CASE under one X server: the test's exit
    status (77: skipped, saying why)."""
    if available():
        print("skip: " + available())
        return 77
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    with Xvfb(out):
        for case in cases:
            d = os.path.join(out, case.__name__)
            os.makedirs(d)
            case(d)
    print("ok")
    return 0


def xdo(*args):
    subprocess.run(["xdotool", *args], check=True, timeout=60)


class Window:
    """voxrg run GRAPH in cwd, its stderr in cwd/run.stderr (each window of
    a folder appends), shown once frames are presented, focused."""

    def __init__(self, voxrg, graph, cwd, args=("--window", "160x100", "--scale", "1"), out="out"):
        self.cwd, self.out, self.log = cwd, out, os.path.join(cwd, "run.stderr")
        self.start = os.path.getsize(self.log) if os.path.exists(self.log) else 0
        self.err = open(self.log, "a")
        self.proc = subprocess.Popen([voxrg, "run", graph, "--validate", *args], cwd=cwd, stdout=subprocess.DEVNULL, stderr=self.err)
        self.wid = subprocess.run(["xdotool", "search", "--sync", "--name", "^voxrg"], capture_output=True, text=True,
                                  timeout=120).stdout.split()[0]
        self.wait(lambda: "fps" in subprocess.run(["xdotool", "getwindowname", self.wid], capture_output=True, text=True).stdout,
                  "frames shown")
        xdo("windowfocus", "--sync", self.wid)
        shots = os.path.join(cwd, out)
        self.shots = len([f for f in os.listdir(shots) if f.startswith("screenshot-")]) if os.path.isdir(shots) else 0

    def said(self):
        """What this window wrote to stderr so far."""
        with open(self.log) as f:
            f.seek(self.start)
            return f.read()

    def wait(self, cond, what, seconds=60):
        end = time.time() + seconds
        while time.time() < end:
            if cond():
                return
            if self.proc.poll() is not None:
                break
            time.sleep(0.1)
        sys.exit(f"FAIL: waiting for {what}; voxrg said:\n" + self.said()[-3000:])

    def stderr_has(self, pattern, count=1):
        self.wait(lambda: len(re.findall(pattern, self.said())) >= count, f"'{pattern}' x{count}")
        return re.findall(pattern, self.said())[count - 1]

    def screenshot(self):
        """P: the next screenshot, numbered after those the folder holds."""
        name = f"{self.out}/screenshot-{self.shots:03d}.png"
        self.shots += 1
        xdo("key", "p")
        self.stderr_has("wrote " + re.escape(name))
        return load(os.path.join(self.cwd, name))

    def settled(self):
        """A screenshot equal to the one before: streaming has loaded what the camera sees."""
        last = self.screenshot()
        for _ in range(30):
            shot = self.screenshot()
            if pixels(shot) == pixels(last):
                return shot
            last = shot
        sys.exit("FAIL: the picture never settled")

    def close(self):
        xdo("key", "Escape")
        rc = self.proc.wait(timeout=120)
        self.err.close()
        if rc != 0:
            sys.exit(f"FAIL: voxrg run exited {rc}:\n" + self.said()[-3000:])


def pixels(shot):
    w, h, px = shot
    return [px(x, y) for y in range(h) for x in range(w)]


def changed(a, b):
    return sum(1 for p, q in zip(pixels(a), pixels(b)) if max(abs(i - j) for i, j in zip(p, q)) > 8)
