#!/usr/bin/env python3
"""Each layer's ABI is its public headers, no more and no less: every
symbol a library exports is a function or variable the headers in its
include folder declare, and every function they declare (but static inline
ones and the plugin's own entry point) is exported by it.
Usage: check_exports.py LIB.so INCLUDE_DIR [LIB.so INCLUDE_DIR]..."""
import glob
import os
import re
import subprocess
import sys

def check(lib, include):
    nm = subprocess.run(["nm", "-D", "--defined-only", lib], capture_output=True, text=True, check=True).stdout
    exported = {line.split()[-1] for line in nm.splitlines() if len(line.split()) == 3}
    # the linker's bounds of sections named like C identifiers (the fuzzer
    # build's coverage counters) are not ours
    exported = {name for name in exported if not re.match(r"__(start|stop)_", name)}

    declared = set()
    for header in glob.glob(os.path.join(include, "voxrg", "*.h")):
        text = open(header).read()
        text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
        text = re.sub(r"//[^\n]*", " ", text)
        text = re.sub(r"^\s*#(?:[^\n]*\\\n)*[^\n]*", " ", text, flags=re.M)  # macros (VRG_PLUGIN defines the entry)
        # a declaration ends at ';' or starts a body at '{': split on both and
        # keep the function declarations that are not static inline or typedefs
        for decl in re.split(r"[;{}]", text):
            m = re.search(r"\b(vrg_\w+)\s*\(", decl)
            if not m or re.search(r"\b(static|typedef)\b", decl) or "(*" in decl.split(m.group(1))[0]:
                continue
            declared.add(m.group(1))
    failures = 0
    for name in sorted(exported - declared):
        print("exported but not in a public header: %s" % name)
        failures += 1
    for name in sorted(declared - exported):
        print("declared in a public header but not exported: %s" % name)
        failures += 1
    print("%s: %d exported, %d declared: %s" % (os.path.basename(lib), len(exported), len(declared), "ok" if not failures else "FAILED"))
    return failures


args = sys.argv[1:]
if not args or len(args) % 2:
    sys.exit(__doc__)
sys.exit(1 if sum(check(args[k], args[k + 1]) for k in range(0, len(args), 2)) else 0)
