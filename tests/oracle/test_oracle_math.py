#!/usr/bin/python3
"""scripts/eval/oracle.py without a renderer: the allocation maths on sigma fields whose answers are worked out by
hand (below, beside each case), and the command line's bad-argument paths (one line, exit status 2, no stdout).

    /usr/bin/python3 tests/oracle/test_oracle_math.py
"""
import importlib.util
import math
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCRIPT = os.path.join(ROOT, "scripts", "eval", "oracle.py")
_spec = importlib.util.spec_from_file_location("oracle", SCRIPT)
oracle = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(oracle)


def half_half(a, b, n=1000):
    return np.array([a] * n + [b] * n, dtype=np.float64)


class Moments(unittest.TestCase):
    def test_two_values_half_half(self):
        # sigma in {1, 3}: E[s^2] = (1 + 9) / 2 = 5, E[s]^2 = 2^2 = 4, ratio 5/4.
        mean_square, square_mean, ratio = oracle.moments(half_half(1.0, 3.0))
        self.assertAlmostEqual(mean_square, 5.0, places=12)
        self.assertAlmostEqual(square_mean, 4.0, places=12)
        self.assertAlmostEqual(ratio, 1.25, places=12)
        self.assertAlmostEqual(oracle.db(ratio), 10 * math.log10(1.25), places=12)

    def test_constant_field_has_no_headroom(self):
        self.assertAlmostEqual(oracle.moments(np.full(100, 0.3))[2], 1.0, places=12)

    def test_half_zero(self):
        # sigma in {0, 2}: E[s^2] = 2, E[s]^2 = 1: allocation can halve the error by skipping the quiet half.
        self.assertAlmostEqual(oracle.moments(half_half(0.0, 2.0))[2], 2.0, places=12)

    def test_all_zero_is_an_error(self):
        with self.assertRaises(ValueError):
            oracle.moments(np.zeros(10))


class Kurtosis(unittest.TestCase):
    def test_known_distributions(self):
        # Two pixels over K = 4 samples: +-1 (two-point, kurtosis 1) and (0, 0, 0, 2) (m2 = 3/4, m4 = 21/16:
        # kurtosis 21/16 / (9/16) = 7/3); a third pixel never moves and is left out. The median of 1 and 7/3 is 5/3.
        lum = np.array([[1.0, 0.0, 5.0], [-1.0, 0.0, 5.0], [1.0, 0.0, 5.0], [-1.0, 2.0, 5.0]]).reshape(4, 1, 3)
        mask = np.ones((1, 3), dtype=bool)
        self.assertAlmostEqual(oracle.median_kurtosis(lum, mask), 5.0 / 3.0, places=12)

    def test_nothing_moves_is_an_error(self):
        with self.assertRaises(ValueError):
            oracle.median_kurtosis(np.ones((4, 1, 2)), np.ones((1, 2), dtype=bool))


class ClampedAllocation(unittest.TestCase):
    def check(self, sigma, budget, floor, cap, expected_lambda, expected_n, expected_ratio):
        lam, n, ratio = oracle.allocation_gain(sigma, budget, floor, cap)
        self.assertAlmostEqual(lam, expected_lambda, places=9)
        np.testing.assert_allclose(np.unique(n), expected_n, rtol=1e-12)
        self.assertAlmostEqual(ratio, expected_ratio, places=12)

    def test_bounds_not_binding_gives_the_unclamped_ratio(self):
        # sigma {1, 3}, B = 8: lambda (1 + 3) / 2 = 8 -> lambda 4, N {4, 12}, inside [1, 64].
        # MSE: uniform 5 / 8, allocated (1/4 + 9/12) / 2 = 1/2: ratio 5/4, as E[s^2] / E[s]^2.
        self.check(half_half(1.0, 3.0), 8, 1, 64, 4.0, [4.0, 12.0], 1.25)

    def test_floor_binding(self):
        # sigma {1, 3}, B = 8, floor 6: lambda 4 would give 4 < 6, so N = {6, 3 lambda}, (6 + 3 lambda) / 2 = 8,
        # lambda 10/3, N {6, 10}. MSE allocated (1/6 + 9/10) / 2 = 8/15; ratio (5/8) / (8/15) = 75/64.
        self.check(half_half(1.0, 3.0), 8, 6, 64, 10.0 / 3.0, [6.0, 10.0], 75.0 / 64.0)

    def test_cap_binding(self):
        # sigma {1, 3}, B = 48, cap 64: lambda 24 would give 72 > 64, so N = {lambda, 64}, (lambda + 64) / 2 = 48,
        # lambda 32, N {32, 64}. MSE uniform 5/48, allocated (1/32 + 9/64) / 2 = 11/128; ratio 640/528 = 40/33.
        self.check(half_half(1.0, 3.0), 48, 1, 64, 32.0, [32.0, 64.0], 40.0 / 33.0)

    def test_floor_and_cap_binding(self):
        # sigma {0.1, 1, 10} in thirds, floor 4, cap 64, B = 30: N = {4, lambda, 64} for 6.4 <= lambda <= 40,
        # (4 + lambda + 64) / 3 = 30 -> lambda 22. MSE uniform (0.01 + 1 + 100) / 3 / 30,
        # allocated (0.01/4 + 1/22 + 100/64) / 3.
        sigma = np.array([0.1] * 500 + [1.0] * 500 + [10.0] * 500)
        expected = ((0.01 + 1 + 100) / 3 / 30) / ((0.01 / 4 + 1 / 22 + 100 / 64) / 3)
        self.check(sigma, 30, 4, 64, 22.0, [4.0, 22.0, 64.0], expected)

    def test_budget_beyond_what_noisy_pixels_take(self):
        # sigma {0, 1}, B = 40, cap 64: the noisy half at 64 and the quiet half at the floor 1 average 32.5 < 40;
        # lambda is inf and the quiet half keeps the floor (extra samples there change no error).
        # MSE uniform (1/2) / 40, allocated (1/64) / 2: ratio 64/40 = 1.6.
        lam, n, ratio = oracle.allocation_gain(half_half(0.0, 1.0), 40, 1, 64)
        self.assertEqual(lam, math.inf)
        np.testing.assert_array_equal(np.unique(n), [1.0, 64.0])
        self.assertAlmostEqual(ratio, 1.6, places=12)

    def test_constant_field_allocates_uniformly(self):
        for budget, floor in ((8, 1), (12, 4), (16, 4)):
            lam, n, ratio = oracle.allocation_gain(np.full(50, 0.2), budget, floor, 64)
            self.assertAlmostEqual(lam, budget / 0.2, places=9)
            np.testing.assert_allclose(n, budget, rtol=1e-12)
            self.assertAlmostEqual(ratio, 1.0, places=12)

    def test_spends_the_budget_and_never_loses_to_uniform(self):
        # The clamped allocation is the optimum under the bounds, and uniform B is inside them: ratio >= 1.
        rng = np.random.default_rng(7)
        for trial in range(20):
            sigma = rng.lognormal(0.0, rng.uniform(0.1, 2.0), size=3000)
            sigma[rng.random(3000) < 0.05] = 0.0
            for budget in (8, 12, 16):
                for floor in (1, 4):
                    lam, n, ratio = oracle.allocation_gain(sigma, budget, floor, 64)
                    self.assertTrue(math.isfinite(lam))
                    self.assertAlmostEqual(float(np.mean(n)), budget, places=9)
                    self.assertTrue(np.all((n >= floor) & (n <= 64)))
                    self.assertGreaterEqual(ratio, 1.0 - 1e-12)
                    self.assertLessEqual(ratio, oracle.moments(sigma)[2] + 1e-12)

    def test_bad_bounds_are_errors(self):
        with self.assertRaises(ValueError):
            oracle.allocation_gain(half_half(1.0, 3.0), 4, 8, 64)  # budget below the floor
        with self.assertRaises(ValueError):
            oracle.allocation_gain(half_half(1.0, 3.0), 80, 1, 64)  # budget above the cap
        with self.assertRaises(ValueError):
            oracle.allocation_gain(np.zeros(4), 8, 1, 64)


class HeldOut(unittest.TestCase):
    def test_halves_that_agree_give_the_allocation_gain(self):
        sigma = half_half(1.0, 3.0)
        for budget, floor in ((8, 1), (8, 6), (48, 1)):
            self.assertAlmostEqual(oracle.held_out_gain(sigma, sigma, budget, floor, 64),
                                   oracle.allocation_gain(sigma, budget, floor, 64)[2], places=12)

    def test_halves_that_disagree_lose_to_uniform(self):
        # Half a says sigma {1, 3}, half b says {3, 1} on the same pixels. B = 8: N(a) = {4, 12}, N(b) = {12, 4}.
        # Judged on the other half: mean(b^2 / N(a)) = (9/4 + 1/12) / 2 = 7/6, and mean(a^2 / N(b)) = 7/6 too.
        # Uniform: (5 + 5) / 8 = 5/4. Ratio (5/4) / (7/3) = 15/28: allocating on noise costs 2.7 dB.
        a, b = half_half(1.0, 3.0), half_half(3.0, 1.0)
        self.assertAlmostEqual(oracle.held_out_gain(a, b, 8, 1, 64), 15.0 / 28.0, places=12)

    def test_below_the_gain_on_noisy_estimates_of_one_field(self):
        # sigma_i lognormal; each half estimates it from 5 Gaussian samples. Reading s as sigma overstates the
        # true gain, the held-out gain understates it.
        rng = np.random.default_rng(3)
        sigma = rng.lognormal(0.0, 0.7, size=20000)
        samples = rng.normal(0.0, 1.0, size=(10, sigma.size)) * sigma
        s_a, s_b = np.std(samples[:5], axis=0, ddof=1), np.std(samples[5:], axis=0, ddof=1)
        s = np.std(samples, axis=0, ddof=1)
        true = oracle.allocation_gain(sigma, 8, 1, 64)[2]
        self.assertLess(oracle.held_out_gain(s_a, s_b, 8, 1, 64), true)
        self.assertGreater(oracle.allocation_gain(s, 8, 1, 64)[2], true)
        self.assertGreater(oracle.moments(s)[2], oracle.moments(sigma)[2])


class Sigmas(unittest.TestCase):
    def test_sample_standard_deviation_over_frames_on_the_mask_only(self):
        # Pixel (0, 0) takes 0, 1, 2 over three frames: sample variance ((-1)^2 + 0 + 1^2) / (3 - 1) = 1.
        # Pixel (0, 1) takes 5, 5, 8: mean 6, variance (1 + 1 + 4) / 2 = 3. Pixel (1, 1) is outside the mask.
        lum = np.zeros((3, 2, 2))
        lum[:, 0, 0] = [0, 1, 2]
        lum[:, 0, 1] = [5, 5, 8]
        lum[:, 1, 1] = [0, 100, 0]
        mask = np.array([[True, True], [True, False]])
        np.testing.assert_allclose(oracle.pixel_sigmas(lum, mask), [1.0, math.sqrt(3.0), 0.0], rtol=1e-12)

    def test_a_pixel_that_never_moves_has_sigma_exactly_0(self):
        # 0.3 summed 49 times and divided by 49 is not 0.3 in binary floating point; sigma must still be 0.
        lum = np.full((49, 1, 2), 0.3)
        lum[:, 0, 1] = 0.1 * np.arange(49)
        sigma = oracle.pixel_sigmas(lum, np.array([[True, True]]))
        self.assertEqual(sigma[0], 0.0)
        self.assertGreater(sigma[1], 0.0)

    def test_gaussian_floor(self):
        # c4(2) = sqrt(2 / pi): 1 / c4^2 = pi / 2. c4 tends to 1 as K grows.
        self.assertAlmostEqual(oracle.gaussian_floor(2), math.pi / 2, places=12)
        self.assertLess(oracle.gaussian_floor(1000), 1.001)


class Usage(unittest.TestCase):
    def run_oracle(self, *args):
        return subprocess.run(["/usr/bin/python3", SCRIPT, *args], capture_output=True, text=True)

    def test_bad_arguments_are_one_line_and_status_2(self):
        with tempfile.TemporaryDirectory() as tmp:
            fake_demo = os.path.join(tmp, "emcv-demo")  # executable, never run: every case fails before
            with open(fake_demo, "w") as f:
                f.write("#!/bin/sh\nexit 3\n")
            os.chmod(fake_demo, 0o755)
            base = ["--scene", "static", "--demo", fake_demo, "--mask", "varying"]
            cases = {
                "no --scene": (["--demo", fake_demo], "--scene"),
                "a size without x": (base + ["--size", "64"], "--size"),
                "a zero size": (base + ["--size", "0x64"], "--size"),
                "one frame": (base + ["--frames", "1"], "--frames"),
                "frames not a number": (base + ["--frames", "five"], "--frames"),
                "a negative seed": (base + ["--seed", "-1"], "--seed"),
                "a seed list with a gap": (base + ["--seed", "1,,2"], "--seed"),
                "a seed given twice": (base + ["--seed", "1,2,01"], "--seed"),
                "a budget under a floor": (base + ["--budgets", "2,8", "--floors", "4"], "--budgets"),
                "a budget over the cap": (base + ["--budgets", "80"], "--budgets"),
                "a budget that is no number": (base + ["--budgets", "8,x"], "--budgets"),
                "two caps": (base + ["--cap", "32,64"], "--cap"),
                "a missing emcv-demo": (["--scene", "static", "--demo", os.path.join(tmp, "none")], "--demo"),
                "no emcv-eval beside it": (["--scene", "static", "--demo", fake_demo], "emcv-eval"),
                "an unknown mask": (base + ["--mask", "all"], "--mask"),
                "an unknown flag": (base + ["--budget", "8"], "--budget"),
                "--csv a folder": (base + ["--csv", tmp], "--csv"),
                "--out a file": (base + ["--out", fake_demo], "--out"),
            }
            for name, (args, word) in cases.items():
                with self.subTest(name):
                    r = self.run_oracle(*args)
                    self.assertEqual(r.returncode, 2, r.stderr)
                    self.assertEqual(r.stdout, "")
                    lines = r.stderr.strip().splitlines()
                    self.assertEqual(len(lines), 1, r.stderr)
                    self.assertTrue(lines[0].startswith("oracle.py: "), lines[0])
                    self.assertIn(word, lines[0])

    def test_help(self):
        r = self.run_oracle("--help")
        self.assertEqual(r.returncode, 0)
        for flag in ("--scene", "--size", "--frames", "--demo", "--out", "--csv"):
            self.assertIn(flag, r.stdout)


if __name__ == "__main__":
    unittest.main(verbosity=2)
