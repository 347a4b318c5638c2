"""The per-frame API against independent numpy re-implementations of the documented formulas
(docs/integration.md step 2, adaptive_sampling.hpp): the quality target's count, the per-sample variance of a
moving-stats history and its 3x3 same-material pooling in 8x8 tiles, the budget's mean and where it goes, and
sampling_update's treatment of refused values and empty batches."""
import numpy as np
import pytest

import emcv
from streams import gradient_control, run_stream, sss_output

F32 = np.float32


def quality_counts(sigma2, target, n_min, n_max):
    """N = clamp(ceil(sigma^2 / target), n_min, n_max); n_max without a variance; 0 for no samples."""
    q = np.ceil(sigma2.astype(F32) / F32(target))
    n = np.clip(q, n_min, n_max)
    n = np.where(sigma2 < 0, n_max, n)
    return np.where(sigma2 == emcv.NO_SAMPLES, 0, n).astype(np.int32)


def own_sigma2_moving(state, eta):
    """spvg / cv_notex: the moving variance times (2 - eta) / (2 (1 - eta)) (the EMCM's steady-state bias divided
    out), in float32; no variance (-1) before two frames."""
    eta = F32(eta)
    unbias = (F32(2) - eta) / (F32(2) * (F32(1) - eta))
    v = state["variance"].astype(F32) * unbias
    return np.where(state["count"] < 2, F32(-1), v).astype(F32)


def pooled(own, material, tile=8):
    """Each pixel's mean over its 3x3 neighbours in its tile with its material that have a variance (itself
    included), summed in float32 row by row; codes kept; material 0: no samples."""
    height, width = own.shape
    out = np.empty_like(own)
    for y in range(height):
        for x in range(width):
            if material[y, x] == 0:
                out[y, x] = emcv.NO_SAMPLES
                continue
            total, count = F32(0), 0
            for qy in range(y - 1, y + 2):
                for qx in range(x - 1, x + 2):
                    if not (0 <= qy < height and 0 <= qx < width):
                        continue
                    if qy // tile != y // tile or qx // tile != x // tile or material[qy, qx] != material[y, x]:
                        continue
                    if own[qy, qx] >= 0:
                        total = F32(total + own[qy, qx])
                        count += 1
            out[y, x] = own[y, x] if own[y, x] < 0 or count == 0 else F32(total / F32(count))
    return out


def materials(width, height):
    """A border that does not scatter (0) and two materials split by a diagonal (1, 2)."""
    y, x = np.mgrid[0:height, 0:width]
    m = np.where(x + y < width, 1, 2).astype(np.uint32)
    m[:2, :] = 0
    m[:, -3:] = 0
    return np.ascontiguousarray(m)


@pytest.mark.parametrize("estimator", ["spvg", "cv", "cv_notex"])
def test_quality_counts_follow_the_documented_formula(estimator):
    params = emcv.SamplingParams(estimator, "quality_target", target=2e-4, n_min=2, n_max=40)
    g0 = gradient_control(20, 12)
    plans, _ = run_stream(params, g0, rho=0.12, frames=12)
    interior = 0
    for plan in plans:
        expected = quality_counts(plan.sigma2, params.target, params.n_min, params.n_max)
        assert np.array_equal(plan.counts, expected)
        assert plan.samples == int(plan.counts.sum())
        assert plan.lambda_ == 0.0
        interior += int(np.count_nonzero((plan.counts > params.n_min) & (plan.counts < params.n_max)))
    assert interior > 100  # the ceil, not only the clamps, is exercised
    assert np.all(plans[0].counts == params.n_max)  # an empty history has no variance yet


@pytest.mark.parametrize("estimator", ["spvg", "cv_notex"])
def test_sigma2_is_the_unbiased_moving_variance_pooled_over_same_material_neighbours(estimator):
    width, height = 21, 13  # partial tiles on both axes
    params = emcv.SamplingParams(estimator, "quality_target", eta=0.25)
    material = materials(width, height)
    g0 = gradient_control(width, height)
    history = emcv.History(width, height, estimator)
    rng = np.random.default_rng(3)
    for t in range(6):
        before = history.state.copy()
        plan = emcv.plan_frame(params, history, material=material, frame=t)
        expected = pooled(own_sigma2_moving(before, params.effective_eta), material)
        assert np.array_equal(plan.sigma2, expected), f"frame {t}"
        f = sss_output(g0, plan.counts, 0.3 * (1 + np.arange(width) % 3), rng)
        emcv.sampling_update(params, history, f, g0, plan.counts)
    assert np.count_nonzero(plan.sigma2 > 0) > width * height // 2


def test_budget_spends_b_per_sss_pixel_where_the_noise_is():
    width = height = 64
    budget = 8.0
    params = emcv.SamplingParams("cv", "budget", budget=budget)
    material = materials(width, height)
    sss = material != 0
    g0 = gradient_control(width, height, 0.2, 0.8)
    noisy = np.zeros((height, width), dtype=bool)
    noisy[: height // 2] = True
    rho = np.where(noisy, 0.5, 0.05)
    history = emcv.History(width, height, "cv")
    rng = np.random.default_rng(11)
    for t in range(40):
        plan = emcv.plan_frame(params, history, material=material, frame=t, seed=9)
        f = sss_output(g0, plan.counts, rho, rng)
        emcv.sampling_update(params, history, f, g0, plan.counts)
    mean = plan.counts[sss].mean()
    assert abs(mean - budget) <= 0.02 * budget
    assert np.all(plan.counts[~sss] == 0) and np.all(plan.sigma2[~sss] == emcv.NO_SAMPLES)
    assert np.all(plan.counts[sss] >= params.n_min) and np.all(plan.counts[sss] <= params.n_max)
    # N proportional to sigma: ten times the noise, several times the samples
    assert plan.counts[sss & noisy].mean() > 4 * plan.counts[sss & ~noisy].mean()
    # the same lambda from the frame's sigma2 alone
    assert emcv.budget_solve(params, plan.sigma2, material) == plan.lambda_


def test_a_refused_value_counts_as_rejected_and_an_empty_batch_changes_nothing():
    width, height = 8, 4
    for estimator, refusing_g in (("spvg", False), ("cv", True), ("cv_notex", True)):
        params = emcv.SamplingParams(estimator)
        history = emcv.History(width, height, estimator)
        g = gradient_control(width, height)
        f = (g * 1.1).astype(np.float32)
        counts = np.full((height, width), 4, dtype=np.int32)
        for _ in range(3):
            emcv.sampling_update(params, history, f, g, counts)
        before = history.state.copy()
        f2, g2, counts2 = f.copy(), g.copy(), counts.copy()
        f2[0, 0] = np.nan
        g2[1, 1] = np.inf
        counts2[2, 2] = 0
        counts2[3, 3] = -5
        emcv.sampling_update(params, history, f2, g2, counts2)
        after = history.state
        assert after["rejected"][0, 0] == before["rejected"][0, 0] + 1
        assert after["count"][0, 0] == before["count"][0, 0]
        assert after["rejected"][1, 1] == before["rejected"][1, 1] + (1 if refusing_g else 0)
        assert after[2, 2].tobytes() == before[2, 2].tobytes() and after[3, 3].tobytes() == before[3, 3].tobytes()
        assert after["count"][0, 1] == before["count"][0, 1] + 1


def test_g_may_be_none_for_spvg_only():
    g = gradient_control(8, 8)
    counts = np.ones((8, 8), dtype=np.int32)
    spvg = emcv.History(8, 8, "spvg")
    emcv.sampling_update(emcv.SamplingParams("spvg"), spvg, g, None, counts)
    assert np.all(spvg.state["count"] == 1)
    with pytest.raises(ValueError, match="g must be given for cv and cv_notex"):
        emcv.sampling_update(emcv.SamplingParams("cv"), emcv.History(8, 8, "cv"), g, None, counts)


def test_history_view_reset_and_copy():
    history = emcv.History(6, 5, "cv")
    assert history.state.shape == (5, 6)
    assert history.state.dtype.names == ("mean", "cov", "count", "rejected", "reseeded")
    assert emcv.History(6, 5, "spvg").state.dtype.names == ("mean", "variance", "count", "rejected", "reseeded")
    params = emcv.SamplingParams("cv")
    g = gradient_control(6, 5)
    counts = np.full((5, 6), 2, dtype=np.int32)
    for scale in (1.0, 1.2, 0.9):
        emcv.sampling_update(params, history, (g * scale).astype(np.float32), g, counts)
    copy = history.copy()
    mask = np.zeros((5, 6), dtype=bool)
    mask[1, 2] = mask[4, 5] = True
    history.reset(mask)
    assert np.all(history.state["count"][mask] == 0) and np.all(history.state["cov"][mask] == 0)
    assert np.all(history.state["count"][~mask] == 3)
    assert np.all(copy.state["count"] == 3)  # the copy is its own
    view = history.state
    view["count"][0, 0] = 7  # the view is the history's memory
    del history
    assert view["count"][0, 0] == 7  # and keeps it alive
