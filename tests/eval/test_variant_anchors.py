#!/usr/bin/python3
"""Every shader edit of the study scripts in scripts/eval still finds its anchor, once, in this tree.

The scripts that measure a cut-out piece of a pass (adaptive_overhead.py's rows, the plain variants of
resolve_motion.py, ...) render a copy of shaders/ (or include/) with a text replacement
(adaptive_overhead.make_variant), which refuses an anchor that is gone. A refactor of a shader can remove an
anchor without any test noticing until someone reruns the study. This walks every module-level value of those
scripts for edits, (file, anchor, replacement) with a .glsl or .h file, and checks each anchor occurs exactly once
in the file under shaders/ or include/. It also fails when it finds no edit in a script that builds variants, so
a script whose edits moved inside a function is named here rather than silently skipped.

    /usr/bin/python3 tests/eval/test_variant_anchors.py
"""
import glob
import importlib
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EVAL = os.path.join(ROOT, "scripts", "eval")
sys.path.insert(0, EVAL)


def edits_in(value, seen):
    """The (file, anchor, replacement) triples anywhere inside value (lists, tuples, dicts)."""
    if id(value) in seen:
        return []
    seen.add(id(value))
    if isinstance(value, tuple) and len(value) == 3 and all(isinstance(v, str) for v in value) and \
            value[0].endswith((".glsl", ".h")):
        return [value]
    out = []
    if isinstance(value, (list, tuple)):
        for v in value:
            out += edits_in(v, seen)
    elif isinstance(value, dict):
        for v in value.values():
            out += edits_in(v, seen)
    return out


failures = []
checked = 0
for path in sorted(glob.glob(os.path.join(EVAL, "*.py"))):
    with open(path) as f:
        source = f.read()
    if "make_variant(" not in source:
        continue
    name = os.path.splitext(os.path.basename(path))[0]
    module = importlib.import_module(name)
    seen = set()
    edits = []
    for value in vars(module).values():
        if isinstance(value, (list, tuple, dict)):
            edits += edits_in(value, seen)
    if not edits and "make_variant(" in source.replace("def make_variant(", ""):
        failures.append(f"{name}: builds variants, but no module-level edit was found")
    for file, anchor, _ in edits:
        checked += 1
        found = [p for p in (os.path.join(ROOT, "shaders", file), os.path.join(ROOT, "include", file)) if os.path.isfile(p)]
        if not found:
            failures.append(f"{name}: {file} is in neither shaders/ nor include/")
            continue
        with open(found[0]) as f:
            count = f.read().count(anchor)
        if count != 1:
            failures.append(f"{name}: the anchor occurs {count} times in {file}: {anchor!r}")

print(f"{checked} edits checked")
if checked == 0:
    failures.append("no edit found at all")
for f in failures:
    print("FAIL:", f)
sys.exit(1 if failures else 0)
