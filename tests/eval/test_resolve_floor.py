#!/usr/bin/python3
"""scripts/eval/resolve_floor.py's model of a fixed-weight resolve under a moving camera, against a simulation of
the filter it models (no renderer):
  - MSE(w) = sigma^2 w / (2 - w) + e^2 (1 - w)^2 / (w (2 - w)) is the stationary error of h' = w x + (1 - w)(h + eps)
    with x = truth + noise (variance sigma^2) and eps the reprojection's error (variance e^2), both independent
    from step to step. Simulated with 100000 independent chains (seed 1), 400 steps each (the start's weight
    (1 - w)^400 < 1e-18 at w >= 0.1), the last state of each: the variance of 100000 independent normal values has
    a relative standard error of sqrt(2 / 100000) = 0.45%, so the bound is 5 of them, 2.2%.
  - best_weight() finds the minimum of the model (a grid of 99999 weights finds no lower value);
  - six_db_ratio() is where the best weight's gain is 6 dB: just below it the gain exceeds 6 dB, just above it
    falls short.

    /usr/bin/python3 tests/eval/test_resolve_floor.py
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "scripts", "eval"))
import resolve_floor  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from script_checks import check, finish  # noqa: E402


def simulated_mse(sigma2, e2, w, chains=100000, steps=400, seed=1):
    rng = np.random.default_rng(seed)
    h = np.zeros(chains)  # the history's error (the truth is 0)
    for _ in range(steps):
        x = rng.normal(0.0, math.sqrt(sigma2), chains)
        eps = rng.normal(0.0, math.sqrt(e2), chains)
        h = w * x + (1.0 - w) * (h + eps)
    return float(np.mean(h * h))


def main():
    bound = 5 * math.sqrt(2 / 100000)
    for sigma2, e2, w in ((1.0, 0.1, 0.5), (1.0, 0.1, 0.25), (1.0, 0.1, 0.1), (2e-5, 2.3e-6, 0.28), (1.0, 0.0, 0.1)):
        model = resolve_floor.model(sigma2, e2, w)
        sim = simulated_mse(sigma2, e2, w)
        check(abs(sim / model - 1) < bound, f"model({sigma2}, {e2}, {w}) = {model:.6g}, simulated {sim:.6g} "
                                            f"(relative difference over {bound:.3f})")
    for sigma2, e2 in ((1.0, 0.1), (2.17e-5, 2.29e-6), (1.0, 0.5)):
        w = resolve_floor.best_weight(sigma2, e2)
        grid = min(resolve_floor.model(sigma2, e2, k / 100000) for k in range(1, 100000))
        check(resolve_floor.model(sigma2, e2, w) <= grid * (1 + 1e-9),
              f"best_weight({sigma2}, {e2}) = {w:.4f} is the model's minimum (grid found {grid:.6g})")
    r = resolve_floor.six_db_ratio()

    def gain(ratio):
        return -10 * math.log10(resolve_floor.model(1.0, ratio, resolve_floor.best_weight(1.0, ratio)))
    check(gain(0.99 * r) > 6.0 > gain(1.01 * r), f"six_db_ratio() = {r:.4f} is where the best gain crosses 6 dB "
                                                 f"(gains {gain(0.99 * r):.4f} and {gain(1.01 * r):.4f})")
    return finish("test_resolve_floor")


if __name__ == "__main__":
    sys.exit(main())
