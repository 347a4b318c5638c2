#!/usr/bin/python3
"""How much an oracle could gain by spending a fixed sample budget unevenly across the SSS pixels of a static scene.

    /usr/bin/python3 scripts/eval/oracle.py --scene static [--size 128x128] [--frames 19] [--demo build/bin/emcv-demo]
        [--eval PATH] [--mask sss|varying] [--seed S[,S...]] [--out DIR] [--csv FILE]
        [--budgets 8,12,16] [--floors 1,4] [--cap 64]

It renders K = --frames one-sample frames of burley-1 with emcv-demo (PNG display frames under --out, or a
temporary folder), frames 0..K-1 of the scene, which differ only in their per-frame sample rotation, and takes,
per SSS pixel i, sigma_i: the sample standard deviation (divisor K - 1) over the K frames of the display
luminance Y = 0.2126 R + 0.7152 G + 0.0722 B of the stored sRGB-encoded values in [0, 1] (what PSNR compares).
sigma_i is then the noise of one sample at pixel i, and n samples there leave sigma_i^2 / n. Several seeds
(--seed 1,2,3) render the K frames once per seed and pool them: K x seeds samples per pixel, for a scene whose
static stretch is short (light-off's 30 frames before its switch); K below then counts the pooled samples.

With B samples per pixel everywhere the mean squared error is E[sigma^2] / B. Spending the same total as
N_i proportional to sigma_i minimises it at E[sigma]^2 / B, so E[sigma^2] / E[sigma]^2 is the headroom of any
per-pixel allocation that knows sigma exactly. A renderer also keeps a floor and a cap on N:
N_i = clamp(lambda sigma_i, n_min, cap), with lambda such that mean N_i = B, is the optimum under those bounds
(the Lagrangian of sum sigma_i^2 / N_i under the box constraints gives it), so its ratio
(E[sigma^2] / B) / mean(sigma_i^2 / N_i), is never below 1 while n_min <= B <= cap. N is real-valued here.

Those gains use the measured s_i as if it were sigma_i, and overstate the headroom: s_i from K samples scatters
around sigma_i, which widens the spread of sigma that allocation feeds on (E[s]^2 is biased low while E[s^2] is
not). The held-out gain bounds it from the other side: the samples are split in halves a and b, N is allocated
from s_a and its error read from s_b^2 (unbiased for sigma^2 and independent of N), and the other way round.
That is the gain of an allocation that knows K/2 samples per pixel, below what knowing sigma would give. The
headroom lies between the two; they close in as K grows (docs/results.md, "Allocation headroom").

The SSS pixels are the renderer's own mask (--mask sss, the default: emcv-eval --heatmaps writes it, --eval
beside --demo unless given), or the pixels whose luminance varies over the K frames (--mask varying: on a static
scene only scattering is random, but an SSS pixel whose 8-bit value never moved is then left out).

The scene must not change over frames 0..K-1: the reference, which emcv-demo renders beside burley-1 and
re-renders only when a light or the camera changes, must give K identical frames, or the run stops (use
frames before a light event: K <= 30 on light-off).

Output: Markdown tables on stdout; --csv FILE also writes the numbers. Exit status 0; 2 for bad arguments
(one line on stderr); 1 when a renderer run fails or the frames do not allow the measurement.
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
METHOD = "burley-1"
# Rec. 709 luminance weights, applied to the display values as stored.
LUMA = np.array([0.2126, 0.7152, 0.0722])
SUMMARY_HEADER = "| SSS pixels | sigma = 0 | E[sigma^2] | E[sigma]^2 | E[sigma^2] / E[sigma]^2 | gain (dB) |"
ALLOCATION_HEADER = ("| budget B | floor n_min | cap | lambda | mean N | pixels at floor | pixels at cap "
                     "| MSE uniform / allocated | gain (dB) | held-out gain (dB) |")


class UsageError(Exception):
    """Bad arguments: exit status 2."""


class MeasurementError(Exception):
    """A renderer run failed or its frames cannot be measured: exit status 1."""


# ---- the allocation maths (tests/oracle/test_oracle_math.py checks it on fields with known answers) ----

def pixel_sigmas(luminance, mask):
    """Per masked pixel, the sample standard deviation over frames (divisor K - 1) of luminance[K, H, W]."""
    if luminance.shape[0] < 2:
        raise ValueError("need at least 2 frames for a standard deviation")
    values = luminance[:, mask]
    sigma = np.std(values, axis=0, ddof=1)
    # The mean of equal values need not round back to them (K = 49 copies of one value, say), which leaves a
    # pixel that never moved with a sigma of 1e-17 instead of 0.
    sigma[np.all(values == values[0], axis=0)] = 0.0
    return sigma


def median_kurtosis(luminance, mask):
    """The median over masked pixels that move of the kurtosis m4 / m2^2 of their samples (a Gaussian's is 3):
    how heavy the noise's tails are, which sets how many samples a variance estimate needs."""
    values = luminance[:, mask].astype(np.float64)
    centred = values - values.mean(axis=0)
    m2 = np.mean(centred ** 2, axis=0)
    moving = m2 > 0
    if not np.any(moving):
        raise ValueError("no pixel moves")
    return float(np.median(np.mean(centred[:, moving] ** 4, axis=0) / m2[moving] ** 2))


def moments(sigma):
    """(E[sigma^2], E[sigma]^2, their ratio): the uniform allocation's MSE over the proportional one's."""
    sigma = np.asarray(sigma, dtype=np.float64)
    if sigma.size == 0:
        raise ValueError("no pixels")
    mean_square = float(np.mean(sigma * sigma))
    square_mean = float(np.mean(sigma)) ** 2
    if square_mean == 0.0:
        raise ValueError("every sigma is 0: nothing to allocate")
    return mean_square, square_mean, mean_square / square_mean


def clamped_allocation(sigma, budget, floor, cap):
    """N_i = clamp(lambda sigma_i, floor, cap) with mean N_i = budget; returns (lambda, N).

    mean N is continuous and non-decreasing in lambda, so bisection brackets the segment on which it is linear,
    and that segment's equation gives lambda exactly. Pixels with sigma 0 stay at the floor whatever lambda is:
    when the budget exceeds what the others can take at the cap, lambda is inf and mean N < budget (those extra
    samples would go to pixels with no noise and change no error)."""
    sigma = np.asarray(sigma, dtype=np.float64)
    if not (0 < floor <= budget <= cap):
        raise ValueError(f"need 0 < floor <= budget <= cap, got floor {floor}, budget {budget}, cap {cap}")
    if sigma.size == 0 or np.any(sigma < 0) or not np.all(np.isfinite(sigma)):
        raise ValueError("sigma must be a non-empty array of finite non-negative values")

    def mean_n(lam):
        return float(np.mean(np.clip(lam * sigma, floor, cap)))

    positive = sigma[sigma > 0]
    if positive.size == 0:
        raise ValueError("every sigma is 0: nothing to allocate")
    lo, hi = 0.0, cap / float(positive.min())  # mean N at hi: every pixel with noise at the cap
    if mean_n(hi) <= budget:
        return math.inf, np.where(sigma > 0, float(cap), float(floor))
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mean_n(mid) < budget:
            lo = mid
        else:
            hi = mid
        at_floor_lo, at_cap_lo = lo * sigma <= floor, lo * sigma >= cap
        if np.array_equal(at_floor_lo, hi * sigma <= floor) and np.array_equal(at_cap_lo, hi * sigma >= cap):
            break
    lam = 0.5 * (lo + hi)
    at_floor, at_cap = lam * sigma <= floor, lam * sigma >= cap
    free = ~(at_floor | at_cap)
    free_sum = float(np.sum(sigma[free]))
    if free_sum > 0:
        exact = (budget * sigma.size - floor * np.count_nonzero(at_floor) - cap * np.count_nonzero(at_cap)) / free_sum
        # The segment's solution lies in [lo, hi] up to the rounding of the sums (a bracket end can be it).
        slack = 1e-9 * hi
        if lo - slack <= exact <= hi + slack:
            lam = exact
    return lam, np.clip(lam * sigma, floor, cap)


def allocation_gain(sigma, budget, floor, cap):
    """(lambda, N, MSE of B everywhere / MSE of the clamped allocation)."""
    sigma = np.asarray(sigma, dtype=np.float64)
    lam, n = clamped_allocation(sigma, budget, floor, cap)
    uniform = float(np.mean(sigma * sigma)) / budget
    allocated = float(np.mean(sigma * sigma / n))
    if allocated == 0.0:
        raise ValueError("every sigma is 0: nothing to allocate")
    return lam, n, uniform / allocated


def held_out_gain(sigma_a, sigma_b, budget, floor, cap):
    """MSE of B everywhere / MSE of the clamped allocation, each half's allocation judged on the other half's
    sigma^2: (mean(a^2) + mean(b^2)) / B over mean(b^2 / N(a)) + mean(a^2 / N(b))."""
    a, b = np.asarray(sigma_a, dtype=np.float64), np.asarray(sigma_b, dtype=np.float64)
    if a.shape != b.shape:
        raise ValueError("the halves must have one sigma per pixel each")
    _, n_a = clamped_allocation(a, budget, floor, cap)
    _, n_b = clamped_allocation(b, budget, floor, cap)
    uniform = (float(np.mean(a * a)) + float(np.mean(b * b))) / budget
    allocated = float(np.mean(b * b / n_a)) + float(np.mean(a * a / n_b))
    if allocated == 0.0:
        raise ValueError("every sigma is 0: nothing to allocate")
    return uniform / allocated


def db(ratio):
    return 10.0 * math.log10(ratio)


def gaussian_floor(k):
    """E[s^2] / E[s]^2 of K Gaussian samples with one sigma everywhere: 1 / c4(K)^2, the ratio a field with no
    spread of sigma at all reads as, from the estimation noise of s alone."""
    c4 = math.sqrt(2.0 / (k - 1)) * math.exp(math.lgamma(k / 2.0) - math.lgamma((k - 1) / 2.0))
    return 1.0 / (c4 * c4)


# ---- the command line ----

def parse_size(text):
    parts = text.split("x")
    if len(parts) != 2 or not all(p.isdigit() for p in parts):
        raise UsageError(f"--size: expected WxH, got '{text}'")
    w, h = int(parts[0]), int(parts[1])
    if not (1 <= w <= 8192 and 1 <= h <= 8192):
        raise UsageError(f"--size: each side must be 1..8192, got '{text}'")
    return w, h


def parse_list(flag, text, low, high):
    values = []
    for item in text.split(","):
        try:
            v = float(item)
        except ValueError:
            raise UsageError(f"{flag}: expected numbers separated by commas, got '{text}'") from None
        if not (low <= v <= high) or not math.isfinite(v):
            raise UsageError(f"{flag}: each value must be in {low:g}..{high:g}, got '{item}'")
        values.append(v)
    return values


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def parse_args(argv):
    # allow_abbrev off: a misspelt flag such as --budget must be an error, not --budgets.
    p = Parser(prog="oracle.py", allow_abbrev=False, description="The headroom of per-pixel sample allocation on a static scene "
                                            "(see the module docstring: /usr/bin/python3 -m pydoc ./scripts/eval/oracle.py).")
    p.add_argument("--scene", required=True, metavar="FILE|NAME",
                   help="scene file or built-in scene name (emcv-demo --scene)")
    p.add_argument("--size", default="128x128", metavar="WxH", help="image size (default 128x128)")
    p.add_argument("--frames", default="19", metavar="K", help="frames 0..K-1, K in 2..100000 (default 19)")
    p.add_argument("--demo", default=os.path.join(ROOT, "build", "bin", "emcv-demo"), metavar="PATH",
                   help="emcv-demo (default build/bin/emcv-demo)")
    p.add_argument("--eval", metavar="PATH", help="emcv-eval, for the SSS mask (default: beside --demo)")
    p.add_argument("--mask", default="sss", choices=["sss", "varying"],
                   help="sss: the renderer's mask (default); varying: pixels whose luminance varies")
    p.add_argument("--seed", default="1", metavar="S[,S...]",
                   help="emcv-demo --seed; a list pools the K frames of each seed (default 1)")
    p.add_argument("--out", metavar="DIR", help="keep the frames under DIR (default: a temporary folder, removed)")
    p.add_argument("--csv", metavar="FILE", help="also write the numbers as CSV to FILE")
    p.add_argument("--budgets", default="8,12,16", metavar="B[,B...]",
                   help="mean samples per SSS pixel (default 8,12,16)")
    p.add_argument("--floors", default="1,4", metavar="N[,N...]", help="floors n_min (default 1,4)")
    p.add_argument("--cap", default="64", metavar="N", help="cap on N (default 64)")
    a = p.parse_args(argv)

    a.width, a.height = parse_size(a.size)
    if not a.frames.isdigit() or not (2 <= int(a.frames) <= 100000):
        raise UsageError(f"--frames: expected an integer in 2..100000, got '{a.frames}'")
    a.frames = int(a.frames)
    a.seeds = a.seed.split(",")
    if not all(v.isdigit() and int(v) < 2 ** 32 for v in a.seeds):
        raise UsageError(f"--seed: expected integers in 0..4294967295 separated by commas, got '{a.seed}'")
    a.seeds = [str(int(v)) for v in a.seeds]
    if len(set(a.seeds)) != len(a.seeds):
        raise UsageError(f"--seed: a seed given twice renders the same frames twice: '{a.seed}'")
    a.cap = parse_list("--cap", a.cap, 1, 1024)
    if len(a.cap) != 1:
        raise UsageError("--cap: expected one number")
    a.cap = a.cap[0]
    a.budgets = parse_list("--budgets", a.budgets, 1, a.cap)
    a.floors = parse_list("--floors", a.floors, 1, a.cap)
    if min(a.budgets) < max(a.floors):
        raise UsageError(f"--budgets: each budget must be at least the largest floor ({max(a.floors):g})")
    for flag, path in (("--demo", a.demo), ("--eval", a.eval)):
        if path is not None and not (os.path.isfile(path) and os.access(path, os.X_OK)):
            raise UsageError(f"{flag}: not an executable file: '{path}'")
    if a.mask == "sss" and a.eval is None:
        a.eval = os.path.join(os.path.dirname(os.path.abspath(a.demo)), "emcv-eval")
        if not (os.path.isfile(a.eval) and os.access(a.eval, os.X_OK)):
            raise UsageError(f"--mask sss needs emcv-eval, not found beside --demo ('{a.eval}'): "
                             "pass --eval PATH or --mask varying")
    if a.csv is not None and os.path.isdir(a.csv):
        raise UsageError(f"--csv: '{a.csv}' is a folder")
    if a.out is not None and os.path.exists(a.out) and not os.path.isdir(a.out):
        raise UsageError(f"--out: '{a.out}' exists and is not a folder")
    return a


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        last = (r.stderr.strip().splitlines() or ["(no message)"])[-1]
        # emcv-demo's own usage errors (a bad --scene, say) are this tool's bad arguments.
        err = UsageError if r.returncode == 2 else MeasurementError
        raise err(f"{os.path.basename(cmd[0])} failed ({r.returncode}): {last}")
    return r.stdout


def read_luminance(path):
    import matplotlib.image  # only here: the maths above is usable without matplotlib
    rgb = np.asarray(matplotlib.image.imread(path), dtype=np.float64)
    if rgb.ndim != 3 or rgb.shape[2] < 3:
        raise MeasurementError(f"{path}: expected an RGB image")
    if rgb.max() > 1.0:  # a reader that returns 8-bit integers
        rgb = rgb / 255.0
    return rgb[:, :, :3] @ LUMA


def read_frames(folder, k):
    frames = []
    for f in range(k):
        path = os.path.join(folder, f"frame-{f:04d}.png")
        if not os.path.isfile(path):
            raise MeasurementError(f"{path}: missing (emcv-demo wrote no frame {f})")
        frames.append(read_luminance(path))
    return np.stack(frames)


def sss_mask(a, work):
    """The renderer's sss_mask of frame 0 (the scene is static, so every frame's), top row first as the PNGs."""
    folder = os.path.join(work, "mask")
    run([a.eval, "--scene", a.scene, "--method", METHOD, "--size", f"{a.width}x{a.height}", "--frames", "1",
         "--seed", a.seeds[0], "--heatmaps", "0", "--heatmap-dir", folder])
    mask = np.loadtxt(os.path.join(folder, f"{METHOD}.f0.mask.csv"), delimiter=",", ndmin=2)
    if mask.shape != (a.height, a.width):
        raise MeasurementError(f"emcv-eval's mask is {mask.shape[1]}x{mask.shape[0]}, not {a.width}x{a.height}")
    return mask > 0.5


def render(a, seed, folder):
    """The luminance of frames 0..K-1 of burley-1 for one seed, after checking that the scene holds still."""
    run([a.demo, "--scene", a.scene, "--method", METHOD, "--size", f"{a.width}x{a.height}",
         "--frames", str(a.frames), "--seed", seed, "--out", folder])
    reference = read_frames(os.path.join(folder, "reference"), a.frames)
    changed = [f for f in range(1, a.frames) if not np.array_equal(reference[f], reference[0])]
    if changed:
        raise MeasurementError(f"the scene changes at frame {changed[0]} (the reference differs from frame 0): "
                               f"the measurement needs frames 0..{a.frames - 1} static; use fewer --frames")
    return read_frames(os.path.join(folder, METHOD), a.frames)


def measure(a, work):
    """(luminance[samples, H, W], SSS mask, how the mask was found); samples = K x seeds, seed after seed."""
    single = len(a.seeds) == 1
    lum = np.concatenate([render(a, seed, work if single else os.path.join(work, f"seed-{seed}"))
                          for seed in a.seeds])
    if lum.shape[1:] != (a.height, a.width):
        raise MeasurementError(f"the frames are {lum.shape[2]}x{lum.shape[1]}, not {a.width}x{a.height}")
    if a.mask == "sss":
        mask, how = sss_mask(a, work), "the renderer's sss_mask (emcv-eval --heatmaps 0)"
    else:
        mask, how = np.any(lum != lum[0], axis=0), "pixels whose luminance varies over the frames"
    if not mask.any():
        raise MeasurementError("no SSS pixel in the image")
    return lum, mask, how


def report(a, lum, mask, how):
    sigma = pixel_sigmas(lum, mask)
    samples = lum.shape[0]
    try:
        mean_square, square_mean, ratio = moments(sigma)
    except ValueError as e:
        raise MeasurementError(f"{e} (over {sigma.size} SSS pixels)") from None
    # Halves of at least 2 samples each, for a standard deviation in each.
    halves = None
    if samples >= 4:
        halves = pixel_sigmas(lum[:samples // 2], mask), pixel_sigmas(lum[samples // 2:], mask)
    zero = int(np.count_nonzero(sigma == 0))
    seeds = ("seed " if len(a.seeds) == 1 else "seeds ") + ", ".join(a.seeds)
    lines = [
        f"## Allocation headroom: {a.scene}, {a.width}x{a.height}, frames 0-{a.frames - 1} of {METHOD}, {seeds}: "
        f"K = {samples} samples per pixel",
        "",
        f"sigma: per SSS pixel, the sample standard deviation (K - 1) of the display luminance over the K samples; "
        f"SSS pixels: {how}.",
        "",
        SUMMARY_HEADER,
        "|---|---|---|---|---|---|",
        f"| {sigma.size} | {zero} | {mean_square:.6g} | {square_mean:.6g} | {ratio:.4f} | {db(ratio):.2f} |",
        "",
        f"Clamped proportional allocation N_i = clamp(lambda sigma_i, n_min, cap), mean N_i = B; "
        f"gain = (E[sigma^2] / B) / mean(sigma_i^2 / N_i); held-out: N from one half of the samples, "
        f"its error from the other half, both ways:",
        "",
        ALLOCATION_HEADER,
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    rows = [{"allocation": "proportional", "budget": "", "floor": "", "cap": "", "lambda": "", "mean_n": "",
             "at_floor": "", "at_cap": "", "mse_ratio": ratio, "held_out": None}]
    for budget in a.budgets:
        for floor in a.floors:
            lam, n, r = allocation_gain(sigma, budget, floor, a.cap)
            held_out = None
            if halves is not None:
                try:
                    held_out = held_out_gain(halves[0], halves[1], budget, floor, a.cap)
                except ValueError:
                    pass  # a half in which no pixel moved: nothing to allocate from, the cell says n/a
            at_floor = int(np.count_nonzero(n <= floor))
            at_cap = int(np.count_nonzero(n >= a.cap))
            held = "n/a" if held_out is None else f"{db(held_out):.2f}"
            lines.append(f"| {budget:g} | {floor:g} | {a.cap:g} | {lam:.6g} | {float(np.mean(n)):.3f} | {at_floor} "
                         f"| {at_cap} | {r:.4f} | {db(r):.2f} | {held} |")
            rows.append({"allocation": "clamped", "budget": budget, "floor": floor, "cap": a.cap, "lambda": lam,
                         "mean_n": float(np.mean(n)), "at_floor": at_floor, "at_cap": at_cap, "mse_ratio": r,
                         "held_out": held_out})
    lines += [
        "",
        f"The gains read s_i as sigma_i and overstate the headroom, the held-out gains (N from half the samples) "
        f"understate it; the two close in as K grows. Estimation noise alone: a field with one sigma "
        f"everywhere, Gaussian noise, reads as E[s^2] / E[s]^2 = 1 / c4(K)^2 = {gaussian_floor(samples):.4f} "
        f"({db(gaussian_floor(samples)):.2f} dB) at K = {samples}; heavier-tailed noise reads higher.",
        "",
        f"Median per-pixel kurtosis of the K samples (a Gaussian's is 3): {median_kurtosis(lum, mask):.2f}.",
    ]
    print("\n".join(lines))
    if a.csv:
        tmp = a.csv + ".tmp"
        with open(tmp, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["scene", "width", "height", "frames", "seeds", "samples", "mask", "sss_pixels",
                        "zero_sigma_pixels", "e_sigma2", "e_sigma_squared", "allocation", "budget", "floor", "cap",
                        "lambda", "mean_n", "at_floor", "at_cap", "mse_ratio", "gain_db", "held_out_mse_ratio",
                        "held_out_gain_db"])
            for row in rows:
                held_out = row["held_out"]
                w.writerow([a.scene, a.width, a.height, a.frames, ";".join(a.seeds), samples, a.mask, sigma.size,
                            zero, repr(mean_square), repr(square_mean), row["allocation"], row["budget"],
                            row["floor"], row["cap"], row["lambda"], row["mean_n"], row["at_floor"], row["at_cap"],
                            repr(row["mse_ratio"]), repr(db(row["mse_ratio"])),
                            "" if held_out is None else repr(held_out), "" if held_out is None else repr(db(held_out))])
        os.replace(tmp, a.csv)


def main(argv):
    try:
        a = parse_args(argv)
        if a.out:
            os.makedirs(a.out, exist_ok=True)
            work, temporary = a.out, False
        else:
            work, temporary = tempfile.mkdtemp(prefix="emcv-oracle-"), True
        try:
            report(a, *measure(a, work))
        finally:
            if temporary:
                shutil.rmtree(work, ignore_errors=True)
    except UsageError as e:
        sys.stderr.write(f"oracle.py: {e}\n")
        return 2
    except (MeasurementError, OSError) as e:
        sys.stderr.write(f"oracle.py: {e}\n")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
