#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The temporal resolve with and without camera jitter, against an anti-aliased reference (docs/frame.md,
"Jitter and an anti-aliased reference").

Without jitter a pixel samples the same point of the scene every frame, so the resolve can only average noise,
and under a moving camera it resamples a point-sampled history every frame (edges and fine relief blur). With
`--jitter` every frame samples another sub-pixel offset and the resolve accumulates the pixel's area: what it
converges to is the anti-aliased image, which a point-sampled reference does not show. This script makes that
reference outside the renderer: the `reference` method at SCALE times the size (per side), each frame's display
image (8-bit sRGB, what every PSNR column compares) averaged over SCALE x SCALE blocks, the box filter over the
pixel that a uniform sub-pixel jitter integrates. Each method is rendered at the size with `--resolve taa`, with
and without `--jitter`, and its raw and resolved frames are compared with that reference: PSNR of the whole
frame, the mean over frames FIRST.. of each frame's dB (frames before FIRST are the resolve's warm-up).

Usage: /usr/bin/python3 scripts/eval/jitter_aa.py [--build build] [--scenes static,moving] [--size 96x96]
           [--scale 4] [--budget 8] [--methods burley-8,spvg,cv,cv-notex] [--frames N] [--first 20] [--seed 1]
Prints one markdown table per scene.
"""
import argparse
import math
import os
import sys
import tempfile

import numpy as np
from matplotlib import image as mpimg

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import runner  # noqa: E402


def render(demo, out, scene, size, methods, extra, frames, seed):
    """One emcv-demo run writing its frames under `out` (runner.run_demo: a failed run stops with its stderr)."""
    command = [demo, "--scene", scene, "--size", size, "--method", ",".join(methods), "--seed", str(seed)] + extra
    if frames:
        command += ["--frames", str(frames)]
    runner.run_demo("jitter_aa.py", command + ["--out", out])


def load(path):
    """An 8-bit display image as floats in [0, 1], RGB."""
    return np.asarray(mpimg.imread(path), dtype=np.float64)[..., :3]


def box_down(image, scale):
    h, w = image.shape[0] // scale, image.shape[1] // scale
    return image[:h * scale, :w * scale].reshape(h, scale, w, scale, 3).mean(axis=(1, 3))


def psnr(a, b):
    mse = float(np.mean((a - b) ** 2))
    return math.inf if mse == 0.0 else 10.0 * math.log10(1.0 / mse)


def frame_count(folder):
    return len([f for f in os.listdir(folder) if f.startswith("frame-") and f.endswith(".png")])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--scenes", default="static,moving")
    parser.add_argument("--size", default="96x96")
    parser.add_argument("--scale", type=int, default=4)
    parser.add_argument("--budget", type=int, default=8)
    parser.add_argument("--methods", default=None)
    parser.add_argument("--frames", type=int, default=0)
    parser.add_argument("--first", type=int, default=20)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args(argv)
    if args.scale < 1:
        sys.exit("jitter_aa.py: --scale must be at least 1")
    demo = os.path.join(args.build, "bin", "emcv-demo")
    if not os.access(demo, os.X_OK):
        sys.exit(f"jitter_aa.py: no {demo} (build first)")
    width, height = (int(v) for v in args.size.split("x"))
    big = f"{width * args.scale}x{height * args.scale}"
    methods = args.methods.split(",") if args.methods else [f"burley-{args.budget}", "spvg", "cv", "cv-notex"]
    budget = ["--spp-budget", str(args.budget)]
    for scene in args.scenes.split(","):
        with tempfile.TemporaryDirectory() as tmp:
            render(demo, os.path.join(tmp, "ref"), scene, big, ["reference"], ["--resolve", "none"], args.frames,
                   args.seed)
            render(demo, os.path.join(tmp, "plain"), scene, args.size, methods, ["--resolve", "taa"] + budget,
                   args.frames, args.seed)
            render(demo, os.path.join(tmp, "jitter"), scene, args.size, methods, ["--resolve", "taa", "--jitter"] +
                   budget, args.frames, args.seed)
            frames = frame_count(os.path.join(tmp, "ref", "reference"))
            window = range(args.first, frames)
            references = {f: box_down(load(os.path.join(tmp, "ref", "reference", f"frame-{f:04d}.png")), args.scale)
                          for f in window}
            print(f"scene `{scene}`, {args.size}, frames {args.first}-{frames - 1}, the reference at {big} "
                  f"box-filtered {args.scale}x{args.scale}\n")
            print("| method | raw | resolved | gain | raw, jitter | resolved, jitter | gain, jitter |")
            print("|---|---:|---:|---:|---:|---:|---:|")
            for m in methods:
                cells = []
                for run in ("plain", "jitter"):
                    folder = os.path.join(tmp, run, m)
                    raw = np.mean([psnr(load(os.path.join(folder, f"frame-{f:04d}.png")), references[f]) for f in window])
                    res = np.mean([psnr(load(os.path.join(folder, f"resolved-{f:04d}.png")), references[f])
                                   for f in window])
                    cells += [f"{raw:.2f}", f"{res:.2f}", f"{res - raw:+.2f}"]
                print(f"| {m} | " + " | ".join(cells) + " |")
            print()


if __name__ == "__main__":
    main()
