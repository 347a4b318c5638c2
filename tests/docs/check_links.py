#!/usr/bin/python3
"""Every relative link of the docs resolves: its file exists and its #anchor is a heading of that file.

Usage: /usr/bin/python3 tests/docs/check_links.py [REPO_ROOT]

Reads README.md, CHANGELOG.md and docs/**/*.md. A link is `[text](target)` outside code spans and fenced blocks;
http(s) and mailto links are not followed. An anchor is GitHub's slug of a heading (lower case, punctuation but
`-` and `_` dropped, spaces to `-`, a repeated slug numbered -1, -2, ...). Exit 0 when every link resolves, 1 with
one line per broken link otherwise.
"""
import os
import re
import sys

LINK = re.compile(r"\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def strip_code(text):
    """The text with fenced blocks and code spans blanked (line numbers kept)."""
    out, fenced = [], False
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
            out.append("")
            continue
        out.append("" if fenced else re.sub(r"`[^`]*`", "``", line))
    return out


def slug(heading):
    s = heading.strip().lower()
    s = re.sub(r"<[^>]+>", "", s)                     # inline html
    s = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", s)    # links keep their text
    s = s.replace("`", "")
    s = re.sub(r"[^\w\- ]", "", s)
    return s.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        found, seen = set(), {}
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
        fenced = False
        for line in lines:
            if line.lstrip().startswith("```"):
                fenced = not fenced
                continue
            m = None if fenced else HEADING.match(line)
            if m:
                base = slug(m.group(2))
                n = seen.get(base, 0)
                seen[base] = n + 1
                found.add(base if n == 0 else f"{base}-{n}")
            for a in re.findall(r"<a (?:name|id)=\"([^\"]+)\"", line):
                found.add(a)
        cache[path] = found
    return cache[path]


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    docs = [os.path.join(root, "README.md"), os.path.join(root, "CHANGELOG.md")]
    for d, _, files in os.walk(os.path.join(root, "docs")):
        docs += [os.path.join(d, f) for f in sorted(files) if f.endswith(".md")]
    broken, links = [], 0
    for doc in docs:
        if not os.path.exists(doc):
            continue
        with open(doc, encoding="utf-8") as f:
            lines = strip_code(f.read())
        for number, line in enumerate(lines, 1):
            for target in LINK.findall(line):
                if re.match(r"^(https?:|mailto:)", target):
                    continue
                links += 1
                path, _, anchor = target.partition("#")
                where = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path else doc
                rel = os.path.relpath(doc, root)
                if not os.path.exists(where):
                    broken.append(f"{rel}:{number}: {target}: no file {os.path.relpath(where, root)}")
                elif anchor and where.endswith(".md") and anchor not in anchors(where):
                    broken.append(f"{rel}:{number}: {target}: no heading #{anchor} in {os.path.relpath(where, root)}")
    for b in broken:
        print(b)
    if broken:
        print(f"check_links.py: {len(broken)} of {links} links broken")
        return 1
    print(f"check_links.py: all {links} relative links of {len(docs)} documents resolve")
    return 0


if __name__ == "__main__":
    sys.exit(main())
