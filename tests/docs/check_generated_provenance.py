#!/usr/bin/python3
"""Every generated block of the docs says how to regenerate it and at which commit it was made.

Usage: /usr/bin/python3 tests/docs/check_generated_provenance.py [REPO_ROOT]

A block runs from <!-- BEGIN GENERATED: name --> to <!-- END GENERATED: name --> in a docs/**/*.md file. Its
text, or the line directly above its BEGIN marker, must hold
  - the command that regenerates it: a `code span` running a script of this repository, e.g.
    `/usr/bin/python3 scripts/demo_docs.py --only passes` (the script must exist), and
  - the commit it was made at: "commit <7 to 40 hex digits>".
Markers must pair up (one END per BEGIN, same name, in order). Exit status 0 when every block passes (or is a
listed exception), 1 with one line per failure otherwise.
"""
import os
import re
import sys

# Blocks known to lack their command or commit, as "path:name" relative to docs/. Each entry is a failure that
# is tolerated until its generator is fixed; an entry whose block passes (or no longer exists) is an error too,
# so that the list only ever shrinks.
KNOWN_EXCEPTIONS: set = set()

MARKER = re.compile(r"<!-- (BEGIN|END) GENERATED: ([^ ]+) -->")
COMMAND = re.compile(r"`(?:(?:/usr/bin/)?(?:python3|bash|sh) +)?(scripts/[^\s`]+)[^`]*`")
COMMIT = re.compile(r"\bcommit [0-9a-f]{7,40}\b")


def blocks(text, path):
    """(name, the line above BEGIN plus the block's text) of each block; problems as a list of strings."""
    out, problems, open_block = [], [], None
    lines = text.splitlines()
    for i, line in enumerate(lines):
        m = MARKER.search(line)
        if not m:
            continue
        kind, name = m.groups()
        if kind == "BEGIN":
            if open_block:
                problems.append(f"{path}:{i + 1}: BEGIN GENERATED: {name} inside the open block {open_block[0]}")
            open_block = (name, i)
        else:
            if not open_block or open_block[0] != name:
                problems.append(f"{path}:{i + 1}: END GENERATED: {name} without its BEGIN")
                continue
            begin = open_block[1]
            above = lines[begin - 1] if begin > 0 else ""
            out.append((name, begin + 1, "\n".join([above] + lines[begin + 1: i])))
            open_block = None
    if open_block:
        problems.append(f"{path}:{open_block[1] + 1}: BEGIN GENERATED: {open_block[0]} has no END")
    return out, problems


def missing(body, root):
    """What the block lacks: "command", "commit", or a named script that does not exist."""
    lacks = []
    scripts = [m.group(1) for m in COMMAND.finditer(body)]
    existing = [s for s in scripts if os.path.isfile(os.path.join(root, s))]
    if not scripts:
        lacks.append("a regenerating command (a `code span` running scripts/...)")
    elif not existing:
        lacks.append(f"a command whose script exists (named: {', '.join(scripts)})")
    if not COMMIT.search(body):
        lacks.append("the commit it was made at (\"commit <hex>\")")
    return lacks


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    docs = os.path.join(root, "docs")
    failures, seen, checked = [], set(), 0
    for folder, _, files in sorted(os.walk(docs)):
        for f in sorted(files):
            if not f.endswith(".md"):
                continue
            path = os.path.join(folder, f)
            rel = os.path.relpath(path, docs)
            with open(path, encoding="utf-8") as fh:
                found, problems = blocks(fh.read(), "docs/" + rel)
            failures += problems
            for name, line, body in found:
                checked += 1
                key = f"{rel}:{name}"
                lacks = missing(body, root)
                if key in KNOWN_EXCEPTIONS:
                    seen.add(key)
                    if not lacks:
                        failures.append(f"docs/{rel}:{line}: block {name} now names its command and commit: remove "
                                        f"\"{key}\" from KNOWN_EXCEPTIONS in {os.path.relpath(__file__, root)}")
                    continue
                for what in lacks:
                    failures.append(f"docs/{rel}:{line}: block {name} lacks {what}")
    for key in sorted(KNOWN_EXCEPTIONS - seen):
        failures.append(f"KNOWN_EXCEPTIONS lists {key}, which is no block of docs/: remove it")
    for line in failures:
        print(line)
    if failures:
        print(f"check_generated_provenance: {len(failures)} problem(s) in {checked} generated blocks")
        return 1
    print(f"check_generated_provenance: {checked} generated blocks name their command and commit "
          f"({len(KNOWN_EXCEPTIONS)} known exceptions)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
