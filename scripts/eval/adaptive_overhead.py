#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Where an adaptive method's SSS time goes, beside burley-B's (docs/accuracy-vs-time.md, "Where the adaptive
passes' time goes").

Each variant is the shaders of this tree with one piece of the adaptive work cut out: a copy of shaders/ in a
temporary folder with one text replacement, read by the renderer through EMCV_SHADER_DIR (the port headers stay
the tree's). The script refuses when a replacement's anchor is no longer in the shader, so a variant cannot
silently measure the unchanged pass. Every run is emcv-demo with burley-B and the method side by side (frame
by frame, the same load on both), the variants interleaved round by round; per run, each pass's median over
frames FIRST.. is divided by burley-B's pass median of the same run, and the table gives the median of those
ratios over the rounds. A cut changes what the other pass sees (no flush: the burley pass reads a stale
lambda; no reprojection: every pixel takes the uniform share), so a row's number that answers a question is
the pass it cut; the table says which.

Usage: /usr/bin/python3 scripts/eval/adaptive_overhead.py [--build build] [--scene light-off] [--size 256x256]
           [--frames 16] [--first 4] [--rounds 3] [--spp-budget 8] [--method cv] [--write-doc]
With --write-doc the table replaces the GENERATED block "adaptive-overhead" of docs/accuracy-vs-time.md.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

from run_eval import publish_table

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SAMPLES = "adaptive/samples.comp.glsl"
PLANNING = "adaptive/samples.h"  # the reprojection and the pooling, shared with the quality target's burley pass
BUDGET = "adaptive/budget_block.h"
BURLEY = "render/sss_burley.comp.glsl"
HISTORY_IO = "adaptive/history_io.h"

# (name, the pass it answers for, [(file, anchor, replacement)]). Every row but the last runs with the samples pass
# on every frame (EMCV_HISTORY_PLAN_AHEAD=0): the cuts are the samples pass's pieces, and under a still camera the
# as-built renderer records that pass only on the first frame (docs/renderer.md, "Planning the next frame").
AS_BUILT_PLANNED = "as built, the burley pass planning each next frame (no samples pass under a still camera)"
VARIANTS = [
    ("as built", "both", []),
    ("no reprojection: every history fresh (no previous G-buffer or history reads)", "samples",
     [(PLANNING, "    if (emcv_adaptive_reproject(blk, a, b, s, resampled) && !resampled) {",
       "    s = emcv_adaptive_init();\n    if (false) {")]),
    ("nearest texel: the reprojected history not resampled (the same under a still camera)", "samples",
     [(PLANNING, "    if (t == vec2(0.0f) || s.count < 1u) return true;", "    if (true) return true;")]),
    ("no 3x3 pooling", "samples",
     [(PLANNING, "    for (int dy = -1; dy <= 1; ++dy) {", "    for (int dy = 0; dy < 0; ++dy) {")]),
    ("budget: no solve (its dispatch runs empty)", "samples",
     [(BUDGET, "void emcv_budget_solve(uint thread) {\n", "void emcv_budget_solve(uint thread) {\n    return;\n")]),
    ("no budget work at all (histograms, solve)", "samples",
     [(PLANNING, "        emcv_budget_add(sigma2, blk.pixels);\n", ""),
      (PLANNING, "        emcv_budget_add_raw(sigma2, frames, blk.pixels);\n", ""),
      (BUDGET, "void emcv_budget_solve(uint thread) {\n", "void emcv_budget_solve(uint thread) {\n    return;\n")]),
    ("burley pass: every pixel takes B (no divergence; the history update runs)", "burley",
     [(BURLEY, "own = adaptive_count(p);", "own = uint(EMCV_HISTORY_SPP_BUDGET);")]),
    ("burley pass: no noise test (cv: the push alone, no pool)", "burley",
     [(HISTORY_IO, "#if defined(EMCV_ADAPTIVE_CV)\n        float term", "#if 0\n        float term"),
      (HISTORY_IO, "emcv_adaptive_update(texel, s, f, g, batch, emcv_history_noise_ratio(pool));",
       "emcv_adaptive_update(texel, s, f, g, batch, 1.0f);")]),
    ("burley pass: no history update", "burley",
     [(BURLEY, "    emcv_adaptive_update_tile(assigned_local, tile_origin, pending_scattered, pending_unscattered, "
               "pending_albedo, n);\n", "")]),
    (AS_BUILT_PLANNED, "both", []),
]


def make_variant(root, edits, source="shaders"):
    """This tree's `source` folder (shaders/ or include/) with `edits` (file, anchor, replacement) applied to a
    copy under root; the folder itself without edits. Exits when an anchor is not in its file exactly once."""
    if not edits:
        return os.path.join(ROOT, source)
    shutil.copytree(os.path.join(ROOT, source), root)
    for file, anchor, replacement in edits:
        path = os.path.join(root, file)
        with open(path) as f:
            text = f.read()
        if text.count(anchor) != 1:
            sys.exit(f"{os.path.basename(sys.argv[0])}: the anchor of a variant is not (once) in {source}/{file}: {anchor!r}")
        with open(path, "w") as f:
            f.write(text.replace(anchor, replacement))
    return root


def run(a, shader_dir, out, plan_ahead=False):
    baseline = f"burley-{a.spp_budget}"
    cmd = [os.path.join(a.build, "bin", "emcv-demo"), "--scene", a.scene, "--size", a.size, "--frames",
           str(a.frames), "--method", f"{baseline},{a.method}", "--spp-budget", str(a.spp_budget), "--resolve",
           "none", "--no-frames", "--out", out, "--define", f"EMCV_HISTORY_PLAN_AHEAD={int(plan_ahead)}"]
    subprocess.run(cmd, check=True, capture_output=True, text=True, env=dict(os.environ, EMCV_SHADER_DIR=shader_dir))
    with open(os.path.join(out, "metrics.json")) as f:
        m = json.load(f)
    times, clock = {}, m.get("timing", "?")
    for r in m["rows"]:
        if r["frame"] < a.first:
            continue
        for p in r["passes"]:
            if p["name"].startswith("sss"):
                times.setdefault((r["method"], p["name"]), []).append(p["ms"])
    base = statistics.median(times[(baseline, "sss-burley")])
    ratio = {name: statistics.median(v) / base for (method, name), v in times.items() if method == a.method}
    return ratio, base, clock


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--scene", default="light-off")
    p.add_argument("--size", default="256x256")
    p.add_argument("--frames", type=int, default=16)
    p.add_argument("--first", type=int, default=4)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--spp-budget", type=int, default=8)
    p.add_argument("--method", default="cv")
    p.add_argument("--write-doc", action="store_true", help="replace the adaptive-overhead block of "
                                                            "docs/accuracy-vs-time.md")
    a = p.parse_args(argv)
    if a.rounds < 1 or a.first >= a.frames:
        sys.exit("adaptive_overhead.py: need --rounds >= 1 and --first < --frames")
    ratios = {v[0]: [] for v in VARIANTS}
    bases, clock = [], "?"
    with tempfile.TemporaryDirectory() as tmp:
        dirs = {name: make_variant(os.path.join(tmp, f"v{i}"), edits) for i, (name, _, edits) in enumerate(VARIANTS)}
        for k in range(a.rounds):
            for name, _, _ in VARIANTS:
                r, base, clock = run(a, dirs[name], os.path.join(tmp, "out"), plan_ahead=name == AS_BUILT_PLANNED)
                ratios[name].append(r)
                bases.append(base)
    lines = [f"{a.scene}, {a.size}, {a.method} at a budget of {a.spp_budget} beside burley-{a.spp_budget} (the same "
             f"emcv-demo run), frames {a.first}-{a.frames - 1}, {a.rounds} rounds interleaved, clock {clock}; "
             f"burley-{a.spp_budget}'s pass: median {statistics.median(bases):.3f} ms", "",
             f"| variant (one cut) | answers for | samples pass / burley-{a.spp_budget} | burley pass / "
             f"burley-{a.spp_budget} | both / burley-{a.spp_budget} |", "|---|---|---:|---:|---:|"]
    for name, answers, _ in VARIANTS:
        rs = ratios[name]
        s = statistics.median(r.get("sss-adaptive-samples", 0.0) for r in rs)
        b = statistics.median(r.get("sss-burley", 0.0) for r in rs)
        t = statistics.median(sum(r.values()) for r in rs)
        lines.append(f"| {name} | {answers} | {s:.2f} | {b:.2f} | {t:.2f} |")
    publish_table("\n".join(lines), a.write_doc, os.path.join(ROOT, "docs", "accuracy-vs-time.md"), "adaptive-overhead", "scripts/eval/adaptive_overhead.py", argv)


if __name__ == "__main__":
    main(sys.argv[1:])
