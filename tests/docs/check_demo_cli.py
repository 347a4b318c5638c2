#!/usr/bin/python3
"""The docs state emcv-demo's command line as it is: docs/demo.md names every flag of `emcv-demo --help` and no
emcv-demo flag that --help does not list, and the methods tables of docs/demo.md and docs/renderer.md (the
section "## Methods") name every method of `emcv-demo --list-methods` and no other.

Usage: /usr/bin/python3 tests/docs/check_demo_cli.py EMCV_DEMO DOCS_DIR

A flag is `--name` in --help's text and in demo.md; a line that runs another program of the repository
(`scripts/...`) is not read for the second direction. A method is the first column of --list-methods without
its parameter ("burley-16" -> "burley"); a table row's methods are the code spans of its first cell, likewise
("burley-N", "separable-11|17|25" -> "burley", "separable"). Exit 0 when all hold, 1 with one line per problem.
"""
import re
import subprocess
import sys

FLAG = re.compile(r"(?<![\w-])--[a-z][a-z-]*")


def base_name(name):
    """A method's name without its parameter: burley-16, burley-N, separable[-11|-17|-25] -> burley, separable."""
    name = re.sub(r"\[.*\]$", "", name)
    return re.sub(r"-(N|\d+([|\\]+\d+)*)$", "", name)


def table_methods(path):
    """The methods named in the first cells of the rows of `path`'s section "## Methods"."""
    names, inside = set(), False
    for line in open(path, encoding="utf-8"):
        if line.startswith("## "):
            inside = line.strip() == "## Methods"
        elif inside and line.startswith("| `") and not line.startswith("| `--"):
            names |= {base_name(n) for n in re.findall(r"`([^`]+)`", line.split(" | ")[0])}
    return names


def check_methods(demo, docs):
    listing = subprocess.run([demo, "--list-methods"], capture_output=True, text=True, check=True).stdout
    methods = {base_name(line.split("\t")[0]) for line in listing.splitlines() if line.strip()}
    problems = []
    for page in ("demo.md", "renderer.md"):
        named = table_methods(f"{docs}/{page}")
        problems += [f"docs/{page}: the method {m} has no row in its Methods table" for m in sorted(methods - named)]
        problems += [f"docs/{page}: its Methods table names {m}, which emcv-demo does not have"
                     for m in sorted(named - methods)]
    return problems, len(methods)


def main():
    demo, docs = sys.argv[1], sys.argv[2]
    doc = f"{docs}/demo.md"
    help_text = subprocess.run([demo, "--help"], capture_output=True, text=True, check=True).stdout
    flags = set(FLAG.findall(help_text))
    text = open(doc, encoding="utf-8").read()
    documented = set(FLAG.findall(text))
    named = set()
    for line in text.splitlines():
        if "scripts/" not in line:
            named |= set(FLAG.findall(line))
    problems = [f"{doc}: emcv-demo's {f} is not documented" for f in sorted(flags - documented)]
    problems += [f"{doc}: {f} is not a flag of emcv-demo --help" for f in sorted(named - flags)]
    method_problems, methods = check_methods(demo, docs)
    problems += method_problems
    for p in problems:
        print(p)
    if problems or not flags:
        return 1
    print(f"demo command line: OK ({len(flags)} flags of --help in {doc}; {methods} methods in the Methods tables of "
          f"demo.md and renderer.md)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
