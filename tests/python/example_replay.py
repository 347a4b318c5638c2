"""Replay captured frames through emcv's adaptive-sampling policy and compare settings (docs/python.md)."""
import numpy as np

import emcv


def captured_frames(width=64, height=64, frames=60, switch=30, seed=1):
    """Stands in for an engine capture: per frame the SSS output f (the mean of the frame's counts samples), the
    unscattered diffuse G and the counts it was rendered with. The top half is ten times noisier; the light
    drops to 30% at frame `switch`."""
    rng = np.random.default_rng(seed)
    g0 = np.broadcast_to(np.linspace(0.2, 0.8, width, dtype=np.float32), (height, width))
    spread = np.where(np.arange(height)[:, None] < height // 2, 0.5, 0.05)
    counts = np.full((height, width), 8, dtype=np.int32)
    for t in range(frames):
        g = np.ascontiguousarray(g0 * (1.0 if t < switch else 0.3), dtype=np.float32)
        z = rng.standard_normal((height, width))
        f = (g * (1 + spread * z / np.sqrt(counts))).astype(np.float32)
        yield f, g, counts


def replay(params, frames, first=10):
    """Plans every frame with `params` and pushes the captured (f, G) with the counts they were rendered with,
    so that the history estimates the per-sample variance. Returns the mean samples per pixel the plans ask
    for and the mean predicted output variance sigma^2 / N over the pixels with a variance, from frame `first`."""
    height, width = frames[0][0].shape
    history = emcv.History(width, height, params.estimator)
    spent, variance = [], []
    for t, (f, g, counts) in enumerate(frames):
        plan = emcv.plan_frame(params, history, frame=t, seed=7)
        if t >= first:
            known = plan.sigma2 >= 0
            spent.append(plan.counts.mean())
            variance.append(np.mean(plan.sigma2[known] / plan.counts[known]))
        emcv.sampling_update(params, history, f, g, counts)
    return float(np.mean(spent)), float(np.mean(variance))


def main():
    frames = list(captured_frames())
    settings = {
        "spvg, target 1e-4": emcv.SamplingParams("spvg", "quality_target", target=1e-4),
        "cv, target 1e-4": emcv.SamplingParams("cv", "quality_target", target=1e-4),
        "cv, target 4e-4": emcv.SamplingParams("cv", "quality_target", target=4e-4),
        "cv, target 1e-4, eta 0.05": emcv.SamplingParams("cv", "quality_target", target=1e-4, eta=0.05),
        "cv, budget 8": emcv.SamplingParams("cv", "budget", budget=8),
        "cv, budget 16": emcv.SamplingParams("cv", "budget", budget=16),
    }
    results = {}
    print(f"{'setting':28} {'samples/pixel':>14} {'predicted variance':>19}")
    for name, params in settings.items():
        results[name] = replay(params, frames)
        print(f"{name:28} {results[name][0]:14.2f} {results[name][1]:19.3g}")
    return results


if __name__ == "__main__":
    main()
