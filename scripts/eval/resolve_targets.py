#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Where the resolve's clip points: the resolved PSNR with each clip target (docs/frame.md, "Where the clip points").

The resolve moves a history outside its neighbourhood's box along the line towards a target until it reaches
the box (include/emcv/port/resolve.h, emcv_resolve_clip). Each variant is the shaders of this tree with the
target replaced (a copy of shaders/ with one text replacement, read through EMCV_SHADER_DIR; the script refuses
when the anchor is no longer in the shader): the box's centre (the neighbourhood's mean), the raw current
value, the filtered current value, and the target as built (emcv_resolve_target: the filtered value with the
detail the history's own neighbourhood shows put back). Every run is emcv-demo --resolve taa with the adaptive
methods under --spp-budget B; a cell is the mean over frames FIRST.. of psnr_resolved_db (whole frame), or of
psnr_sss_resolved_db for the rows marked "SSS pixels".

Usage: /usr/bin/python3 scripts/eval/resolve_targets.py [--build build] [--write-doc]
With --write-doc the table replaces the GENERATED block "resolve-targets" of docs/frame.md.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

from adaptive_overhead import make_variant
from run_eval import publish_table

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RESOLVE = "render/resolve.comp.glsl"
AS_BUILT = "        vec3 target = emcv_resolve_clip(detailed, current, lo, hi);\n"
VARIANTS = [
    ("the box's centre", [(RESOLVE, AS_BUILT, "        vec3 target = emcv_resolve_clip(sum / 9.0f, current, lo, hi);\n")]),
    ("the raw current value", [(RESOLVE, AS_BUILT, "        vec3 target = current;\n")]),
    ("the filtered current value", [(RESOLVE, AS_BUILT, "        vec3 target = emcv_resolve_clip(filtered, current, lo, hi);\n")]),
    ("as built: filtered, with the history's detail", []),
]
SCENES = "demo/scenes/"
# (scene, size, frames, first frame averaged, budget, methods, column)
CASES = [
    ("static", "96x96", 40, 20, 8, "burley-64,burley-8,cv,separable-17", "psnr_resolved_db"),
    ("light-off", "96x96", 60, 20, 8, "burley-64,burley-8,cv,separable-17", "psnr_resolved_db"),
    (SCENES + "variations/fade.json", "96x96", 60, 20, 8, "burley-8,cv", "psnr_resolved_db"),
    ("flicker", "96x96", 60, 20, 8, "burley-8,cv", "psnr_resolved_db"),
    ("club", "96x96", 40, 20, 8, "burley-64,burley-8,cv", "psnr_resolved_db"),
    ("moving", "96x96", 40, 20, 8, "burley-64,burley-8,cv", "psnr_resolved_db"),
    (SCENES + "validation/skin-close.json", "96x96", 30, 20, 8, "burley-64,burley-8,cv", "psnr_resolved_db"),
    ("static", "128x128", 40, 20, 4, "burley-4,cv", "psnr_sss_resolved_db"),
]


def run(build, shader_dir, case, out):
    scene, size, frames, first, budget, methods, column = case
    path = os.path.join(ROOT, scene) if scene.startswith(SCENES) else scene
    cmd = [os.path.join(build, "bin", "emcv-demo"), "--scene", path, "--size", size, "--frames", str(frames),
           "--method", methods, "--spp-budget", str(budget), "--resolve", "taa", "--no-frames", "--out", out]
    done = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, EMCV_SHADER_DIR=shader_dir))
    if done.returncode != 0:
        sys.exit(f"resolve_targets.py: {' '.join(cmd)} failed:\n{done.stderr}")
    with open(os.path.join(out, "metrics.csv")) as f:
        rows = [r for r in csv.DictReader(f) if int(r["frame"]) >= first]
    return {m: sum(float(r[column]) for r in rows if r["method"] == m) / sum(1 for r in rows if r["method"] == m)
            for m in methods.split(",")}


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--write-doc", action="store_true", help="replace the resolve-targets block of docs/frame.md")
    a = p.parse_args(argv)
    cells = {}
    with tempfile.TemporaryDirectory() as tmp:
        dirs = {name: make_variant(os.path.join(tmp, f"v{i}"), edits) for i, (name, edits) in enumerate(VARIANTS)}
        for k, case in enumerate(CASES):
            for name, _ in VARIANTS:
                for method, value in run(a.build, dirs[name], case, os.path.join(tmp, "out")).items():
                    cells[(k, method, name)] = value
    lines = ["| scene | size, budget, frames | method | " + " | ".join(n for n, _ in VARIANTS) + " |",
             "|---|---|---|" + "---:|" * len(VARIANTS)]
    for k, (scene, size, frames, first, budget, methods, column) in enumerate(CASES):
        where = f"{size}, {budget}, {first}-{frames - 1}" + (", SSS pixels" if column == "psnr_sss_resolved_db" else "")
        for method in methods.split(","):
            values = [cells[(k, method, n)] for n, _ in VARIANTS]
            best = max(values)
            shown = [f"**{v:.2f}**" if v == best else f"{v:.2f}" for v in values]
            lines.append(f"| {os.path.basename(scene).replace('.json', '')} | {where} | {method} | " + " | ".join(shown) + " |")
    publish_table("\n".join(lines), a.write_doc, os.path.join(ROOT, "docs", "frame.md"), "resolve-targets", "scripts/eval/resolve_targets.py", argv)


if __name__ == "__main__":
    main(sys.argv[1:])
