#!/usr/bin/python3
"""docs/demo.md names every flag of `emcv-demo --help`, and no emcv-demo flag that --help does not list.

Usage: /usr/bin/python3 tests/docs/check_demo_flags.py EMCV_DEMO DOC

A flag is `--name` in --help's text and in the document; a document line that runs another program of the
repository (`scripts/...`) is not read for the second direction. Exit 0 when both directions hold, 1 with one
line per problem otherwise.
"""
import re
import subprocess
import sys

FLAG = re.compile(r"(?<![\w-])--[a-z][a-z-]*")


def main():
    demo, doc = sys.argv[1], sys.argv[2]
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
    for p in problems:
        print(p)
    if problems or not flags:
        return 1
    print(f"demo flags: OK ({len(flags)} flags of --help, all in {doc})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
