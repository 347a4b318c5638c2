# SPDX-License-Identifier: MIT
"""The resolve's noise box: how well one frame's noise estimate predicts the error, and what the box changes
(docs/frame.md, "The noise box").

The burley pass stores beside its estimate the ratio estimator's per-sample variance from its own samples
(include/emcv/port/sss.h, emcv_sss_noise), and the resolve narrows its clip box to EMCV_RESOLVE_NOISE_SIGMA
standard deviations of it around the current value (include/emcv/port/resolve.h, emcv_resolve_narrow_to_noise)
and takes up a history beyond that box, or one whose neighbourhood has shifted off this frame's, at a higher
weight (emcv_resolve_current_weight, emcv_resolve_shift_weight).
Two tables, each from variants of this tree's shaders (a copy of shaders/ with a text replacement, read through
EMCV_SHADER_DIR; the script refuses when an anchor is no longer in the shader):

  calibration  the resolve made to write, instead of its image, the predicted standard deviation of the current
               luma (the noise box's luma half-width over EMCV_RESOLVE_NOISE_SIGMA, display units; 0 where the
               frame had no noise box), frames 5-39 of still scenes (`static`, the skin close-up before its
               switch), 96x96; against it, per pixel over the frames with a box, the root mean square of the raw
               frame's luma error against the reference (noise and the estimator's bias) over that of the
               prediction, for the pixels whose prediction is at least 2/3 of an 8-bit step (below that the 8-bit
               rounding is the error). The ratio's median and 10th-90th percentiles, and the share of the (frame,
               pixel) with a box whose error exceeds 3 predicted standard deviations.
  cost         the burley pass's and the resolve pass's times (wall clock, llvmpipe: work, not GPU time) as built
               and without the noise (the pass's estimate of it not stored, so its three sums are dead code, and
               the resolve neither loads nor applies it): `static` at 256x256, burley-8 and cv at a budget of 8,
               5 rounds alternating the two, each pass's median over frames 4-29, the median round.
  effect       resolve_table.py's PSNR columns (whole frame; "before" frames 20 up to the first light change,
               "after" its 30 frames), 96x96, the adaptive methods at a budget of 8, for four resolves: without
               the noise box (neither its narrowing nor its weight), with the box carried through the display
               encoding upwards only and the blend's weight everywhere (the resolve up to commit 39ee210), sized
               both ways with a history beyond it taken up at emcv_resolve_current_weight's weight (the resolve
               of commit 3679e5a), also a neighbourhood shifted off this frame taken up at
               emcv_resolve_shift_weight's (commit ae169b5), and as built (where the frame's noise is unknown, the
               neighbourhood's box from the neighbours on the pixel's own surface alone).

    /usr/bin/python3 scripts/eval/resolve_noise.py [--build build] [--write-doc]

With --write-doc the tables replace the GENERATED blocks "resolve-noise-calibration", "resolve-noise-cost" and
"resolve-noise-effect" of docs/frame.md.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

import numpy as np
from matplotlib import image as mpimg

from adaptive_overhead import make_variant
from resolve_table import mean, number, run_scene
from run_eval import git_commit, replace_block, write_atomically

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RESOLVE = "render/resolve.comp.glsl"
BOX = "        bool noise_box = !jitters() && noise_extent(p, local, current, extent);\n"
NARROW = "        if (noise_box) emcv_resolve_narrow_to_noise(current, extent, lo, hi);\n"
# Where this frame's noise is unknown, the neighbourhood's box from all nine neighbours, whatever surface they show
# (as up to commit ae169b5), not from those on the pixel's own surface (same_surface_moments).
ALL_NEIGHBOURS = [(RESOLVE, "        if (!jitters() && !noise_box) {\n", "        if (false) {\n")]
# No noise box at all (and so no box from the own surface where the noise is unknown, which is every pixel then).
NO_BOX = [(RESOLVE, BOX, "        bool noise_box = false;\n")] + ALL_NEIGHBOURS
# The current value's weight raised where the history lay beyond the box (emcv_resolve_current_weight) undone.
BLEND_ONLY = [(RESOLVE, "        float weight = noise_box ? emcv_resolve_current_weight(history, current, extent) : float(EMCV_RESOLVE_BLEND);\n",
               "        float weight = float(EMCV_RESOLVE_BLEND);\n")]
# The current value's weight where the history's neighbourhood moved off this frame's (emcv_resolve_shift_weight) undone.
NO_SHIFT = [(RESOLVE, "        if (noise_box && history_mean_known)\n"
                      "            weight = max(weight, emcv_resolve_shift_weight(sum / 9.0f - history_mean, extent, 9.0f));\n", "")]
# The box carried through the display encoding upwards only (as up to commit 39ee210).
UPWARDS = [(RESOLVE, "    extent = emcv_resolve_noise_extent(resolved_part(p) * exposure, emcv_ycocg_to_rgb(current), deviation * exposure,\n"
                     "                                       int(frame.ambient.w));\n",
            "    extent = emcv_resolve_ycocg_extent(emcv_display_encode((resolved_part(p) + deviation) * exposure,\n"
            "                                       int(frame.ambient.w)) - emcv_ycocg_to_rgb(current));\n")]
PREDICTION = [
    (RESOLVE, "    vec3 resolved = current;\n", "    vec3 resolved = current;\n    float predicted = 0.0f;\n"),
    (RESOLVE, NARROW, "        if (noise_box) predicted = extent.x / float(EMCV_RESOLVE_NOISE_SIGMA);\n"),
    (RESOLVE, "    imageStore(resolved_out, p, vec4(clamp(shown, 0.0f, 1.0f), 1.0f));",
     "    imageStore(resolved_out, p, vec4(clamp(vec3(predicted * float(PREDICTION_GAIN)), 0.0f, 1.0f), 1.0f));"),
    (RESOLVE, "#version 450 core\n", "#version 450 core\n#define PREDICTION_GAIN 20\n"),
]
PREDICTION_GAIN = 20.0  # the predicted deviation is stored x20 in the 8-bit image: 1/255 resolves 0.0002
SCENES = "demo/scenes/"
CALIBRATION = [  # (scene, methods, extra arguments); frames 5-39, before any light change
    ("static", "burley-8", []),
    ("static", "burley-32", []),
    ("static", "cv", ["--spp-budget", "8"]),
    (SCENES + "validation/skin-close.json", "burley-8", []),
    (SCENES + "validation/skin-close.json", "cv", ["--spp-budget", "8"]),
]
CALIBRATION_FRAMES = range(5, 40)
EFFECT_SCENES = ["static", "light-off", SCENES + "variations/burst-3.json", SCENES + "variations/camera-switch.json",
                 SCENES + "variations/fade.json", "moving", SCENES + "validation/skin-close.json",
                 SCENES + "validation/skin-orbit.json", SCENES + "validation/mixed-off.json", "flicker", "club"]
NO_NOISE = [
    ("render/sss_burley.comp.glsl", "    float noise = keeps_noise ? emcv_sss_noise(sum_w, sum_w2, sum_w2l, sum_w2l2, scattered, n) : 1.0f;\n",
     "    float noise = 1.0f;\n"),
    (RESOLVE, "        if (!jitters()) tile_noise[i] = noise_at(q);\n", ""),
] + NO_BOX
COST_ROUNDS = 5
COST_PASSES = ["sss-burley", "resolve"]
EFFECT_METHODS = ["diffuse", "burley-8", "separable-17", "spvg", "cv", "cv-notex"]


def luma(image):
    return 0.25 * image[..., 0] + 0.5 * image[..., 1] + 0.25 * image[..., 2]


def load(path):
    return np.asarray(mpimg.imread(path), dtype=np.float64)[..., :3]


def calibration_row(build, shader_dir, case, out):
    scene, method, extra = case
    path = os.path.join(ROOT, scene) if scene.startswith(SCENES) else scene
    cmd = [os.path.join(build, "bin", "emcv-demo"), "--scene", path, "--size", "96x96", "--frames",
           str(CALIBRATION_FRAMES.stop), "--method", method + ",reference", "--resolve", "taa", "--out", out] + extra
    done = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, EMCV_SHADER_DIR=shader_dir))
    if done.returncode != 0:
        sys.exit(f"resolve_noise.py: {' '.join(cmd)} failed:\n{done.stderr}")
    errors, predicted = [], []
    for f in CALIBRATION_FRAMES:
        reference = luma(load(os.path.join(out, "reference", f"frame-{f:04d}.png")))
        errors.append(luma(load(os.path.join(out, method, f"frame-{f:04d}.png"))) - reference)
        predicted.append(load(os.path.join(out, method, f"resolved-{f:04d}.png"))[..., 0] / PREDICTION_GAIN)
    errors, predicted = np.stack(errors), np.stack(predicted)
    # A frame predicts at a pixel where its noise box applied (0 where it did not: fewer than two effective
    # samples); a pixel is kept where its boxes' mean prediction is at least 2/3 of an 8-bit step.
    boxed = predicted > 0.0
    frames = np.maximum(boxed.sum(axis=0), 1)
    mean_square = lambda a: np.where(boxed, a ** 2, 0.0).sum(axis=0) / frames
    kept = (boxed.sum(axis=0) > 0) & (np.sqrt(mean_square(predicted)) >= (2.0 / 3.0) / 255.0)
    ratio = np.sqrt(mean_square(errors))[kept] / np.sqrt(mean_square(predicted))[kept]
    beyond = (np.abs(errors) > 3.0 * predicted)[:, kept][boxed[:, kept]]
    name = os.path.basename(scene).replace(".json", "")
    budget = f" (budget {extra[1]})" if extra else ""
    return (f"| {name} | {method}{budget} | {int(kept.sum())} | {np.median(ratio):.2f} | "
            f"{np.percentile(ratio, 10):.2f}-{np.percentile(ratio, 90):.2f} | {100.0 * beyond.mean():.2f}% |")


def pass_medians(build, shader_dir, out):
    """Per (method, pass): the median over frames 4-29 of the pass's time on `static`, 256x256, 30 frames."""
    cmd = [os.path.join(build, "bin", "emcv-demo"), "--scene", "static", "--size", "256x256", "--frames", "30",
           "--method", "burley-8,cv", "--spp-budget", "8", "--resolve", "taa", "--timing", "wall", "--no-frames",
           "--out", out]
    done = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, EMCV_SHADER_DIR=shader_dir))
    if done.returncode != 0:
        sys.exit(f"resolve_noise.py: {' '.join(cmd)} failed:\n{done.stderr}")
    with open(os.path.join(out, "metrics.json")) as f:
        rows = json.load(f)["rows"]
    times = {}
    for r in rows:
        if r["frame"] < 4:
            continue
        for entry in r["passes"]:
            times.setdefault((r["method"], entry["name"]), []).append(entry["ms"])
    return {k: statistics.median(v) for k, v in times.items()}


def cost_table(build, dirs, tmp):
    rounds = {name: [] for name in dirs}
    for k in range(COST_ROUNDS):
        for name, shader_dir in (dirs.items() if k % 2 == 0 else reversed(list(dirs.items()))):
            rounds[name].append(pass_medians(build, shader_dir, os.path.join(tmp, f"cost-{name}-{k}")))
    lines = ["| method | pass | without the noise (ms) | as built (ms) | as built / without |", "|---|---|---:|---:|---:|"]
    for method in ("burley-8", "cv"):
        for name in COST_PASSES:
            without = statistics.median(r[(method, name)] for r in rounds["without"])
            built = statistics.median(r[(method, name)] for r in rounds["as built"])
            lines.append(f"| {method} | {name} | {without:.3f} | {built:.3f} | {built / without:.2f} |")
    return "\n".join(lines)


def effect_rows(build, shader_dirs, scene, tmp):
    """Per method: raw, without the box, as built, for the frames before the first light change and after it."""
    runs = {}
    for name, shader_dir in shader_dirs.items():
        os.environ["EMCV_SHADER_DIR"] = shader_dir
        runs[name] = run_scene(build, os.path.join(ROOT, scene) if scene.startswith(SCENES) else scene,
                               EFFECT_METHODS, "96x96", 8, os.path.join(tmp, name, os.path.basename(scene)))
    del os.environ["EMCV_SHADER_DIR"]
    change = runs["as built"][1]
    rows = []
    for m in EFFECT_METHODS:
        cells = []
        for before in (True, False):
            raw = None
            values = []
            for name in shader_dirs:
                rs, _ = runs[name]
                frames = sorted({int(r["frame"]) for r in rs})
                span = ([f for f in frames if f >= 20 and (change is None or f < change)] if before else
                        [f for f in frames if change is not None and change <= f < change + 30])
                own = {int(r["frame"]): r for r in rs if r["method"] == m}
                raw = mean([number(own[f]["psnr_db"]) for f in span if f in own])
                values.append(mean([number(own[f]["psnr_resolved_db"]) for f in span if f in own]))
            cells += ["-" if v is None else f"{v:.2f}" for v in [raw] + values]
        rows.append(f"| {os.path.basename(scene).replace('.json', '')} | {m} | " + " | ".join(cells) + " |")
    return rows


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--write-doc", action="store_true", help="replace the resolve-noise-* blocks of docs/frame.md")
    a = p.parse_args(argv)
    commit = git_commit()  # before this script writes its own doc (which would read as -dirty)
    tables = []
    with tempfile.TemporaryDirectory() as tmp:
        predicting = make_variant(os.path.join(tmp, "prediction"), PREDICTION)
        lines = ["| scene | method | pixels | measured / predicted deviation, median | 10th-90th percentile | "
                 "beyond 3 predicted deviations |", "|---|---|---:|---:|---:|---:|"]
        for k, case in enumerate(CALIBRATION):
            lines.append(calibration_row(a.build, predicting, case, os.path.join(tmp, f"calibration{k}")))
        tables.append(("resolve-noise-calibration", "\n".join(lines)))

        costs = {"without": make_variant(os.path.join(tmp, "no-noise"), NO_NOISE), "as built": os.path.join(ROOT, "shaders")}
        tables.append(("resolve-noise-cost", cost_table(a.build, costs, tmp)))

        dirs = {"without": make_variant(os.path.join(tmp, "without"), NO_BOX),
                "upwards": make_variant(os.path.join(tmp, "upwards"), UPWARDS + BLEND_ONLY + NO_SHIFT + ALL_NEIGHBOURS),
                "no shift": make_variant(os.path.join(tmp, "no-shift"), NO_SHIFT + ALL_NEIGHBOURS),
                "all neighbours": make_variant(os.path.join(tmp, "all-neighbours"), ALL_NEIGHBOURS),
                "as built": os.path.join(ROOT, "shaders")}
        variants = ("without the box", "the box sized upwards, the blend's weight", "sized both ways, its weight beyond it",
                    "and the shift's weight", "as built: unknown noise, its own surface's box")
        lines = ["| scene | method | raw before | " + " | ".join(f"resolved before: {v}" for v in variants) +
                 " | raw after | " + " | ".join(f"resolved after: {v}" for v in variants) + " |",
                 "|---|---|" + "---:|" * (2 + 2 * len(variants))]
        for scene in EFFECT_SCENES:
            lines += effect_rows(a.build, dirs, scene, tmp)
        tables.append(("resolve-noise-effect", "\n".join(lines)))
    command = " ".join(["/usr/bin/python3 scripts/eval/resolve_noise.py"] + argv)
    doc = os.path.join(ROOT, "docs", "frame.md")
    for name, table in tables:
        print(table)
        if a.write_doc:
            with open(doc) as f:
                text = f.read()
            write_atomically(doc, replace_block(text, name, f"Regenerated by `{command}`, made at commit {commit}.\n\n{table}", doc))


if __name__ == "__main__":
    main(sys.argv[1:])
