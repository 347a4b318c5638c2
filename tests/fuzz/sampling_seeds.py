#!/usr/bin/python3
"""Writes the seed inputs of the `sampling` fuzz target (tests/fuzz/fuzz_sampling.cpp) into
tests/fuzz/corpus/sampling/: per estimator and mode, an 8x8 frame replaying docs/integration.md's synthetic
stream (plan, then push f = G (1 + noise) with the planned counts) with the light dimmed halfway, one with
materials and sub-pixel flags, and one with hard-case parameters. Each file is named seed-<what>.

    /usr/bin/python3 tests/fuzz/sampling_seeds.py
"""
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "corpus", "sampling")
ESTIMATORS = ["spvg", "cv", "cv_notex"]
MODES = ["quality", "budget"]


def header(estimator, mode, which=0, extra=b""):
    return bytes([estimator + 3 * mode, which]) + extra


def plan(what=0, frame=0, seed=7, materials=None, sub_pixel=None):
    body = bytes([0, what])  # op 0: plan
    if what & 1:
        body += bytes(materials)
    if what & 4:
        body += bytes(sub_pixel)
    return body + struct.pack("<II", frame, seed)


def update_noisy(rng, light, pixels):
    noise = bytes(rng.randrange(-100, 101) & 0xFF for _ in range(pixels))
    return bytes([3, 1, light]) + noise  # op 3: update, a noisy stream with the planned counts


def stream(estimator, mode, which, params, rng, width=8, height=8, frames=12, materials=None, sub_pixel=None):
    pixels = width * height
    data = header(estimator, mode, which, params) + bytes([width - 1, height - 1])
    for frame in range(frames):
        what = 0
        if frame == 0 and materials is not None:
            what |= 1
        if frame == 0 and sub_pixel is not None:
            what |= 4
        data += plan(what, frame, 7, materials, sub_pixel)
        data += update_noisy(rng, 128 if frame < frames // 2 else 16, pixels)
    return data


def main():
    os.makedirs(OUT, exist_ok=True)
    rng = random.Random(1)
    seeds = {}
    for e, estimator in enumerate(ESTIMATORS):
        for m, mode in enumerate(MODES):
            # budget mode: which bit 2 + bit 64, budget = byte / 4 = 8
            which, params = (2 | 64, bytes([32])) if m == 1 else (0, b"")
            seeds[f"seed-{estimator}-{mode}"] = stream(e, m, which, params, rng)
            materials = [rng.choice([0, 1, 1, 2]) for _ in range(64)]
            sub_pixel = [rng.choice([1, 1, 1, 0]) for _ in range(64)]  # 0: sub-pixel (byte % 4 == 0)
            seeds[f"seed-{estimator}-{mode}-materials"] = stream(e, m, which, params, rng, materials=materials,
                                                                 sub_pixel=sub_pixel)
    # hard-case parameters: target NaN (tag 4), n_min 0 (small int), n_max -1, eta raw bits
    seeds["seed-bad-params"] = header(1, 0, 1 | 4 | 8 | 16, bytes([4, 1, 0, 1, 0xFF, 16]) + struct.pack("<f", 0.7))
    # a poke of a history field, a reset, a plan and an update with arbitrary counts
    seeds["seed-poke-reset"] = (header(0, 1, 2 | 64, bytes([16])) + bytes([3, 3]) + plan() +
                                update_noisy(rng, 64, 16) + bytes([6, 5, 2, 5]) + bytes([7, 9]) + plan() +
                                bytes([3, 2]) + bytes(16 * 2) + bytes([1, 3] * 16))
    for name, data in seeds.items():
        with open(os.path.join(OUT, name), "wb") as f:
            f.write(data)
    print(f"wrote {len(seeds)} seeds to {OUT}")


if __name__ == "__main__":
    main()
