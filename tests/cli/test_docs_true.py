#!/usr/bin/env python3
"""The docs against the tree they describe, one part per run:
  readme        README.md opens with the title, one sentence and the two
                commands of a fresh machine (scripts/main.sh, scripts/test.sh)
  architecture  docs/architecture.md names every file of core/ (by its path
                under core/), and every repository path it names exists
  headers       the public headers speak of the API: no command-line flag
                (`--set`) and no `voxrg COMMAND`
  synopses      each `voxrg COMMAND [--flag ...]` synopsis in the docs has
                exactly the flags of `voxrg COMMAND --help`'s usage, and every
                flag a doc's example command line gives exists there
  pass_readmes  every passes/NAME/ has README.md in the one form (its
                headings) naming each parameter `voxrg plugins NAME` lists,
                and its Slots and Parameters tables list exactly the slots
                and parameters `voxrg plugins NAME` lists
  tmp_citations no doc cites a script or graph in a temporary folder, which
                its reader does not have
  frame_uniforms plugin-abi.md's table of the frame uniforms is frame.glsl's
                block: names, types, order and size
usage: test_docs_true.py PART SOURCE_DIR [VOXRG]   (each problem on a line
of its own, FILE[:LINE]: ...; exit 1 if there is any)"""
import glob
import os
import re
import subprocess
import sys

COMMANDS = ("check", "render", "run", "plugins", "compare", "bench", "new-pass")
FENCE = re.compile(r"^\s*(```+|~~~+)")


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def doc_pages(root):
    return [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))


def code_blocks(text):
    """(first line number, lines) of each fenced block; an indented block
    (four spaces after a blank line, outside lists) counts as one too."""
    lines = text.split("\n")
    blocks, i = [], 0
    while i < len(lines):
        if FENCE.match(lines[i]):
            j = i + 1
            while j < len(lines) and not FENCE.match(lines[j]):
                j += 1
            blocks.append((i + 2, lines[i + 1:j]))
            i = j + 1
        elif lines[i].startswith("    ") and i > 0 and not lines[i - 1].strip():
            j = i
            while j < len(lines) and (lines[j].startswith("    ") or not lines[j].strip()):
                j += 1
            blocks.append((i + 1, lines[i:j]))
            i = j
        else:
            i += 1
    return blocks


# ---- README -----------------------------------------------------------------

def sentences(paragraph):
    return [s for s in re.split(r"(?<=[.!?])\s+", paragraph.strip()) if s]


def part_readme(root, _voxrg):
    path = os.path.join(root, "README.md")
    lines = read(path).split("\n")
    problems = []
    if lines[0] != "# voxrg":
        problems.append(f"{path}:1: the first line is {lines[0]!r}, not the title '# voxrg'")
    i = 1
    while i < len(lines) and not lines[i].strip():
        i += 1
    start = i
    while i < len(lines) and lines[i].strip() and not FENCE.match(lines[i]):
        i += 1
    paragraph = " ".join(lines[start:i])
    said = sentences(paragraph)
    if len(said) != 1 or not paragraph.rstrip().endswith("."):
        problems.append(f"{path}:{start + 1}: after the title comes one sentence saying what voxrg is; "
                        f"found {len(said)}: {paragraph!r}")
    while i < len(lines) and not lines[i].strip():
        i += 1
    if i >= len(lines) or not FENCE.match(lines[i]):
        problems.append(f"{path}:{i + 1}: after the sentence comes a code block with the two commands")
        return problems
    j = i + 1
    while j < len(lines) and not FENCE.match(lines[j]):
        j += 1
    commands = [re.sub(r"\s+#.*", "", l).strip() for l in lines[i + 1:j] if l.strip()]
    if commands != ["./scripts/main.sh", "./scripts/test.sh"]:
        problems.append(f"{path}:{i + 2}: the first code block holds {commands}, "
                        "not exactly ./scripts/main.sh and ./scripts/test.sh")
    for line in lines[i + 1:j]:
        if "Debian 12" not in line:
            problems.append(f"{path}:{i + 2}: {line.strip()!r} does not say it is for a fresh Debian 12 machine")
    for script in ("scripts/main.sh", "scripts/test.sh"):
        if not os.access(os.path.join(root, script), os.X_OK):
            problems.append(f"{path}: {script} is not an executable file")
    return problems


# ---- architecture -----------------------------------------------------------

REPO_DIRS = ("core", "tests", "shaders", "passes", "plugins", "graphs", "scripts", "docs", "cmake")


def core_files(root):
    """Every source file of a layer, as its path under core/."""
    found = []
    for pattern in ("*/src/*", "*/include/voxrg/*", "cli/*"):
        for path in glob.glob(os.path.join(root, "core", pattern)):
            name = os.path.basename(path)
            if os.path.isfile(path) and name != "CMakeLists.txt":
                found.append(os.path.relpath(path, os.path.join(root, "core")))
    return sorted(found)


def part_architecture(root, _voxrg):
    path = os.path.join(root, "docs", "architecture.md")
    text = read(path)
    quoted = set(re.findall(r"`([^`\s]+)`", text))
    missing = [f for f in core_files(root) if f not in quoted]
    problems = [f"{path}: does not name core/{f} (write `{f}` in the files table of its layer)" for f in missing]
    for number, line in enumerate(text.split("\n"), 1):
        for name in re.findall(r"`([^`\s]+)`", line):
            candidates = []
            if name.split("/")[0] in REPO_DIRS and "/" in name:
                candidates = [name]
            elif re.match(r"^(runtime|voxel|tools|cli)/", name):
                candidates = ["core/" + name]
            for c in candidates:
                if "*" not in c and "NAME" not in c and not os.path.exists(os.path.join(root, c)):
                    problems.append(f"{path}:{number}: `{name}` names {c}, which does not exist")
    return problems


# ---- headers ----------------------------------------------------------------

def part_headers(root, _voxrg):
    problems = []
    for path in sorted(glob.glob(os.path.join(root, "core", "*", "include", "voxrg", "*.h"))):
        for number, line in enumerate(read(path).split("\n"), 1):
            if line.lstrip().startswith("#"):
                continue
            flag = re.search(r"(?<![-\w])--[a-z][a-z-]*", line)
            command = re.search(r"\bvoxrg (%s)\b" % "|".join(map(re.escape, COMMANDS)), line)
            tool = re.search(r"`(%s)[ `]" % "|".join(map(re.escape, COMMANDS)), line)
            for m in (flag, command, tool):
                if m:
                    problems.append(f"{path}:{number}: names the command line ({m.group(0).strip('`')}); "
                                    "a library header speaks of its API")
                    break
    return problems


# ---- synopses ---------------------------------------------------------------

def help_flags(voxrg, command):
    """The usage lines of `voxrg COMMAND --help`, their flags, and every
    flag its text names."""
    out = subprocess.run([voxrg, command, "--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"voxrg {command} --help exited {out.returncode}:\n{out.stdout}")
    lines = out.stdout.split("\n")
    usage = [lines[0]]
    for line in lines[1:]:
        if not line.startswith(" "):
            break
        usage.append(line)
    usage = "\n".join(usage)
    return usage, set(flag_names(usage)), set(flag_names(out.stdout)) | {"--help"}


def flag_names(text):
    return re.findall(r"(?<![-\w])--[a-z][a-z-]*", text)


def choices(text, flag):
    """The alternatives of `--flag a|b|c`, or None."""
    m = re.search(re.escape(flag) + r" ([a-z-]+(?:\|[a-z-]+)+)", text)
    return set(m.group(1).split("|")) if m else None


def command_lines(block):
    """The block's lines joined over trailing backslashes, each cut at
    pipes, `;`, `&&`, `||` and comments, with its first line number."""
    joined, start, current = [], None, ""
    for number, line in block:
        if start is None:
            start = number
        if line.rstrip().endswith("\\"):
            current += line.rstrip()[:-1] + " "
            continue
        joined.append((start, current + line))
        start, current = None, ""
    if current:
        joined.append((start, current))
    for number, line in joined:
        line = re.sub(r"\s#.*", "", line)
        for piece in re.split(r"\|\||&&|[|;&]", line):
            yield number, piece.strip()


INVOCATION = re.compile(r"^(?:\S*/)?voxrg\s+(%s)\b(.*)$" % "|".join(map(re.escape, COMMANDS)))


def synopses_in(numbered):
    """(line, command, text) of each synopsis of a block: a line `voxrg
    COMMAND ...` with [optional] parts, continued on indented lines that
    start with '['."""
    k = 0
    while k < len(numbered):
        number, line = numbered[k]
        m = INVOCATION.match(re.sub(r"\s#.*", "", line).strip())
        k += 1
        if m and line.lstrip().startswith("voxrg") and "[" in m.group(2):
            text = m.group(2)
            while k < len(numbered) and numbered[k][1].strip().startswith("["):
                text += " " + numbered[k][1]
                k += 1
            yield number, m.group(1), text


def example_problems(path, numbered, known):
    """Flags an example command line gives that its command does not know."""
    for number, piece in command_lines(numbered):
        m = INVOCATION.match(piece)
        if not m or "[" in m.group(2):
            continue
        for flag in flag_names(m.group(2)):
            if flag not in known[m.group(1)]:
                yield f"{path}:{number}: `voxrg {m.group(1)} {flag}`: voxrg {m.group(1)} --help has no {flag}"


def synopsis_problems(where, command, text, usage, usage_text):
    named = set(flag_names(text))
    for flag in sorted(named - usage):
        yield f"{where}: the synopsis of `voxrg {command}` names {flag}, which voxrg {command} --help does not"
    for flag in sorted(usage - named):
        yield f"{where}: the synopsis of `voxrg {command}` lacks {flag} (voxrg {command} --help has it)"
    for flag in sorted(named & usage):
        doc, want = choices(text, flag), choices(usage_text, flag)
        if doc is not None and doc != want:
            yield (f"{where}: the synopsis of `voxrg {command}` gives {flag} {'|'.join(sorted(doc))}; "
                   f"voxrg {command} --help: {'|'.join(sorted(want or []))}")


def part_synopses(root, voxrg):
    usage_text, usage, known = {}, {}, {}
    for c in COMMANDS:
        usage_text[c], usage[c], known[c] = help_flags(voxrg, c)
    problems, seen = [], set()
    for path in doc_pages(root):
        for first, lines in code_blocks(read(path)):
            numbered = list(zip(range(first, first + len(lines)), lines))
            # a command of several forms (compare, compare --merge) has a
            # synopsis per form in one block: together they give its flags
            forms = {}
            for number, command, text in synopses_in(numbered):
                seen.add(command)
                first_line, joined = forms.get(command, (number, ""))
                forms[command] = (first_line, joined + " " + text)
            for command, (number, text) in forms.items():
                problems += synopsis_problems(f"{path}:{number}", command, text, usage[command], usage_text[command])
            problems += example_problems(path, numbered, known)
    for command in COMMANDS:
        if command not in seen:
            problems.append(f"{root}/docs: no synopsis of `voxrg {command}` (graph-format.md, The CLI)")
    return problems


# ---- pass READMEs -----------------------------------------------------------

PASS_HEADINGS = ("What it does", "Slots", "Parameters", "Cost", "Debug outputs")


def plugin_interface(voxrg, name):
    """The slots (in.X, out.X) and parameters `voxrg plugins NAME` lists."""
    out = subprocess.run([voxrg, "plugins", name], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"voxrg plugins {name} exited {out.returncode}:\n{out.stdout}")
    lists, inside = {"slots": [], "parameters": []}, None
    for line in out.stdout.split("\n"):
        head = line.split(":")[0]
        if not line.startswith(" ") and head in lists:
            inside = head
        elif inside and line.startswith("  ") and line.split():
            lists[inside].append(line.split()[0])
        elif line.strip():
            inside = None
    return lists["slots"], lists["parameters"]


def table_names(body):
    """The first cell of each row of a section's table, without its
    backticks; a row of a numbered series (`in.t0` ... `in.t8`) names each."""
    names = []
    for row in [l for l in body.split("\n") if l.startswith("|")][2:]:
        series = re.match(r"\|\s*`([^`]*?)(\d+)([^`\d]*)` \.\.\. `([^`]*?)(\d+)([^`\d]*)`\s*\|", row)
        one = re.match(r"\|\s*`([^`]+)`\s*\|", row)
        if series and series.group(1, 3) == series.group(4, 6):
            names += [f"{series.group(1)}{i}{series.group(3)}" for i in range(int(series.group(2)), int(series.group(5)) + 1)]
        elif one:
            names.append(one.group(1))
    return names


def part_pass_readmes(root, voxrg):
    problems = []
    for folder in sorted(glob.glob(os.path.join(root, "passes", "*", ""))):
        name = os.path.basename(os.path.dirname(folder))
        others = [f for f in os.listdir(folder) if f.lower() == "readme.md" and f != "README.md"]
        for other in others:
            problems.append(f"{folder}{other}: named README.md in every pass folder")
        path = os.path.join(folder, "README.md")
        if not os.path.isfile(path):
            problems.append(f"{path}: missing (headings: {', '.join(PASS_HEADINGS)})")
            continue
        text = read(path)
        if not text.startswith(f"# {name}\n"):
            problems.append(f"{path}:1: the title is not '# {name}'")
        headings = re.findall(r"^## (.+?)\s*$", text, re.M)
        if tuple(headings) != PASS_HEADINGS:
            problems.append(f"{path}: headings {headings}, expected {list(PASS_HEADINGS)} in that order")
        slots, params = plugin_interface(voxrg, name)
        for heading, listed in (("Slots", slots), ("Parameters", params)):
            section = re.search(r"^## %s\n(.*?)(?=^## |\Z)" % heading, text, re.M | re.S)
            body = section.group(1) if section else ""
            if heading == "Parameters":
                for param in listed:
                    if f"`{param}`" not in body:
                        problems.append(f"{path}: the Parameters section does not name `{param}` (voxrg plugins {name})")
            # the table: exactly what the plugin declares, each once ("None." where it declares none)
            rows = table_names(body)
            if not listed and not rows and "None." not in body:
                problems.append(f"{path}: the {heading} section has no table and does not say None. ({name} has no {heading.lower()})")
            if sorted(rows) != sorted(listed):
                problems.append(f"{path}: the {heading} table lists {rows}; voxrg plugins {name} lists {listed}"
                                f" (missing {sorted(set(listed) - set(rows))}, not the plugin's {sorted(set(rows) - set(listed))})")
    return problems


# ---- temporary folders --------------------------------------------------------

def part_tmp_citations(root, _voxrg):
    problems = []
    for path in doc_pages(root):
        for number, line in enumerate(read(path).split("\n"), 1):
            for m in re.finditer(r"/tmp/[\w./-]*\.(?:sh|py|ini|path)\b", line):
                problems.append(f"{path}:{number}: cites {m.group(0)}, a file in a temporary folder its reader "
                                "does not have: show the command, or ship the script in scripts/")
    return problems


# ---- frame uniforms --------------------------------------------------------
STD140_SIZE = {"mat4": 64, "vec4": 16, "uvec4": 16, "ivec4": 16}


def part_frame_uniforms(root, _voxrg):
    """plugin-abi.md's table of the frame block: the fields of frame.glsl's
    block, in its order, with its types, and the block's size as stated."""
    glsl = read(os.path.join(root, "shaders", "include", "frame.glsl"))
    block = re.search(r"uniform FrameUniforms\s*\{(.*?)\}\s*frame;", glsl, re.S)
    if not block:
        return ["shaders/include/frame.glsl: no `uniform FrameUniforms { ... } frame;` block"]
    members = re.findall(r"^\s*(\w+)\s+(\w+);", block.group(1), re.M)
    page = os.path.join(root, "docs", "plugin-abi.md")
    text = read(page)
    problems = []
    rows = [(m.group(1), m.group(2)) for m in re.finditer(r"^\| `(\w+)` \| `(\w+)` \|", text, re.M)]
    if [(name, kind) for kind, name in members] != rows:
        problems.append(f"{page}: the frame uniforms' table lists {rows}, frame.glsl declares "
                        f"{[(name, kind) for kind, name in members]}")
    unknown = [kind for kind, _ in members if kind not in STD140_SIZE]
    if unknown:
        problems.append(f"frame.glsl: member types {unknown}: add their std140 sizes to this check")
    size = sum(STD140_SIZE.get(kind, 0) for kind, _ in members)
    said = re.search(r"std140,\s*(\d+)\s*bytes", text)
    if not said or int(said.group(1)) != size:
        problems.append(f"{page}: the frame block is {size} bytes (std140, all members 16-byte multiples), "
                        f"the page says {said.group(1) if said else 'nothing'}")
    return problems


PARTS = {name[len("part_"):]: fn for name, fn in globals().items() if name.startswith("part_")}


def main():
    if len(sys.argv) < 3 or sys.argv[1] not in PARTS:
        print(__doc__)
        return 2
    part, root = sys.argv[1], sys.argv[2]
    voxrg = sys.argv[3] if len(sys.argv) > 3 else None
    problems = PARTS[part](root, voxrg)
    print("\n".join(problems + [f"docs {part}: {'%d problems' % len(problems) if problems else 'ok'}"]))
    return int(bool(problems))


if __name__ == "__main__":
    sys.exit(main())
