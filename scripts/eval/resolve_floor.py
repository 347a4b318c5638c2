# SPDX-License-Identifier: MIT
"""What a moving camera lets any fixed-weight resolve gain: the history's per-frame resampling error against this
frame's noise (docs/frame.md, "Known limits").

A resolve that blends a reprojected history h with this frame's value x at weight w, h' = w x + (1 - w) R(h), where
the reprojection R adds an error of variance e^2 that differs from frame to frame (an interpolated point-sampled
image errs by the fractional offset, which the camera changes every frame), holds after its warm-up

    MSE(w) = sigma^2 w / (2 - w) + e^2 (1 - w)^2 / (w (2 - w))

(sigma^2: the raw frame's error; both terms are the stationary variance of an exponential filter of weight w fed
independent errors, the second fed after each step's (1 - w)). The first falls with w, the second rises: the best
weight gains at most 10 log10(sigma^2 / min_w MSE(w)) dB, and that reaches 6 dB only where e^2 is at least 10.7 dB
under sigma^2 (min_w MSE(w) = sigma^2 / 10^0.6 at e^2 / sigma^2 = 0.084, solved by bisection below).

Measured per scene (128x128, frames 10-39 of 40, PSNR of the whole frame against the reference, mean over frames):
e^2 from `burley-256` (nearly noise free) under a fixed blend at w = 0.5 (resolve_motion.py's PLAIN variant of the
shaders: no clip and no weight rule, the history still moved by the guide as built), less its own noise's share
sigma_256^2 / 3; the model's curve for `burley-8` under the same fixed blend at w = 0.5, 0.25 and 0.1 beside the
measured one; the model's best weight and gain; and the gain of the resolve as built (its box, guide
and weights). `moving` orbits about 5 px a frame, the validation scene `cow-orbit` about 1 px a frame.

    /usr/bin/python3 scripts/eval/resolve_floor.py [--build build] [--write-doc]

With --write-doc the table replaces the GENERATED block "resolve-floor" of docs/frame.md.
"""
import argparse
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from adaptive_overhead import make_variant  # noqa: E402
from resolve_motion import PLAIN, run  # noqa: E402
from run_eval import publish_table  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = ["moving", "demo/scenes/validation/cow-orbit.json"]
SIZE, FRAMES, FIRST = "128x128", 40, 10
NOISY, CLEAN = "burley-8", "burley-256"
WEIGHTS = [0.5, 0.25, 0.1]
SIX_DB = 10 ** -0.6  # the MSE ratio of a 6 dB gain


def to_mse(db):
    return 10 ** (-db / 10)


def to_db(mse):
    return -10 * math.log10(mse)


def model(sigma2, e2, w):
    """MSE of the blend at weight w (module text)."""
    return sigma2 * w / (2 - w) + e2 * (1 - w) ** 2 / (w * (2 - w))


def best_weight(sigma2, e2):
    """The weight in (0, 1) that minimises model(): a golden-section search (the model is convex in w there)."""
    lo, hi = 1e-4, 1.0 - 1e-4
    g = (math.sqrt(5) - 1) / 2
    for _ in range(100):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if model(sigma2, e2, a) < model(sigma2, e2, b):
            hi = b
        else:
            lo = a
    return (lo + hi) / 2


def six_db_ratio():
    """The largest e^2 / sigma^2 at which the best weight still gains 6 dB (bisection; the best MSE rises with it)."""
    lo, hi = 0.0, 1.0
    for _ in range(60):
        r = (lo + hi) / 2
        if model(1.0, r, best_weight(1.0, r)) > SIX_DB:
            hi = r
        else:
            lo = r
    return lo


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--write-doc", action="store_true")
    a = ap.parse_args(argv)
    ratio = six_db_ratio()
    lines = [f"{SIZE}, frames {FIRST}-{FRAMES - 1}, PSNR (dB, whole frame); e^2 from `{CLEAN}` under the fixed blend at "
             f"0.5 (no clip, the guide as built); a 6 dB gain needs e^2 at least {to_db(ratio):.1f} dB under the raw frame's error "
             f"(e^2 / sigma^2 <= {ratio:.3f}).", "",
             f"| scene | e^2 (dB) | `{NOISY}` raw | e^2 under raw (dB) | fixed 0.5: model / measured | "
             "fixed 0.25 | fixed 0.1 | best weight (model) | its gain | as built: gain |",
             "|---|---:|---:|---:|---|---|---|---:|---:|---:|"]
    methods = [NOISY, CLEAN]
    with tempfile.TemporaryDirectory() as tmp:
        fixed = os.path.join(tmp, "shaders")
        make_variant(fixed, PLAIN)
        for scene in SCENES:
            def demo(shader_dir, defines):
                with tempfile.TemporaryDirectory(dir=tmp) as out:
                    return run(a.build, SIZE, shader_dir, defines, out, scene, methods, FRAMES, FIRST)
            measured = {w: demo(fixed, [f"EMCV_RESOLVE_BLEND={w}"]) for w in WEIGHTS}
            built = demo(os.path.join(ROOT, "shaders"), [])
            clean_raw, clean_fixed = measured[0.5][CLEAN]
            e2 = (to_mse(clean_fixed) - to_mse(clean_raw) * 0.5 / 1.5) / (0.25 / 0.75)
            if not e2 > 0:
                sys.exit(f"resolve_floor: {scene}: {CLEAN}'s fixed blend is not worse than its own noise allows")
            raw = built[NOISY][0]
            sigma2 = to_mse(raw)
            cells = [f"{to_db(model(sigma2, e2, w)):.2f} / {measured[w][NOISY][1]:.2f}" for w in WEIGHTS]
            w = best_weight(sigma2, e2)
            name = os.path.splitext(os.path.basename(scene))[0]
            lines.append(f"| {name} | {to_db(e2):.1f} | {raw:.2f} | {to_db(e2) - raw:.1f} | " + " | ".join(cells) +
                         f" | {w:.2f} | {to_db(model(sigma2, e2, w)) - raw:+.2f} | {built[NOISY][1] - raw:+.2f} |")
    publish_table("\n".join(lines), a.write_doc, os.path.join(ROOT, "docs", "frame.md"), "resolve-floor",
                  "scripts/eval/resolve_floor.py", argv)


if __name__ == "__main__":
    main(sys.argv[1:])
