#!/usr/bin/env python3
"""The runtime's files call each other one way: the graph object at the top
calls the phases, the phases call the helpers below them, and nothing calls
back up. TIERS below is that order, top first (docs/architecture.md, "The
runtime", says why each file stands where it does). A file may use a
function defined in a file of a lower tier only: not one of its own tier
(phases are siblings: the graph runs them, they do not run each other), not
one above. Every .c file of the folder is in exactly one tier.

Functions are found by name: a definition is a non-static function named
vrg_* or _vrg_* at file scope; a use is that name anywhere in another
file's code (comments and strings aside), called or passed as a pointer.
Usage: check_runtime_order.py RUNTIME_SRC_DIR"""
import glob
import os
import re
import sys

TIERS = [
    ("a frame and a reload, which drive the graph's other faces",
     ["graph_frame.c", "reload.c"]),
    ("the graph object: load and destroy, hot reload, readback, parameters, queries, check's report",
     ["graph.c", "graph_watch.c", "graph_readback.c", "graph_params.c", "graph_info.c", "report.c"]),
    ("the phases",
     ["parse.c", "validate.c", "compile.c", "allocate.c", "record.c"]),
    ("what recording adds when asked: NaN/Inf checks after each pass",
     ["check_finite.c"]),
    ("one texel of images after a frame",
     ["pixels.c"]),
    ("what passes call beside the pass API: the dispatch helper, shared objects",
     ["dispatch.c", "pass_share.c"]),
    ("the pass API",
     ["pass_api.c"]),
    ("helpers of the phases and the pass API",
     ["plugin_loader.c", "barrier.c", "alias.c"]),
    ("a shader-only pass's interface, read from its shader for the loader",
     ["shader_pass.c"]),
    ("run-time GLSL compilation, for the dispatch helper and shader-only passes",
     ["shader.c"]),
    ("what the helpers build on",
     ["reflect.c", "capture.c", "resource.c", "watch.c", "context.c", "crash.c", "install.c", "defaults.c", "camera.c", "param_desc.c"]),
    ("the vocabulary: formats, accesses, messages",
     ["format.c", "access.c", "diag.c", "file.c"]),
    ("the text a message quotes",
     ["escape.c"]),
]


def code_of(path):
    text = open(path).read()
    text = re.sub(r"/\*.*?\*/", " ", text, flags=re.S)
    text = re.sub(r"//[^\n]*", " ", text)
    text = re.sub(r"'(?:\\.|[^'\\\n])'", "' '", text)
    return re.sub(r'"(?:\\.|[^"\\\n])*"', '""', text)


# A definition starts at column 0, is not static, and its parameter list
# (which may hold function-pointer parentheses and span lines) ends in "{".
DEFINITION = re.compile(r"^(?!static\b)[A-Za-z_][^;{}()=#]*?\b(_?vrg_\w+)\s*\(((?:[^(){};]|\([^()]*\))*)\)\s*\{", re.M)


def main(src):
    tier_of, failures = {}, []
    for t, (_, files) in enumerate(TIERS):
        for f in files:
            if f in tier_of:
                failures.append("%s is listed twice" % f)
            tier_of[f] = t
    present = {os.path.basename(p) for p in glob.glob(os.path.join(src, "*.c"))}
    for f in sorted(present - set(tier_of)):
        failures.append("%s is in no tier: add it where it belongs" % f)
    for f in sorted(set(tier_of) - present):
        failures.append("%s is listed but does not exist" % f)

    code = {f: code_of(os.path.join(src, f)) for f in sorted(present)}
    defined_in = {}
    for f, text in code.items():
        for m in DEFINITION.finditer(text):
            defined_in.setdefault(m.group(1), set()).add(f)
    for name, files in sorted(defined_in.items()):
        if len(files) > 1:
            failures.append("%s is defined in %s" % (name, " and ".join(sorted(files))))

    for f, text in code.items():
        if f not in tier_of:
            continue
        for name in sorted(set(re.findall(r"\b_?vrg_\w+\b", text))):
            for owner in sorted(defined_in.get(name, ())):
                if owner == f or owner not in tier_of:
                    continue
                if tier_of[owner] < tier_of[f]:
                    failures.append("%s (%s) uses %s of %s, a tier above it (%s)"
                                    % (f, TIERS[tier_of[f]][0], name, owner, TIERS[tier_of[owner]][0]))
                elif tier_of[owner] == tier_of[f]:
                    failures.append("%s uses %s of %s, its sibling in '%s'" % (f, name, owner, TIERS[tier_of[f]][0]))

    for line in failures:
        print(line)
    print("runtime order: %s" % ("ok" if not failures else "%d problems" % len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
