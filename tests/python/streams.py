"""Synthetic frames for the tests of the Python module: an SSS pass simulated as the mean of N samples
G (1 + rho z), so that f = G (1 + rho z / sqrt(N)) (docs/integration.md, step 2)."""
import numpy as np

import emcv


def gradient_control(width, height, low=0.4, high=0.6):
    """G_i in [low, high]: a horizontal gradient, the same on every row (float32, C-contiguous)."""
    row = np.linspace(low, high, width, dtype=np.float32)
    return np.ascontiguousarray(np.broadcast_to(row, (height, width)))


def sss_output(g, counts, rho, rng):
    """f: the mean of counts[i] samples G (1 + rho z) at each pixel (float32); a pixel with 0 samples keeps G."""
    n = np.maximum(counts, 1).astype(np.float64)
    z = rng.standard_normal(g.shape)
    return (g * (1.0 + rho * z / np.sqrt(n))).astype(np.float32)


def run_stream(params, g0, rho, frames, switch_frame=None, material=None, seed=77):
    """docs/integration.md's recipe: plan from the history, take the counts, push (f, G). The light goes off
    (G -> 0, f -> 0) from switch_frame on. Returns the FramePlan of every frame and the History."""
    height, width = g0.shape
    history = emcv.History(width, height, params.estimator)
    rng = np.random.default_rng(seed)
    plans = []
    for t in range(frames):
        plan = emcv.plan_frame(params, history, material=material, frame=t, seed=5)
        plans.append(plan)
        light = 0.0 if switch_frame is not None and t >= switch_frame else 1.0
        g = (light * g0).astype(np.float32)
        f = sss_output(g, plan.counts, rho, rng)
        emcv.sampling_update(params, history, f, g, plan.counts, material=material)
    return plans, history
