#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Warp efficiency of the SSS sampling loop: how much of a warp's time its threads spend on samples.

The burley pass runs one 8x8 workgroup per SSS tile, one thread per pixel, each looping over its pixel's N
samples; a warp of W threads (W = 32 on NVIDIA: rows 0-3, then 4-7 of the tile, gl_LocalInvocationIndex =
x + 8 y) runs as long as its largest N. Efficiency = sum of N / (W x sum over warps of the warp's largest N),
over the warps of the tiles that hold an SSS pixel (the ones dispatched); 1 for a fixed count over full tiles.

Reads the per-pixel counts that emcv-eval dumps (--heatmaps) and prints a markdown row per method and frame:
the efficiency as the pass runs (threads in tile order), and as it would be with each tile's threads taking
its pixels in order of N (the smallest 32 counts in the first warp), for W = 32 (NVIDIA warps) and W = 8
(llvmpipe's 256-bit SIMD batches of 8 floats).

Usage: /usr/bin/python3 scripts/eval/warp_efficiency.py [--build build] [--scene light-off] [--size 128x128]
           [--frames 29,30,33,59] [--spp-budget 8 | --target-variance V] [--methods spvg,cv,cv-notex]
"""
import argparse
import csv
import subprocess
import tempfile

TILE = 8


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


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", default="build")
    p.add_argument("--scene", default="light-off")
    p.add_argument("--size", default="128x128")
    p.add_argument("--frames", default="29,30,33,59")
    p.add_argument("--spp-budget", default="8")
    p.add_argument("--target-variance", default=None)
    p.add_argument("--methods", default="spvg,cv,cv-notex")
    a = p.parse_args()
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
        print("| method | frame | W=32 as run | W=32 sorted per tile | W=8 as run | W=8 sorted per tile |")
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
