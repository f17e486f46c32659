#!/usr/bin/env python3
"""Places that state a parameter, for every pass in passes/ (issue: a pass is
one file). A shader-only pass (NAME.comp, no C) states each parameter once:
its push-constant member with the @param line. A C pass states a parameter
that its shader reads twice: the params[] table and the push-constant member
of the same name, which the runtime packs by name; the C neither reads it
to copy it into a struct nor pushes it under its name (reading it for its
own logic is a use, not a statement). No pass sets push_size (a C mirror
of the block), and no C pushes a parameter's own member, except those
listed below with the reason.

usage: test_param_places.py VOXRG SOURCE_DIR"""
import glob
import os
import re
import subprocess
import sys

# pass -> why it still pushes a C struct
PUSH_STRUCTS = {}
# (pass, parameter) -> why the C names a pushed parameter again: it computes the member from it
COMPUTED = {
    ("sun_shadow", "rays"): "one ray for a point sun (sun_radius 0)",
    ("sparse_atrous", "long_history"): "turned on per iteration (long_iterations)",
    ("tiles", "columns"): "0: as many as make the grid square",
}


def parameters(voxrg, name):
    out = subprocess.run([voxrg, "plugins", name], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if out.returncode != 0:
        raise RuntimeError("voxrg plugins %s exited %d:\n%s" % (name, out.returncode, out.stdout))
    params, inside = [], False
    for line in out.stdout.split("\n"):
        if line.startswith("parameters:"):
            inside = True
        elif inside and line.startswith("  ") and line.split():
            params.append((line.split()[0], line.split()[1]))
        elif inside and line.strip():
            inside = False
    return params


def push_members(glsl):
    """Each push-constant member's name, with the number of declarations
    (a block declared under several #ifdefs counts once a name)."""
    names = set()
    for m in re.finditer(r"push_constant\)\s*uniform\s+\w+\s*\{(.*?)\}", glsl, re.S):
        body = re.sub(r"//[^\n]*", "", m.group(1))
        body = "\n".join(l for l in body.split("\n") if not l.strip().startswith("#"))
        for decl in body.split(";"):
            words = decl.replace(",", " , ").split()
            if len(words) < 2:
                continue
            for part in " ".join(words[1:]).split(","):
                part = part.strip().split("[")[0].strip()
                if part:
                    names.add(part)
    return names


def main():
    voxrg, root = sys.argv[1], sys.argv[2]
    problems, rows = [], []
    for folder in sorted(glob.glob(os.path.join(root, "passes", "*", ""))):
        name = os.path.basename(os.path.dirname(folder))
        c_path, comp_path = os.path.join(folder, name + ".c"), os.path.join(folder, name + ".comp")
        shaders = sorted(glob.glob(os.path.join(folder, "*.comp")))
        members = set()
        for s in shaders:
            members |= push_members(open(s).read())
        params = parameters(voxrg, name)
        if not os.path.exists(c_path):
            text = open(comp_path).read()
            for p, _ in params:
                places = len(re.findall(r"^\s*\w+\s+%s\s*;\s*//\s*@param\b" % re.escape(p), text, re.M))
                rows.append((name, p, places, "shader-only"))
                if places != 1:
                    problems.append("%s: parameter '%s' is stated %d times, not once (its @param member)" % (comp_path, p, places))
            continue
        c = open(c_path).read()
        if re.search(r"\.push_size\s*=", c) and name not in PUSH_STRUCTS:
            problems.append("%s: sets push_size (a C mirror of the push-constant block): push by name (docs/plugin-abi.md)" % c_path)
        struct = name in PUSH_STRUCTS
        for p, ptype in params:
            if p not in members or ptype == "text":
                continue  # C's own, or a string whose member the C sets (a choice's index)
            # statements: the table, the member, and every copy the C
            # makes: a value pushed under its name, a struct mirroring the
            # block (reading it for the pass's own logic is a use)
            pushed = len(re.findall(r'vrg_push_\w+\(\s*\w+\s*,\s*"%s"' % re.escape(p), c))
            places = 2 + pushed + (1 if struct else 0)
            rows.append((name, p, places, "C, push struct" if struct else "C"))
            if places != 2 and not struct and (name, p) not in COMPUTED:
                problems.append("%s: parameter '%s', a push-constant member, is pushed by the C again: the runtime packs it by name "
                                "(state it in params[] and the shader only)" % (c_path, p))
    for name, p, places, kind in rows:
        print("%-20s %-20s %-12s %d" % (name, p, kind, places))
    for problem in problems:
        print("FAIL:", problem)
    print("test_param_places: %d parameters, %d problems" % (len(rows), len(problems)))
    return 1 if problems else 0


sys.exit(main())
