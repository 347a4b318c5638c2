"""Bad arrays and misuse: a ValueError naming the function, the argument and the expected dtype and shape."""
import numpy as np
import pytest

import emcv

W, H = 10, 6


@pytest.fixture
def frame():
    params = emcv.SamplingParams("cv")
    history = emcv.History(W, H, "cv")
    f = np.full((H, W), 0.5, dtype=np.float32)
    g = np.full((H, W), 0.4, dtype=np.float32)
    counts = np.full((H, W), 2, dtype=np.int32)
    return params, history, f, g, counts


def expected(where, name, dtype):
    return f"{where}: {name} must be a C-contiguous numpy array of dtype {dtype} and shape ({H}, {W}) (height, width)"


@pytest.mark.parametrize("argument, dtype", [("f", "float32"), ("g", "float32"), ("counts", "int32")])
@pytest.mark.parametrize(
    "bad, got",
    [
        (lambda a: a.reshape(-1), "shape ({},)".format(W * H)),
        (lambda a: a[:, :-1].copy(), f"shape ({H}, {W - 1})"),
        (lambda a: a.T.copy(), f"shape ({W}, {H})"),
        (lambda a: a.astype(np.float64), "dtype float64"),
        (lambda a: a.astype(np.int64), "dtype int64"),
        (lambda a: np.asfortranarray(a), "not C-contiguous"),
        (lambda a: np.repeat(a, 2, axis=1)[:, ::2], "not C-contiguous"),
    ],
)
def test_sampling_update_names_the_bad_array(frame, argument, dtype, bad, got):
    params, history, f, g, counts = frame
    arrays = {"f": f, "g": g, "counts": counts}
    original = arrays[argument]
    arrays[argument] = bad(original)
    if arrays[argument].dtype == original.dtype and "dtype" in got:
        pytest.skip("the conversion keeps the dtype")
    before = history.state.copy()
    with pytest.raises(ValueError) as error:
        emcv.sampling_update(params, history, arrays["f"], arrays["g"], arrays["counts"])
    assert expected("emcv.sampling_update", argument, dtype) in str(error.value)
    assert got in str(error.value)
    assert history.state.tobytes() == before.tobytes()  # nothing was pushed


def test_not_an_array(frame):
    params, history, f, g, counts = frame
    with pytest.raises(ValueError, match=r"f must be a C-contiguous numpy array .*got list"):
        emcv.sampling_update(params, history, f.tolist(), g, counts)


def test_plan_frame_checks_material_and_sub_pixel(frame):
    params, history, *_ = frame
    with pytest.raises(ValueError) as error:
        emcv.plan_frame(params, history, material=np.ones((H, W), dtype=np.int32))
    assert expected("emcv.plan_frame", "material", "uint32") in str(error.value)
    with pytest.raises(ValueError) as error:
        emcv.plan_frame(params, history, sub_pixel=np.ones((H, W + 1), dtype=np.uint8))
    assert expected("emcv.plan_frame", "sub_pixel", "uint8 or bool") in str(error.value)
    # both flag dtypes are accepted; a sub-pixel kernel takes no samples under cv
    for flags in (np.eye(H, W, dtype=np.uint8), np.eye(H, W, dtype=bool)):
        plan = emcv.plan_frame(params, history, sub_pixel=flags)
        assert np.all(plan.counts[flags.astype(bool)] == 0) and np.all(plan.counts[~flags.astype(bool)] == 64)


def test_history_and_params_must_agree_on_the_estimator(frame):
    _, history, f, g, counts = frame
    for estimator in ("spvg", "cv_notex"):
        with pytest.raises(ValueError, match="the history holds cv states but params.estimator is " + estimator):
            emcv.plan_frame(emcv.SamplingParams(estimator), history)
        with pytest.raises(ValueError, match="the history holds cv states"):
            emcv.sampling_update(emcv.SamplingParams(estimator), history, f, g, counts)
    with pytest.raises(ValueError, match="the history holds spvg states but params.estimator is cv_notex"):
        emcv.plan_frame(emcv.SamplingParams("cv_notex"), emcv.History(W, H, "spvg"))


def test_history_arguments():
    with pytest.raises(ValueError, match="width and height must be >= 1"):
        emcv.History(0, 4, "cv")
    with pytest.raises(ValueError, match="estimator must be"):
        emcv.History(4, 4, "burley")
    with pytest.raises(ValueError, match=r"emcv.History.reset: mask must be .* dtype bool and shape \(4, 4\)"):
        emcv.History(4, 4, "cv").reset(np.ones((4, 4), dtype=np.uint8))


def test_budget_solve_checks_sigma2():
    params = emcv.SamplingParams(mode="budget")
    with pytest.raises(ValueError, match="sigma2 must be a C-contiguous numpy array of dtype float32"):
        emcv.budget_solve(params, np.zeros(16, dtype=np.float32))
    with pytest.raises(ValueError, match="dtype float32"):
        emcv.budget_solve(params, np.zeros((4, 4)))
    with pytest.raises(ValueError, match=r"material must be .* uint32 and shape \(4, 4\)"):
        emcv.budget_solve(params, np.zeros((4, 4), dtype=np.float32), np.zeros((4, 5), dtype=np.uint32))
    # NaN and codes are documented inputs: a variance code without a variance takes the budget outside the solve
    sigma2 = np.array([[np.nan, emcv.NO_VARIANCE], [emcv.NO_SAMPLES, 0.01]], dtype=np.float32)
    assert emcv.budget_solve(params, sigma2) > 0
