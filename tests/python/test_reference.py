"""The Python module against the C++ library: the recipe of docs/integration.md over the same frames, once
through emcv (Python) and once through emcv-python-reference (tests/python/reference.cpp, the C++ library
alone), compared byte for byte: every frame's counts, pooled sigma2 and lambda, and the final history states."""
import os
import subprocess

import numpy as np
import pytest

import emcv

WIDTH, HEIGHT, FRAMES = 24, 13, 30  # partial tiles on both axes


def frames(seed):
    """f, g and material per frame: a light that dims at frame 15, a noisy left half, a non-scattering border,
    two materials, one NaN f and one Inf g (refused pushes)."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH]
    material = np.where(y < HEIGHT // 2, 1, 2).astype(np.uint32)
    material[:, 0] = 0
    g0 = (0.3 + 0.5 * x / WIDTH).astype(np.float32)
    rho = np.where(x < WIDTH // 2, 0.4, 0.05)
    out = []
    for t in range(FRAMES):
        g = (g0 * (1.0 if t < 15 else 0.25)).astype(np.float32)
        f = (g * (1 + rho * rng.standard_normal(g.shape) / 3)).astype(np.float32)
        if t == 7:
            f[3, 4] = np.nan
            g[5, 6] = np.inf
        out.append((np.ascontiguousarray(f), np.ascontiguousarray(g), np.ascontiguousarray(material)))
    return out


def through_python(params, data, seed):
    history = emcv.History(WIDTH, HEIGHT, params.estimator)
    chunks = []
    for t, (f, g, material) in enumerate(data):
        plan = emcv.plan_frame(params, history, material=material, frame=t, seed=seed)
        emcv.sampling_update(params, history, f, g, plan.counts, material=material)
        chunks += [plan.counts.astype("<i4").tobytes(), plan.sigma2.astype("<f4").tobytes(),
                   np.float32(plan.lambda_).tobytes()]
        assert plan.samples == int(plan.counts.sum())
    return b"".join(chunks) + history.state.tobytes()


def through_cpp(params, data, seed, tmp_path):
    reference = os.environ.get("EMCV_PYTHON_REFERENCE")
    if not reference:
        pytest.fail("EMCV_PYTHON_REFERENCE is not set: run through ctest -L python")
    inputs, output = tmp_path / "frames.bin", tmp_path / "reference.bin"
    with open(inputs, "wb") as stream:
        for f, g, material in data:
            stream.write(f.tobytes() + g.tobytes() + material.tobytes())
    eta = params.eta if params.eta is not None else 0.0
    subprocess.run([reference, params.estimator, params.mode, str(WIDTH), str(HEIGHT), str(FRAMES),
                    repr(params.target), repr(params.budget), str(params.n_min), str(params.n_max), repr(eta), str(seed), str(inputs), str(output)],
                   check=True)
    return output.read_bytes()


@pytest.mark.parametrize("estimator", ["spvg", "cv", "cv_notex"])
@pytest.mark.parametrize("mode", ["quality_target", "budget"])
def test_python_equals_the_cpp_library_byte_for_byte(estimator, mode, tmp_path):
    params = emcv.SamplingParams(estimator, mode, target=5e-4, budget=6.0, n_min=1, n_max=48,
                                 eta=0.1 if estimator == "cv" else None)
    data = frames(seed=21)
    python = through_python(params, data, seed=13)
    cpp = through_cpp(params, data, seed=13, tmp_path=tmp_path)
    assert len(python) == len(cpp)
    assert python == cpp
    # the run is not trivial: the counts take many values over the run
    frame_bytes = WIDTH * HEIGHT * 8 + 4
    counts = [np.frombuffer(python[t * frame_bytes:][: WIDTH * HEIGHT * 4], dtype="<i4") for t in range(FRAMES)]
    assert len(np.unique(np.concatenate(counts))) > 3
