#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The SSS passes' cost model (docs/results.md, "Cost model"): bytes read and written and transcendental
operations per Burley sample and per SSS pixel, counted from the shaders (the tables below; change them with
the shaders), and the floors they put on a GPU's time at a resolution and budget.

Floors: DRAM bytes / memory bandwidth (every per-pixel byte from DRAM once; sample fetches mostly hit the
caches, so they are given apart at the L2 bandwidth), and transcendental operations / the special-function
units' rate (sqrt, exp, log, sin, cos, reciprocal each one SFU operation; pow = exp + log, two).

Usage: /usr/bin/python3 scripts/eval/cost_model.py [--size 1920x1080] [--budget 8] [--device h100]
"""
import argparse

# (bytes, SFU operations) per Burley sample: depth R32F (4, signed with the scatter flag) + lit diffuse RGBA16F
# (8); exact inverse CDF: sqrt, pow (2), log; offset: cos, sin; depth-aware radius: sqrt; pdf: 2 exp and a
# reciprocal; profile: 3 channels x 2 exp.
SAMPLE = {"bytes": 4 + 8, "sfu": 1 + 2 + 1 + 2 + 1 + 3 + 6}

# Per SSS pixel, by pass: bytes (reads + writes) and SFU operations.
PIXEL = {
    # burley pass, every method: depth 4, material code 1, material block 16, albedo 8, centre diffuse 8; writes
    # scattered RGBA16F 8 and count R32UI 4. Shape distance: 3 divisions; pixels per mm: 1 division; rotation:
    # integer hash.
    "burley": {"bytes": 4 + 1 + 16 + 8 + 8 + 8 + 4, "sfu": 4},
    # adaptive samples pass (cv): motion RG16F 4, normal 8, previous depth 4, normal 8, material 1, history a
    # RGBA32F 16 and b RG32F 8 (read), this frame's history a and b (written 24), N or sigma^2 4; sub-pixel test:
    # material block 16, albedo 8; sigma: a division and a sqrt; the world position's projection: a division.
    # Budget shrinkage (emcv_history_shrink_sigma2): the effective frames a division, the pool's 1 / K_j for up to
    # 9 neighbours and its K a division, the weight a division, 1 / K in the frame's sum a division, the raw
    # histogram's sqrt (14; its histograms are shared memory and a few atomics per tile, no DRAM per pixel).
    "adaptive samples (cv)": {"bytes": 4 + 8 + 4 + 8 + 1 + 24 + 24 + 4 + 16 + 8, "sfu": 6 + 1 + 9 + 1 + 1 + 1 + 1},
    # history update inside the burley pass (cv): N or sigma^2 4, history a and b read 24 and written 24, its own
    # output read back 8 (the albedo is the taps' setup's, read once in the burley row); gamma luminance of f and
    # G: 2 pow (4); EMCM push: divisions (3), the 5-sigma test: a division; budget: sqrt of sigma^2.
    "adaptive update (cv)": {"bytes": 4 + 24 + 24 + 8, "sfu": 4 + 3 + 1 + 1},
    # budget, the next frame showing this view: the burley pass plans it after its update instead of that frame's
    # samples pass (docs/renderer.md, "Planning the next frame"): history a and b read back 24 (this invocation's
    # own stores: most hit the caches; counted from DRAM) and sigma^2 written 4; the material code and the
    # sub-pixel test are the taps' setup's (burley row). sigma: a division and a sqrt (2); the pooling and the
    # shrinkage as in the samples pass (14). No motion, no previous G-buffer, no history copy.
    "planned ahead (cv, still view)": {"bytes": 24 + 4, "sfu": 2 + 14},
}

DEVICES = {
    # H100 SXM5 (the repo's GPU tables): HBM3 3.35 TB/s, L2 about 10 TB/s, 132 SMs x 16 SFU lanes at 1.98 GHz.
    "h100": {"name": "NVIDIA H100 SXM5", "dram": 3.35e12, "l2": 10e12, "sfu": 132 * 16 * 1.98e9},
    # H200: HBM3e 4.8 TB/s, otherwise the H100's SMs and clocks.
    "h200": {"name": "NVIDIA H200", "dram": 4.8e12, "l2": 10e12, "sfu": 132 * 16 * 1.98e9},
}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", default="1920x1080")
    p.add_argument("--budget", type=int, default=8)
    p.add_argument("--device", default="h100", choices=sorted(DEVICES))
    a = p.parse_args()
    w, h = (int(x) for x in a.size.split("x"))
    pixels = w * h
    dev = DEVICES[a.device]
    print(f"{a.size} with every pixel scattering, B = {a.budget} samples per pixel, {dev['name']} "
          f"(DRAM {dev['dram'] / 1e12:.2f} TB/s, L2 ~{dev['l2'] / 1e12:.0f} TB/s, "
          f"{dev['sfu'] / 1e12:.2f} T SFU ops/s)")
    print()
    print("| work | bytes | SFU ops | floor from bytes (us) | floor from SFU ops (us) |")
    print("|---|---:|---:|---:|---:|")
    sample_bytes = SAMPLE["bytes"] * a.budget
    sample_sfu = SAMPLE["sfu"] * a.budget
    print(f"| one sample | {SAMPLE['bytes']} | {SAMPLE['sfu']} | | |")
    print(f"| B samples per pixel (L2) | {sample_bytes} | {sample_sfu} | "
          f"{pixels * sample_bytes / dev['l2'] * 1e6:.1f} | {pixels * sample_sfu / dev['sfu'] * 1e6:.1f} |")
    for name, c in PIXEL.items():
        print(f"| {name}, per pixel (DRAM) | {c['bytes']} | {c['sfu']} | "
              f"{pixels * c['bytes'] / dev['dram'] * 1e6:.1f} | {pixels * c['sfu'] / dev['sfu'] * 1e6:.1f} |")
    adaptive = sum(c["bytes"] for n, c in PIXEL.items() if n.startswith("adaptive"))
    still = PIXEL["adaptive update (cv)"]["bytes"] + PIXEL["planned ahead (cv, still view)"]["bytes"]
    print()
    print(f"cv's per-pixel history work reads and writes {adaptive} B a pixel, as many bytes as "
          f"{adaptive / SAMPLE['bytes']:.0f} samples' fetches; where the view holds and the burley pass plans the "
          f"next frame, {still} B ({still / SAMPLE['bytes']:.0f} samples' fetches), in one dispatch instead of two.")


if __name__ == "__main__":
    main()
