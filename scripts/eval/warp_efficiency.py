#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Warp efficiency of the SSS sampling loop: how much of a warp's time its threads spend on samples.

The burley pass runs one 8x8 workgroup per SSS tile, one thread per pixel, each looping over its pixel's N
samples; a warp of W threads (W = 32 on NVIDIA: rows 0-3, then 4-7 of the tile, gl_LocalInvocationIndex =
x + 8 y) runs as long as its largest N. Efficiency = sum of N / (W x sum over warps of the warp's largest N),
over the warps of the tiles that hold an SSS pixel (the ones dispatched); 1 for a fixed count over full tiles.

Reads the per-pixel counts that emcv-eval dumps (--heatmaps) and prints a markdown row per method and frame:
the efficiency with the threads taking the tile's pixels in tile order, and with each tile's threads taking its
pixels in order of N (the smallest 32 counts in the first warp), for W = 32 (NVIDIA warps) and W = 8 (llvmpipe's
256-bit SIMD batches of 8 floats). The adaptive methods' burley pass runs the sorted order
(sss_burley.comp.glsl, sort_tile_by_count: a counting sort whose keys merge a few neighbouring N above 63, so
within a fraction of a sample of this model); burley-N, whose N is one count, runs tile order.

With --steady it answers instead how steady the sampling work is from frame to frame, at a budget B: for each
scene (--scenes) it renders burley-B and the adaptive methods side by side for --frames N frames and dumps every
frame's counts from --first on; per frame, the samples (sum of N over the SSS pixels) and the warp work (W = 32,
in the order the pass runs: 32 x the warp's largest N, summed over the dispatched warps), which is what a GPU's
sampling loop takes time for; per scene and method one markdown row: the SSS pixels' p95 / median over those frames (burley-B's
work follows them alone), then the median, p95 / median and max / median of each of the two. Deterministic: counts,
not clocks (llvmpipe's clock is too noisy to read a 10% spread). The tables as measured:
docs/notebook/2026-12-07-renderer-steady-work.md.

Usage: /usr/bin/python3 scripts/eval/warp_efficiency.py [--build build] [--scene light-off] [--size 128x128]
           [--frames 29,30,33,59] [--spp-budget 8 | --target-variance V] [--methods spvg,cv,cv-notex]
       /usr/bin/python3 scripts/eval/warp_efficiency.py --steady [--build build] [--size 128x128] [--frames 60]
           [--first 2] [--spp-budget 8] [--scenes light-off,...] [--methods spvg,cv,cv-notex]
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import ROOT  # noqa: E402

TILE = 8
STEADY_SCENES = ("static,light-off,flicker,club,moving,variations/burst-1,variations/burst-3,"
                 "variations/camera-switch,variations/fade,variations/switch-on")


def read_grid(path):
    with open(path) as f:
        rows = [[float(v) for v in line] for line in csv.reader(f)]
    return rows[::-1]  # bottom row first, as GL (tiles start at GL rows 0, 8, ...)


def efficiency(counts, mask, width, sort):
    height = len(counts)
    ws = {32: [0.0, 0.0], 8: [0.0, 0.0]}
    for ty in range(0, height, TILE):
        for tx in range(0, width, TILE):
            tile = [(counts[y][x] if mask[y][x] else 0.0) if y < height and x < width else 0.0
                    for y in range(ty, ty + TILE) for x in range(tx, tx + TILE)]
            inside = [mask[y][x] for y in range(ty, min(ty + TILE, height)) for x in range(tx, min(tx + TILE, width))]
            if not any(inside):
                continue  # not an SSS tile: never dispatched
            if sort:
                tile = sorted(tile)
            for w, acc in ws.items():
                for start in range(0, TILE * TILE, w):
                    warp = tile[start:start + w]
                    acc[0] += sum(warp)
                    acc[1] += w * max(warp)
    return {w: (acc[0] / acc[1] if acc[1] > 0 else 1.0) for w, acc in ws.items()}


def frame_work(counts_path, mask_path, sort):
    """(SSS pixels, samples, warp work at W = 32) of one frame's dumped counts, each tile's pixels handed to its
    threads in order of N (`sort`, the adaptive methods' burley pass) or in tile order."""
    import numpy as np
    counts = np.loadtxt(counts_path, delimiter=",", ndmin=2)[::-1]  # bottom row first, as GL
    mask = np.loadtxt(mask_path, delimiter=",", ndmin=2)[::-1] > 0
    counts = np.where(mask, counts, 0.0)
    h, w = counts.shape
    ph, pw = -h % TILE, -w % TILE  # the last tiles' pixels past the image edge take no samples
    counts = np.pad(counts, ((0, ph), (0, pw)))
    mask = np.pad(mask, ((0, ph), (0, pw)))
    th, tw = counts.shape[0] // TILE, counts.shape[1] // TILE
    # tiles x rows-of-4 (a 32-thread warp: rows 0-3, then 4-7 of the tile) x 32 threads
    tiles = counts.reshape(th, TILE, tw, TILE).transpose(0, 2, 1, 3).reshape(th, tw, TILE * TILE)
    if sort:
        tiles = np.sort(tiles, axis=2)
    warps = tiles.reshape(th, tw, 2, 32)
    dispatched = mask.reshape(th, TILE, tw, TILE).any(axis=(1, 3))  # tiles with an SSS pixel
    work = 32.0 * warps.max(axis=3).sum(axis=2)
    return int(mask.sum()), float(counts.sum()), float(work[dispatched].sum())


def spread(values):
    """(median, p95 / median, max / median) of a frame series (p95: numpy's linear interpolation)."""
    import numpy as np
    v = np.asarray(values, dtype=float)
    m = float(np.median(v))
    return m, float(np.percentile(v, 95)) / m, float(v.max()) / m


def steady(a):
    budget = a.spp_budget
    methods = [f"burley-{budget}"] + a.methods.split(",")
    frames = int(a.frames)
    dumped = list(range(a.first, frames))
    lines = [f"{a.size}, budget {budget} spp, frames {a.first}-{frames - 1}: `emcv-eval --scene SCENE --size {a.size} "
             f"--frames {frames} --method {','.join(methods)} --spp-budget {budget} --heatmaps {a.first},...,"
             f"{frames - 1} --heatmap-dir DIR`", "",
             "| scene | method | SSS pixels p95 / median | samples median | p95 / median | max / median "
             "| warp work (W=32) median | p95 / median | max / median |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for scene in a.scenes.split(","):
        path = os.path.join(ROOT, "demo", "scenes", scene + ".json")
        with tempfile.TemporaryDirectory() as d:
            cmd = [f"{a.build}/bin/emcv-eval", "--scene", path if "/" in scene else scene, "--size", a.size,
                   "--frames", str(frames), "--method", ",".join(methods), "--spp-budget", budget,
                   "--heatmaps", ",".join(str(f) for f in dumped), "--heatmap-dir", d]
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            for m in methods:
                per = [frame_work(f"{d}/{m}.f{f}.samples.csv", f"{d}/{m}.f{f}.mask.csv", not m.startswith("burley-"))
                       for f in dumped]
                pixels = spread([p[0] for p in per])
                samples = spread([p[1] for p in per])
                work = spread([p[2] for p in per])
                lines.append(f"| {scene} | {m} | {pixels[1]:.3f} | {samples[0]:.0f} | {samples[1]:.3f} | {samples[2]:.3f} "
                             f"| {work[0]:.0f} | {work[1]:.3f} | {work[2]:.3f} |")
    print("\n".join(lines))


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default="build")
    p.add_argument("--scene", default="light-off")
    p.add_argument("--size", default="128x128")
    p.add_argument("--frames", default=None, help="the frames dumped (default 29,30,33,59); --steady: frames rendered (default 60)")
    p.add_argument("--spp-budget", default="8")
    p.add_argument("--target-variance", default=None)
    p.add_argument("--methods", default="spvg,cv,cv-notex")
    p.add_argument("--steady", action="store_true", help="frame-to-frame spread of the samples and the warp work")
    p.add_argument("--first", type=int, default=2, help="--steady: the first frame counted (default 2)")
    p.add_argument("--scenes", default=STEADY_SCENES, help="--steady: built-in names or paths under demo/scenes without .json")
    a = p.parse_args(argv)
    if a.steady:
        if a.target_variance:
            p.error("--steady compares at a budget: not with --target-variance")
        a.frames = a.frames or "60"
        steady(a)
        return
    a.frames = a.frames or "29,30,33,59"
    frames = [int(f) for f in a.frames.split(",")]
    methods = a.methods.split(",")
    with tempfile.TemporaryDirectory() as d:
        cmd = [f"{a.build}/bin/emcv-eval", "--scene", a.scene, "--size", a.size, "--frames", str(max(frames) + 1),
               "--method", ",".join(methods), "--heatmaps", a.frames, "--heatmap-dir", d]
        cmd += ["--target-variance", a.target_variance] if a.target_variance else ["--spp-budget", a.spp_budget]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        width = int(a.size.split("x")[0])
        mode = f"target variance {a.target_variance}" if a.target_variance else f"budget {a.spp_budget} spp"
        shown = ["emcv-eval"] + ["DIR" if c == d else c for c in cmd[1:]]
        print(f"{a.scene}, {a.size}, {mode}: `{' '.join(shown)}`")
        print()
        print("| method | frame | W=32 tile order | W=32 sorted per tile (as run) | W=8 tile order | W=8 sorted per tile (as run) |")
        print("|---|---|---|---|---|---|")
        for m in methods:
            for f in frames:
                counts = read_grid(f"{d}/{m}.f{f}.samples.csv")
                mask = read_grid(f"{d}/{m}.f{f}.mask.csv")
                run = efficiency(counts, mask, width, False)
                best = efficiency(counts, mask, width, True)
                print(f"| {m} | {f} | {run[32]:.2f} | {best[32]:.2f} | {run[8]:.2f} | {best[8]:.2f} |")


if __name__ == "__main__":
    main()
