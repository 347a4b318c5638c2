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
    # samples pass (docs/renderer.md, "Planning the next frame"): the history it has just stored taken from its
    # registers (cv's 32-bit texels read back bit for bit: emcv_adaptive_as_stored), sigma^2 written 4; the
    # material code and the sub-pixel test are the taps' setup's (burley row). sigma: a division and a sqrt (2);
    # the pooling and the shrinkage as in the samples pass (14). No motion, no previous G-buffer, no history copy.
    "planned ahead (cv, still view)": {"bytes": 4, "sfu": 2 + 14},
}

# The same adaptive rows split by grain, for block statistics (EMCV_HISTORY_BLOCK = K, docs/renderer.md "Block
# statistics"): what each SSS pixel still pays, and what each K x K block pays once (the history texels, the
# reprojection's previous G-buffer at the block's representative, the variance's arithmetic). Per pixel the samples
# pass reads the material code and the sub-pixel test's material block and albedo (25 B); the update reads the
# block's count or variance (4, from the caches after the first pixel; counted) and its own estimate back (8), and
# takes the gamma luminance of f and G (4 SFU). At K = 1 each row adds up to its PIXEL row above.
SPLIT = {
    "adaptive samples (cv)": {"pixel": {"bytes": 1 + 16 + 8, "sfu": 0},
                              "block": {"bytes": 4 + 8 + 4 + 8 + 24 + 24 + 4, "sfu": 20}},
    "adaptive update (cv)": {"pixel": {"bytes": 4 + 8, "sfu": 4},
                             "block": {"bytes": 24 + 24, "sfu": 5}},
    "planned ahead (cv, still view)": {"pixel": {"bytes": 0, "sfu": 0},
                                       "block": {"bytes": 4, "sfu": 16}},
}

# The H100 runs of docs/results/gpu (light-off, 1920x1080, glFinish-timed, before the passes were fused:
# demo-1920x1080.txt, means over frames 1-59): burley-16's and cv's SSS time over the same SSS pixels, to which the
# projection below fits one factor for the samples' floors and one for the history's.
H100_RUN = {"sss_pixels": 344365, "burley_spp": 16, "burley_ms": 1.339, "cv_spp": 11.7, "cv_ms": 1.554}

DEVICES = {
    # H100 SXM5 (the repo's GPU tables): HBM3 3.35 TB/s, L2 about 10 TB/s, 132 SMs x 16 SFU lanes at 1.98 GHz.
    "h100": {"name": "NVIDIA H100 SXM5", "dram": 3.35e12, "l2": 10e12, "sfu": 132 * 16 * 1.98e9},
    # H200: HBM3e 4.8 TB/s, otherwise the H100's SMs and clocks.
    "h200": {"name": "NVIDIA H200", "dram": 4.8e12, "l2": 10e12, "sfu": 132 * 16 * 1.98e9},
}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--size", default="1920x1080")
    p.add_argument("--budget", type=int, default=8)
    p.add_argument("--device", default="h100", choices=sorted(DEVICES))
    p.add_argument("--blocks", default="", help="comma-separated K (1, 2, 4): add the per-K table and its projection")
    a = p.parse_args(argv)
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

    if a.blocks:
        blocks_table(a, pixels, dev)


def floor_us(pixels, c, dev, per_sample=False):
    """The larger of a count's two floors, in microseconds over `pixels` (samples' bytes at L2, the rest at DRAM)."""
    return pixels * max(c["bytes"] / (dev["l2"] if per_sample else dev["dram"]), c["sfu"] / dev["sfu"]) * 1e6


def blocks_table(a, pixels, dev):
    """cv's history work per SSS pixel at each K, its floors, and a projection scaled by the H100's burley-16."""
    def at(k, rows):
        out = {"bytes": 0.0, "sfu": 0.0}
        for name in rows:
            for key in out:
                out[key] += SPLIT[name]["pixel"][key] + SPLIT[name]["block"][key] / (k * k)
        return out

    def burley(n):
        return {"bytes": SAMPLE["bytes"] * n, "sfu": SAMPLE["sfu"] * n}, PIXEL["burley"]

    def burley_floor(n, px):
        samples, per_pixel = burley(n)
        return floor_us(px, samples, dev, per_sample=True) + floor_us(px, per_pixel, dev)

    moving = ["adaptive samples (cv)", "adaptive update (cv)"]
    still = ["adaptive update (cv)", "planned ahead (cv, still view)"]
    # The projection: t = s_samples x (burley's floors) + s_history x (the history's floors), s_samples from
    # burley-16's measured time, s_history from cv's (its samples priced as burley's, its history work at K = 1 on
    # a moving view: the counts of the fused passes, which the run predates). Two measurements, two factors: a fit
    # that is exact on them, not a test of the model.
    run = H100_RUN
    s_samples = run["burley_ms"] * 1e3 / burley_floor(run["burley_spp"], run["sss_pixels"])
    cv_samples_us = s_samples * burley_floor(run["cv_spp"], run["sss_pixels"])
    s_history = (run["cv_ms"] * 1e3 - cv_samples_us) / floor_us(run["sss_pixels"], at(1, moving), dev)
    print()
    print(f"cv's history work by the statistics' grain K, {a.size}, every pixel scattering. Floors as above; "
          f"'projected' prices burley's floors at {s_samples:.1f}x and the history's at {s_history:.1f}x, the factors "
          f"that the H100 run of docs/results/gpu gives (light-off 1920x1080, burley-16 {run['burley_ms']} ms and cv "
          f"{run['cv_ms']} ms at {run['cv_spp']} spp on {run['sss_pixels']} SSS pixels, glFinish-timed, before the "
          f"passes were fused). A projection, not a measurement.")
    print()
    print(f"| K | moving view: B / pixel | floor (us) | projected (us) | still view: B / pixel | floor (us) | "
          f"projected (us) | projected / burley-{a.budget}'s, moving (still) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    base = burley_floor(a.budget, pixels) * s_samples
    for k in (int(x) for x in a.blocks.split(",")):
        if k not in (1, 2, 4):
            raise SystemExit(f"cost_model.py: --blocks takes 1, 2 and 4, got {k}")
        m, st = at(k, moving), at(k, still)
        fm, fs = floor_us(pixels, m, dev), floor_us(pixels, st, dev)
        print(f"| {k} | {m['bytes']:.0f} | {fm:.1f} | {fm * s_history:.0f} | {st['bytes']:.0f} | {fs:.1f} | "
              f"{fs * s_history:.0f} | {fm * s_history / base:.2f} ({fs * s_history / base:.2f}) |")
    for n in (a.budget, 16):
        f = burley_floor(n, pixels)
        print(f"| burley-{n}'s SSS pass | | {f:.1f} | {f * s_samples:.0f} | | | | {f * s_samples / base:.2f} |")


if __name__ == "__main__":
    main()
