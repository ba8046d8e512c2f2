#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Check that every link of the project's Markdown files resolves inside the repository.

    python3 tools/check_links.py [ROOT]          (ROOT: the repository, default: this one)

The files are README.md, CHANGELOG.md and every other ``*.md`` under the root, outside
build trees and hidden directories. A link is ``[text](target)`` or ``![alt](target)``
(also a reference definition ``[label]: target``), outside code spans and fenced code.
Each target must

- be relative (no scheme such as ``https:`` and no absolute path): the docs are
  self-contained, a clone has everything they point to;
- name a file or directory that exists, without leaving the repository;
- when it has an anchor ``#name`` into a Markdown file, name a heading of that file
  (GitHub's rule: lower case, punctuation dropped, spaces turned into hyphens).

Prints every broken link as ``file:line: target: reason`` and exits 1 if there is any,
else prints the count and exits 0.
"""

from __future__ import annotations

import re
import sys
import unicodedata
from pathlib import Path

SKIP_DIRS = {"build", "_build", "node_modules", "__pycache__"}
INLINE = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
HEADING = re.compile(r"^\s{0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s{0,3}(```|~~~)")


def markdown_files(root: Path) -> list[Path]:
    files = []
    for path in sorted(root.rglob("*.md")):
        parts = path.relative_to(root).parts
        if any(p in SKIP_DIRS or p.startswith(".") for p in parts[:-1]):
            continue
        files.append(path)
    return files


def prose_lines(text: str) -> list[tuple[int, str]]:
    """(line number, line) outside fenced code, with code spans blanked out."""
    lines, fenced = [], False
    for number, line in enumerate(text.splitlines(), start=1):
        if FENCE.match(line):
            fenced = not fenced
            continue
        if not fenced:
            lines.append((number, re.sub(r"`[^`]*`", "``", line)))
    return lines


def slug(heading: str) -> str:
    """GitHub's anchor of a heading."""
    text = re.sub(r"`([^`]*)`", r"\1", heading)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)   # a link keeps its text
    text = text.strip().lower()
    kept = [c for c in text
            if c in " -_" or unicodedata.category(c)[0] in ("L", "N")]
    return "".join(kept).replace(" ", "-")


def anchors(path: Path, cache: dict[Path, set[str]]) -> set[str]:
    if path not in cache:
        seen: dict[str, int] = {}
        names = set()
        for _, line in prose_lines(path.read_text(encoding="utf-8")):
            match = HEADING.match(line)
            if not match:
                continue
            base = slug(match.group(2))
            count = seen.get(base, 0)
            seen[base] = count + 1
            names.add(base if count == 0 else f"{base}-{count}")
        cache[path] = names
    return cache[path]


def check(root: Path) -> tuple[int, list[str]]:
    root = root.resolve()
    problems, count, cache = [], 0, {}
    for source in markdown_files(root):
        rel = source.relative_to(root)
        for number, line in prose_lines(source.read_text(encoding="utf-8")):
            targets = INLINE.findall(line)
            reference = REFERENCE.match(line)
            if reference:
                targets.append(reference.group(1))
            for target in targets:
                count += 1
                where = f"{rel}:{number}: {target or '(empty)'}"
                if not target:
                    problems.append(f"{where}: empty link")
                    continue
                if SCHEME.match(target):
                    problems.append(f"{where}: points outside the repository (a URL)")
                    continue
                path_part, _, anchor = target.partition("#")
                if path_part.startswith("/"):
                    problems.append(f"{where}: absolute path")
                    continue
                resolved = (source.parent / path_part).resolve() if path_part else source
                try:
                    resolved.relative_to(root)
                except ValueError:
                    problems.append(f"{where}: leaves the repository")
                    continue
                if not resolved.exists():
                    problems.append(f"{where}: no such file")
                    continue
                if anchor and resolved.suffix == ".md":
                    if anchor not in anchors(resolved, cache):
                        problems.append(f"{where}: no heading with the anchor #{anchor}")
    return count, problems


def main(argv: list[str]) -> int:
    root = Path(argv[1]) if len(argv) > 1 else Path(__file__).resolve().parents[1]
    count, problems = check(root)
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} of {count} links are broken")
        return 1
    print(f"all {count} links of {len(markdown_files(root.resolve()))} Markdown files "
          "resolve inside the repository")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
