#!/usr/bin/python3
"""docs/integration.md's install table is the install: every path it names exists under the installed prefix, and
every installed file is under a path it names.

Usage: /usr/bin/python3 tests/package/check_install_table.py DOC PREFIX [--absent PATTERN]...

The table is the one whose header is "| path under `<prefix>` | what |". Each row's first cell holds
`code spans` separated by commas: a path relative to the prefix (a glob; one ending in "/" takes its whole
folder), or a bare name, which lives in the folder of the span before it. --absent names a path of the table
that this build does not install (the Python module of a build without it). Exit 0 when both directions hold,
1 with one line per problem otherwise.
"""
import fnmatch
import os
import re
import sys


def table_paths(doc):
    lines = open(doc, encoding="utf-8").read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("| path under `<prefix>` |"))
    paths = []
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        folder = ""
        for span in re.findall(r"`([^`]+)`", line.split("|")[1]):
            if "/" not in span.rstrip("/"):
                span = folder + span
            folder = span[: span.rstrip("/").rfind("/") + 1]
            paths.append(span)
    return paths


def covers(pattern, rel):
    if pattern.endswith("/"):
        return rel.startswith(pattern)
    return fnmatch.fnmatchcase(rel, pattern) and rel.count("/") == pattern.count("/")


def main():
    doc, prefix = sys.argv[1], os.path.abspath(sys.argv[2])
    absent = [sys.argv[i + 1] for i in range(3, len(sys.argv) - 1) if sys.argv[i] == "--absent"]
    patterns = table_paths(doc)
    installed = []
    for d, _, files in os.walk(prefix):
        installed += [os.path.relpath(os.path.join(d, f), prefix) for f in files]
    problems = [f"{doc}: `{p}` matches no installed file" for p in patterns
                if p not in absent and not any(covers(p, f) for f in installed)]
    problems += [f"{doc}: the installed {f} is in no row of the install table" for f in sorted(installed)
                 if not any(covers(p, f) for p in patterns)]
    for p in problems:
        print(p)
    if problems or not patterns:
        return 1
    print(f"install table: OK ({len(patterns)} paths, {len(installed)} installed files)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
