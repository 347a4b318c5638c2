#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""cv's allocation after a light change: without the level's bias and the tile's noise test, with the level's
bias only, as built (both), with the pixel's light's change counted too, with the noise test's first ratio freed of
the moving mean's error, with the trust or the whole history of a tile cut where its noise test fires, and with
every history restarted at the change (docs/renderer.md, "After a change: the stale allocation").

After a light change a pixel's per-sample variance still holds the old light's noise, which its exponential
memory forgets at 1 - eta = 0.8 a frame, and the budget keeps following it. Each variant is this tree with a text
replacement in include/emcv/port/history.h (a copy read through EMCV_INCLUDE_DIR) or in
shaders/adaptive/samples.comp.glsl or shaders/adaptive/history_io.h (through EMCV_SHADER_DIR); the script refuses when an anchor is no longer there:

- neither: cv's push never lowers the count and never rescales the comoments (the rule before either was built).
- the level's bias: where f's level moves beyond 5 sigma, the push lowers the history's count to the frames its
  level's bias leaves (emcv_history_push_cv, emcv_history_level_bias), and the budget's shrinkage weighs it by
  them; no noise test (emcv_history_noise_ratio always 1).
- as built: the level's bias and the tile's noise test: each pixel's n e^2 / sigma^2 before its push, averaged over
  its 8x8 tile's scattering pixels, estimates the ratio of the noise now to the history's; where it says the
  noise fell (beyond its sampling variance), the comoments are scaled by the ratio (emcv_history_noise_term,
  emcv_history_noise_ratio, emcv_history_rescale_cv).
- + the pixel's light: as built, and also, under the model "a pixel's noise follows its light", a history
  measured under the light mu_G and spent under this frame's G is off by the relative amount
  delta = (G / mu_G)^2 - 1 (G and mu_G in the tracked display gamma, where the noise of a light scaled by k scales
  by k as G does). The pool's bias (the mean of its pixels' delta) enters the estimate's relative mean squared
  error beside its sampling variance, r / K + delta^2, i.e. the shrinkage weighs 1 / (1 / K + delta^2 / r)
  frames. Unlike the level's bias it is known before the frame is sampled (G is this frame's). delta is 0
  wherever the light is still; it is capped at 1000 (a light switched on where mu_G was 0).
- the mean's error taken out: as built, except that the pool's mean term is read less the part the moving mean's
  own error adds to it, eta / (2 - eta) (the history's means are exponential averages of the old noise), and
  where the ratio it then gives is under that same eta / (2 - eta) (the kept means would hold more error than this
  frame's values) the means restart at this frame's (f, G) after the rescale.
- trust cut where it fires: as built, and where the tile's ratio is under 1 the count is lowered to 2 effective
  frames (emcv_history_count_for_frames), so that the budget's shrinkage pulls the rescaled variance towards the
  frame's mean until new frames come in; the comoments still forget at 1 - eta.
- restarted where it fires: as built, and where the tile's ratio is under 1 every pixel of the tile that took samples
  starts a fresh history with this frame (what the oracle below does at the change, but wherever and whenever the
  noise test says the noise fell).
- restarted at the change (an oracle: it knows the frame): as built, and every history starts fresh at frame
  CHANGE_FRAME, the first change of each scene that has one there; for scenes without a change at that frame it
  is left out.

Cells are cv - burley-B in dB over the window of each row (the raw display image against the reference, the mean
over frames of each frame's dB), the mean over the seeds; 96x96, --resolve none, --spp-budget B. burley-B does
not read the adaptive shaders and runs once per scene, budget and seed.

Usage: /usr/bin/python3 scripts/eval/stale_allocation.py [--build build] [--seeds 1,2] [--write-doc]
With --write-doc the table replaces the GENERATED block "stale-allocation" of docs/renderer.md.
"""
import csv
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

from adaptive_overhead import make_variant, variant_study_arguments
from run_eval import publish_table

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SAMPLES = "adaptive/samples.comp.glsl"
PLANNING = "adaptive/samples.h"  # the reprojection and the pooling, shared with the quality target's burley pass
HISTORY = "emcv/port/history.h"
CHANGE_FRAME = 30
SIZE = "96x96"
BUDGETS = (8, 16)

# The light-change bias: each pixel's delta from its kept history's mean of G and this frame's G, pooled as the
# 3x3 mean over the pixels that have a variance, squared, added to the relative error r / K of the pooled estimate.
BIAS = [
    (PLANNING, "shared float tile_frames[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];  // effective frames of each variance\n",
     "shared float tile_frames[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];  // effective frames of each variance\n"
     "shared float tile_bias[EMCV_RENDER_TILE_SIZE * EMCV_RENDER_TILE_SIZE];\nfloat own_bias = 0.0f;\nfloat pooled_bias = 0.0f;\n"),
    (PLANNING, "    return emcv_adaptive_state_sigma2(emcv_adaptive_sub_pixel(p, code), s, frames);\n",
     "    if (s.count >= 2u) {\n"
     "        float now = emcv_adaptive_tracked(texelFetch(gbuffer_albedo, p, 0).xyz, texelFetch(lit_diffuse, p, 0).xyz);\n"
     "        if (s.mean.y > 1e-6f) own_bias = min((now / s.mean.y) * (now / s.mean.y) - 1.0f, 1e3f);\n"
     "        else if (now > 1e-6f) own_bias = 1e3f;\n"
     "    }\n"
     "    return emcv_adaptive_state_sigma2(emcv_adaptive_sub_pixel(p, code), s, frames);\n"),
    (PLANNING, "    float inverse_frames = 0.0f;\n", "    float inverse_frames = 0.0f;\n    float bias_sum = 0.0f;\n"),
    (PLANNING, "            emcv_history_pool_add(sum, count, tile_sigma2[i]);\n",
     "            emcv_history_pool_add(sum, count, tile_sigma2[i]);\n"
     "            if (tile_sigma2[i] >= 0.0f) bias_sum += tile_bias[i];\n"),
    (PLANNING, "    pooled_frames = emcv_history_pool_frames(count, inverse_frames);\n",
     "    pooled_frames = emcv_history_pool_frames(count, inverse_frames);\n"
     "    pooled_bias = count > 0u ? bias_sum / float(count) : 0.0f;\n"),
    (PLANNING, "        emcv_budget_add_raw(sigma2, frames);\n",
     "        emcv_budget_add_raw(sigma2, frames);\n"
     "        if (frames > 0.0f) frames = 1.0f / (1.0f / frames + pooled_bias * pooled_bias / emcv_history_spend_relative_variance());\n"),
    (PLANNING, "    tile_frames[here] = frames;\n", "    tile_frames[here] = frames;\n    tile_bias[here] = own_bias;\n"),
]
RESTART = [
    (PLANNING, "    if (emcv_adaptive_reproject(p, code, a, b, s, resampled) && !resampled) {\n",
     f"    if (frame.counters.x == {CHANGE_FRAME}u) {{\n        s = emcv_adaptive_init();\n"
     "        emcv_adaptive_store(p, s);\n    } else if (emcv_adaptive_reproject(p, code, a, b, s, resampled) && !resampled) {\n"),
]
UPDATE = "adaptive/history_io.h"
RESCALE = "    emcv_history_rescale_cv(s, noise_ratio);\n"
MEAN_ERROR = "(EMCV_HISTORY_ETA_EMCM / (2.0f - EMCV_HISTORY_ETA_EMCM))"
MEAN_ERROR_OUT_RATIO = [(HISTORY, "    EMCV_PRECISE float z = float(pool.x) * (1.0f / 65536.0f) / m;\n",
                         f"    EMCV_PRECISE float z = float(pool.x) * (1.0f / 65536.0f) / m - {MEAN_ERROR};\n")]
MEAN_ERROR_OUT_MEANS = [(UPDATE, RESCALE, RESCALE + f"    if (noise_ratio < {MEAN_ERROR}) s.mean = vec2(f, g);\n")]
TRUST_CUT = [(UPDATE, RESCALE, RESCALE + "    if (noise_ratio < 1.0f)\n"
              "        s.count = emcv_history_count_for_frames(s.count, EMCV_HISTORY_ETA_EMCM, 2.0f);\n")]
RESTART_FIRED = [(UPDATE, RESCALE, RESCALE + "    if (noise_ratio < 1.0f) {\n        s = emcv_adaptive_init();\n"
                  "        emcv_history_push_cv(s, f, g, EMCV_HISTORY_ETA_EMCM, float(n));\n    }\n")]
NO_LEVEL_BIAS = [(HISTORY, "        s.count = emcv_history_count_for_frames(s.count, eta, trusted);\n",
                  "")]
NO_NOISE_TEST = [(HISTORY, "    if (pool.z == 0u) return 1.0f;\n    float m = float(pool.z);\n",
                  "    return 1.0f;\n    float m = float(pool.z);\n")]
# (name, shader edits, include edits)
VARIANTS = [("neither", [], NO_LEVEL_BIAS + NO_NOISE_TEST), ("the level's bias", [], NO_NOISE_TEST),
            ("as built: + the tile's noise test", [], []), ("+ the pixel's light", BIAS, []),
            ("the mean's error taken out", MEAN_ERROR_OUT_MEANS, MEAN_ERROR_OUT_RATIO),
            ("trust cut where it fires", TRUST_CUT, []), ("restarted where it fires", RESTART_FIRED, []),
            ("restarted at the change (oracle)", RESTART, [])]
ORACLE = VARIANTS[-1][0]
BUILT = VARIANTS[2][0]  # burley-B reads no adaptive shader: it runs once, under this variant

# (scene file under demo/scenes, frames, window (first, last) averaged, change at CHANGE_FRAME, window name)
CASES = [
    ("static.json", 60, (10, 59), False, "frames 10-59"),
    ("light-off.json", 60, (30, 59), True, "30 after the switch"),
    ("variations/long-off.json", 330, (60, 329), True, "frames 60-329"),
    ("variations/switch-half.json", 60, (30, 59), True, "30 after the switch"),
    ("variations/switch-dim.json", 60, (30, 59), True, "30 after the switch"),
    ("variations/switch-on.json", 60, (30, 59), True, "30 after the switch"),
    ("variations/burst-1.json", 60, (30, 59), True, "30 from the burst"),
    ("variations/burst-3.json", 60, (30, 59), True, "30 from the burst"),
    ("variations/camera-switch.json", 60, (30, 59), True, "30 after the switch"),
    ("variations/fade.json", 51, (21, 50), False, "30 from the fade's start"),
    ("flicker.json", 72, (10, 71), False, "frames 10-71"),
    ("moving.json", 60, (10, 59), False, "frames 10-59"),
    ("validation/skin-close.json", 60, (30, 59), True, "30 after the switch"),
    ("validation/skin-orbit.json", 60, (30, 59), True, "30 after the switch"),
]


def run(build, dirs, scene, frames, budget, seed, method, out):
    shader_dir, include_dir = dirs
    cmd = [os.path.join(build, "bin", "emcv-demo"), "--scene", os.path.join(ROOT, "demo", "scenes", scene), "--size",
           SIZE, "--frames", str(frames), "--method", method, "--spp-budget", str(budget), "--seed", str(seed),
           "--resolve", "none", "--no-frames", "--out", out,
           # the variants edit the samples pass's planning: it runs every frame (the as-built images are the same
           # bit for bit with the burley pass planning still frames, docs/renderer.md "Planning the next frame")
           "--define", "EMCV_HISTORY_PLAN_AHEAD=0"]
    done = subprocess.run(cmd, capture_output=True, text=True,
                          env=dict(os.environ, EMCV_SHADER_DIR=shader_dir, EMCV_INCLUDE_DIR=include_dir))
    if done.returncode != 0:
        sys.exit(f"stale_allocation.py: {' '.join(cmd)} failed:\n{done.stderr}")
    with open(os.path.join(out, "metrics.csv")) as f:
        return {int(r["frame"]): float(r["psnr_db"]) for r in csv.DictReader(f) if r["method"] == method}


def main(argv):
    a = variant_study_arguments(argv, __doc__, "1,2", "stale-allocation")
    seeds = a.seeds
    with tempfile.TemporaryDirectory() as tmp:
        dirs = {name: (make_variant(os.path.join(tmp, f"v{i}"), shaders),
                       make_variant(os.path.join(tmp, f"i{i}"), includes, "include"))
                for i, (name, shaders, includes) in enumerate(VARIANTS)}
        jobs = []
        for k, (scene, frames, _, change, _) in enumerate(CASES):
            for budget in BUDGETS:
                for seed in seeds:
                    jobs.append((k, budget, seed, f"burley-{budget}", BUILT))
                    jobs.extend((k, budget, seed, "cv", name) for name, _, _ in VARIANTS if change or name != ORACLE)

        def one(i):
            k, budget, seed, method, name = jobs[i]
            scene, frames = CASES[k][0], CASES[k][1]
            return run(a.build, dirs[name], scene, frames, budget, seed, method, os.path.join(tmp, f"out{i}"))

        with ThreadPoolExecutor(a.jobs) as pool:
            psnr = dict(zip(jobs, pool.map(one, range(len(jobs)))))
    lines = ["| scene | window | B | " + " | ".join(n for n, _, _ in VARIANTS) + " |", "|---|---|---:|" + "---:|" * len(VARIANTS)]
    for k, (scene, frames, (first, last), change, window) in enumerate(CASES):
        for budget in BUDGETS:
            cells = []
            for name, _, _ in VARIANTS:
                if not change and name == ORACLE:
                    cells.append("-")
                    continue
                gaps = []
                for seed in seeds:
                    cv, burley = psnr[(k, budget, seed, "cv", name)], psnr[(k, budget, seed, f"burley-{budget}", BUILT)]
                    gaps.append(sum(cv[f] - burley[f] for f in range(first, last + 1)) / (last - first + 1))
                cells.append(f"{sum(gaps) / len(gaps):+.2f}")
            name = os.path.basename(scene).replace(".json", "")
            lines.append(f"| {name} | {window} | {budget} | " + " | ".join(cells) + " |")
    publish_table("\n".join(lines), a.write_doc, os.path.join(ROOT, "docs", "renderer.md"), "stale-allocation",
                  "scripts/eval/stale_allocation.py", argv)


if __name__ == "__main__":
    main(sys.argv[1:])
