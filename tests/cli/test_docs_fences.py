#!/usr/bin/env python3
"""Code fences in the Markdown docs stand on lines of their own: a closing
fence is only backticks, the text after it starts after a blank line, and no
fence follows text on its line. A paragraph glued to a fence renders inside
the code block or swallows the rest of the page, and the docs_example test
cuts its files out of these blocks.
usage: test_docs_fences.py FILE.md|DIR...   (a DIR: its *.md; each problem
as FILE:LINE: ...)"""
import glob
import os
import re
import sys

FENCE = re.compile(r"^\s*(```+|~~~+)(.*)$")


def problems(path):
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    fence = None  # the open block's fence, None outside blocks
    closed_at = -1  # index of the last closing fence
    for i, line in enumerate(lines):
        where = f"{path}:{i + 1}"
        m = FENCE.match(line)
        if fence is None and closed_at == i - 1 and i > 0 and line.strip():
            yield f"{where}: text right after the closing fence of line {i}: leave a blank line"
        if m and fence is None:
            if " " in m.group(2).strip():
                yield f"{where}: text on an opening fence line (an info string is one word): {line.strip()!r}"
            fence = m.group(1)
        elif m and m.group(1).startswith(fence):
            if m.group(2).strip():
                yield f"{where}: text on a closing fence line: {line.strip()!r}"
            fence, closed_at = None, i
        elif fence is None and re.search(r"\S.*(```|~~~)\s*$", line) and not line.strip().startswith("|"):
            yield f"{where}: a fence after text on the same line: {line.strip()!r}"
            fence = re.search(r"(```+|~~~+)\s*$", line).group(1)  # meant as an opening fence: check the rest as such
    if fence is not None:
        yield f"{path}:{len(lines)}: a code block is never closed"


def main():
    pages = []
    for arg in sys.argv[1:]:
        pages += sorted(glob.glob(os.path.join(arg, "*.md"))) if os.path.isdir(arg) else [arg]
    if not pages:
        print("usage: test_docs_fences.py FILE.md|DIR...")
        return 2
    found = [p for path in pages for p in problems(path)]
    for p in found:
        print(p)
    print(f"{len(pages)} pages, {len(found)} fence problems")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
