"""emcv.SamplingParams: the documented defaults, and every documented requirement refused with a ValueError that
names it (a refused assignment changes nothing)."""
import math

import pytest

import emcv


def test_defaults_are_the_documented_starting_parameters():
    # docs/integration.md: target 1e-4, n_min 1, n_max 64, eta 0.2 for every estimator, a budget of 8
    p = emcv.SamplingParams()
    assert (p.estimator, p.mode) == ("spvg", "quality_target")
    assert p.target == pytest.approx(1e-4, rel=1e-6)
    assert (p.n_min, p.n_max, p.budget, p.eta) == (1, 64, 8.0, None)
    for estimator in ("spvg", "cv", "cv_notex"):
        assert emcv.SamplingParams(estimator).effective_eta == pytest.approx(0.2, rel=1e-6)
        assert emcv.default_eta(estimator) == pytest.approx(0.2, rel=1e-6)
    assert emcv.SamplingParams(eta=0.05).effective_eta == pytest.approx(0.05, rel=1e-6)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"n_min": 0}, "emcv::sampling_params: n_min = 0 must be >= 1"),
        ({"n_min": 9, "n_max": 8}, "n_min = 9 must not exceed n_max = 8"),
        ({"n_max": 1025}, "n_max = 1025 must not exceed 1024"),
        ({"eta": 0.0}, "eta = 0 must lie in (0, 0.5]"),
        ({"eta": 0.6}, "eta = 0.6 must lie in (0, 0.5]"),
        ({"eta": math.nan}, "eta = nan must lie in (0, 0.5]"),
        ({"target": 0.0}, "target = 0 must be finite and > 0"),
        ({"target": math.nan}, "target = nan must be finite and > 0"),
        ({"target": math.inf}, "target = inf must be finite and > 0"),
        ({"mode": "budget", "budget": 0.0}, "budget = 0 must be finite, > 0 and <= n_max"),
        ({"mode": "budget", "budget": 65.0}, "budget = 65 must be finite, > 0 and <= n_max"),
        ({"mode": "budget", "budget": math.nan}, "budget = nan must be finite, > 0 and <= n_max"),
        ({"estimator": "burley"}, "estimator must be 'spvg', 'cv' or 'cv_notex'"),
        ({"mode": "fast"}, "mode must be 'quality_target' or 'budget'"),
    ],
)
def test_invalid_values_are_refused_naming_the_requirement(kwargs, message):
    with pytest.raises(ValueError) as error:
        emcv.SamplingParams(**kwargs)
    assert message in str(error.value)


def test_a_refused_assignment_changes_nothing():
    p = emcv.SamplingParams("cv", "budget", budget=16, n_max=32)
    for field, value in (("n_max", 8), ("budget", 40.0), ("eta", 1.0), ("n_min", 0)):
        with pytest.raises(ValueError):
            setattr(p, field, value)
    assert (p.estimator, p.mode, p.budget, p.n_min, p.n_max, p.eta) == ("cv", "budget", 16.0, 1, 32, None)
    p.n_max = 16  # the budget may equal n_max
    assert p.n_max == 16


def test_only_the_modes_own_value_is_checked():
    # a quality target does not read the budget: an out-of-range budget is accepted until the mode needs it
    p = emcv.SamplingParams(mode="quality_target", budget=1000.0)
    with pytest.raises(ValueError, match="budget = 1000 must be finite"):
        p.mode = "budget"
    assert p.mode == "quality_target"
