"""docs/integration.md's synthetic stream from Python (as tests/policy/test_sampling_behaviour.cpp in C++): 64x64
pixels, G_i in [0.4, 0.6], per-sample values G_i (1 + rho z) with rho = 0.089 under a quality target of 1e-4, 100
frames, the light off (G -> 0, f -> 0) from frame 50. On the static light spvg and cv estimate the same per-sample
variance; after the switch spvg reads the step of f as noise while cv's control explains it: cv takes at most
half of spvg's samples."""
import numpy as np

import emcv
from streams import gradient_control, run_stream

RHO, TARGET, FRAMES, SWITCH = 0.089, 1e-4, 100, 50


def mean_count(plans, first, last):
    return float(np.mean([plans[t].counts.mean() for t in range(first, last + 1)]))


def test_after_the_switch_cv_takes_at_most_half_of_spvgs_samples():
    g0 = gradient_control(64, 64)
    results = {}
    for estimator in ("spvg", "cv"):
        params = emcv.SamplingParams(estimator, "quality_target", target=TARGET, n_min=1, n_max=64)
        results[estimator], _ = run_stream(params, g0, RHO, FRAMES, switch_frame=SWITCH)
    spvg_static, cv_static = mean_count(results["spvg"], 20, 49), mean_count(results["cv"], 20, 49)
    spvg_after, cv_after = mean_count(results["spvg"], 50, 79), mean_count(results["cv"], 50, 79)
    # static light: both ask for about mean_i G_i^2 rho^2 / target (+1 for the ceil)
    asked = float(np.mean(g0.astype(np.float64) ** 2)) * RHO**2 / TARGET
    for m in (spvg_static, cv_static):
        assert 0.95 * asked <= m <= 1.05 * (asked + 1)
    assert abs(cv_static / spvg_static - 1) <= 0.10
    # the switch: spvg reads the step as variance and samples at n_max; cv does not
    assert spvg_after > 2 * spvg_static
    assert cv_after <= 0.5 * spvg_after
