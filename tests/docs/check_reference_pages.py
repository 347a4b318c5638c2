#!/usr/bin/python3
"""The reference pages stay short and free of the lab notebook's history (issue 48's targets).

Usage: /usr/bin/python3 tests/docs/check_reference_pages.py [REPO_ROOT]

The reference pages are docs/*.md (the notebook, docs/notebook/, and the generated tables under docs/results/
are not). Checked:
  - each page at most 30,000 bytes, all of them together at most 150,000;
  - no commit hash (7 to 40 hex digits, a digit and a letter among them) in a page's prose: only inside a
    generated block (<!-- BEGIN GENERATED: x --> ... END), on the provenance line directly above one, or in a
    fenced block; a hash belongs in the notebook;
  - no merge-conflict marker in any docs/**/*.md;
  - docs/ at most 2,000,000 bytes (every file under it that git does not ignore).
Exit 0 when all hold, 1 with one line per failure otherwise.
"""
import os
import re
import subprocess
import sys

PAGE_LIMIT = 30_000
TOTAL_LIMIT = 150_000
DOCS_LIMIT = 2_000_000
HASH = re.compile(r"\b(?=[0-9a-f]*[0-9])(?=[0-9a-f]*[a-f])[0-9a-f]{7,40}\b")
CONFLICT = re.compile(r"^(<<<<<<< |>>>>>>> |=======$)")


def prose_hashes(lines):
    """(line number, hash) of each hash outside generated blocks, their provenance lines and fenced blocks."""
    found, in_block, fenced = [], False, False
    for i, line in enumerate(lines):
        if line.lstrip().startswith("```"):
            fenced = not fenced
            continue
        if "<!-- BEGIN GENERATED:" in line:
            in_block = True
        if in_block or fenced:
            if "<!-- END GENERATED:" in line:
                in_block = False
            continue
        if i + 1 < len(lines) and "<!-- BEGIN GENERATED:" in lines[i + 1]:
            continue  # the block's provenance line
        found += [(i + 1, h) for h in HASH.findall(line)]
    return found


def docs_files(root, docs):
    """Every file under docs/ that the repository holds or would hold: git's tracked and untracked-but-not-ignored
    files where git can list them (a full run_eval.py run leaves its ignored raw CSVs under docs/results/raw/),
    else every file."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others", "--exclude-standard",
                              "--", "docs"], capture_output=True, check=True).stdout.decode()
        return [os.path.join(root, p) for p in out.split("\0") if p and os.path.isfile(os.path.join(root, p))]
    except (OSError, subprocess.CalledProcessError):
        return [os.path.join(d, f) for d, _, files in os.walk(docs) for f in files]


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else ".")
    docs = os.path.join(root, "docs")
    failures, total = [], 0
    pages = sorted(f for f in os.listdir(docs) if f.endswith(".md"))
    for page in pages:
        path = os.path.join(docs, page)
        size = os.path.getsize(path)
        total += size
        if size > PAGE_LIMIT:
            failures.append(f"docs/{page}: {size} bytes, over {PAGE_LIMIT}: move studies to docs/notebook/")
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
        for number, h in prose_hashes(lines):
            failures.append(f"docs/{page}:{number}: commit hash {h} in a reference page (the notebook keeps them)")
    if total > TOTAL_LIMIT:
        failures.append(f"docs/*.md: {total} bytes in all, over {TOTAL_LIMIT}")
    everything = 0
    for path in docs_files(root, docs):
        everything += os.path.getsize(path)
        if path.endswith(".md"):
            with open(path, encoding="utf-8") as text:
                for number, line in enumerate(text, 1):
                    if CONFLICT.match(line):
                        failures.append(f"{os.path.relpath(path, root)}:{number}: merge-conflict marker")
    if everything > DOCS_LIMIT:
        failures.append(f"docs/: {everything} bytes, over {DOCS_LIMIT}")
    for line in failures:
        print(line)
    if failures:
        return 1
    print(f"check_reference_pages.py: {len(pages)} reference pages, {total} bytes in all (largest "
          f"{max(os.path.getsize(os.path.join(docs, p)) for p in pages)}), no commit hash in their prose; "
          f"docs/ {everything} bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
