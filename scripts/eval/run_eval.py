#!/usr/bin/python3
"""The renderer's evaluation: what each SSS method's accuracy costs in time (docs/results.md).

One command regenerates every figure and table of docs/results/ and the generated blocks of docs/results.md:
    /usr/bin/python3 scripts/eval/run_eval.py [--build build] [--size 128x128] [--seeds 1,2] [--quick]

It needs build/bin/emcv-demo, emcv-eval and emcv-golden (cmake --build build --target emcv-demo emcv-eval
emcv-golden) and
runs them headless (EGL; Mesa llvmpipe here, so every time is a CPU rasteriser's time: docs/results.md says
what that means). Stages, each writing its raw CSV under docs/results/raw/ first:
  quality  emcv-demo over static, light-off, flicker, club: burley-1..64, separable-11/17/25, diffuse, and the
           adaptive methods at each knob setting; PSNR against the reference (emcv-demo's metrics), SSS ms.
  switch   emcv-eval on light-off, flicker, club: samples and SSS ms per frame, with the light curves.
  heatmap  emcv-eval on light-off: sample counts before and after the switch, cv's alpha.
  scaling  emcv-eval: SSS ms and samples against resolution and against the scattering radius (--sss-scale).
  spread   emcv-golden: the golden cases rendered with seed 2 against the goldens (seed 1): how far an image
           moves when every sample position moves, the bound for the tolerance another GPU needs.
The adaptive knobs (target variance, N max) are tunables of the shared port (include/emcv/port/history.h,
EMCV_HISTORY_TARGET / EMCV_HISTORY_N_MAX) that the renderer compiles into its GLSL at run time: each setting
is passed as `--define NAME=VALUE`. The adaptive methods are the rows of emcv-demo --list-methods whose
passes are "adaptive" (the method table).
--plots-only redraws from the raw CSVs without rendering. Outputs are written to temporary names and renamed.
"""
import argparse
import csv
import io
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RESULTS = os.path.join(ROOT, "docs", "results")
RAW = os.path.join(RESULTS, "raw")
DOC = os.path.join(ROOT, "docs", "results.md")

QUALITY_SCENES = ["static", "light-off", "flicker", "club"]
# Frames per quality run: light-off whole (30 frames on each side of the switch), flicker through its bursts at
# 8, 20 and 23, club over two periods of its fastest light (14 frames), static long enough to converge.
QUALITY_FRAMES = {"static": 16, "light-off": 60, "flicker": 30, "club": 30}
FIXED_METHODS = ["diffuse"] + [f"burley-{n}" for n in (1, 2, 4, 8, 16, 32, 64)] + \
                [f"separable-{t}" for t in (11, 17, 25)]
ADAPTIVE = []  # filled from emcv-demo --list-methods in main()
DEFAULT_TARGET, DEFAULT_NMAX = 1e-4, 64
# (target variance, N max): the target sweep at SPVG's N max, then N max at SPVG's target.
ADAPTIVE_KNOBS = [(4e-4, 64), (1e-4, 64), (2.5e-5, 64), (1e-4, 32), (1e-4, 16)]
SWITCH_FRAME = 30  # light-off: the key light's step (demo/scenes/light-off.json)
# The paper's teaser (Xie & Olano 2021, Fig. 1): SSS sampling pass ms and PSNR after the switch.
PAPER = {"separable": (4.0, None), "spvg": (12.9, 48.6), "cv": (5.2, 47.5)}
SCALING_SIZES = [(128, 128), (256, 256), (512, 288), (640, 360), (960, 540), (1280, 720)]
SCALING_RADII = [0.25, 0.5, 1, 2, 4, 8]
COST_METHODS = ["burley-16", "separable-17", "spvg", "cv", "cv-notex"]


def die(msg):
    sys.exit(f"run_eval.py: {msg}")


def knob_label(target, nmax):
    return f"t{target:g}-n{nmax}"


def write_atomically(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def run(cmd, env=None):
    r = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if r.returncode != 0:
        die(f"{' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()[-500:]}")
    return r.stdout


def snapshot_shaders(tmp):
    """A copy of shaders/ taken once: every run of this evaluation compiles the same GLSL, even while the
    source tree changes under it."""
    d = os.path.join(tmp, "shaders")
    if not os.path.isdir(d):
        shutil.copytree(os.path.join(ROOT, "shaders"), d)
    return d


def renderer_env(tmp):
    """Snapshots of shaders/ and include/ taken once: every run of this evaluation compiles the same GLSL."""
    env = dict(os.environ)
    env["EMCV_SHADER_DIR"] = snapshot_shaders(tmp)
    d = os.path.join(tmp, "include")
    if not os.path.isdir(d):
        shutil.copytree(os.path.join(ROOT, "include"), d)
    env["EMCV_INCLUDE_DIR"] = d
    return env


def knob_defines(target, nmax):
    """The renderer's --define arguments for a knob setting (validated by the renderer)."""
    return ["--define", f"EMCV_HISTORY_TARGET={target:.6e}", "--define", f"EMCV_HISTORY_N_MAX={nmax}"]


def methods_from_table(build, passes):
    """Method names whose row in the method table records the given SSS passes (emcv-demo --list-methods)."""
    rows = [line.split("\t") for line in run([os.path.join(build, "bin", "emcv-demo"), "--list-methods"]).splitlines()]
    return [r[0] for r in rows if len(r) >= 2 and r[1] == passes]


def read_csv_text(text):
    return list(csv.DictReader(io.StringIO(text)))


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def to_float(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


# ---------------------------------------------------------------------------------------------------- stages

def stage_quality(a, tmp):
    """emcv-demo runs: one per scene and seed for the fixed methods, one per adaptive knob setting."""
    rows = []
    demo = os.path.join(a.build, "bin", "emcv-demo")
    for scene in QUALITY_SCENES:
        for seed in a.seeds:
            jobs = [("fixed", FIXED_METHODS, [])]
            jobs += [(knob_label(t, n), ADAPTIVE, knob_defines(t, n)) for t, n in ADAPTIVE_KNOBS]
            env = renderer_env(tmp)
            for label, methods, defines in jobs:
                out = os.path.join(tmp, f"q-{scene}-{seed}-{label}")
                cmd = [demo, "--scene", scene, "--method", ",".join(methods), "--size", a.size,
                       "--seed", str(seed), "--out", out] + defines
                cmd += ["--frames", str(a.frames or QUALITY_FRAMES[scene])]
                print(f"  quality: {scene} seed {seed} {label}", flush=True)
                first = run(cmd, env).splitlines()[0]  # "scene S, WxH, N frames, seed S, <GL renderer>"
                write_atomically(os.path.join(RAW, "device.txt"), first.split(", seed ")[-1].split(", ", 1)[-1] + "\n")
                for r in read_csv(os.path.join(out, "metrics.csv")):
                    r.update(scene=scene, seed=seed, knobs=label)
                    rows.append(r)
                shutil.rmtree(out)
    return rows


def stage_cost(a, tmp, scene, methods, size, frames, sss_scale=1.0, heatmaps=None):
    cmd = [os.path.join(a.build, "bin", "emcv-eval"), "--scene", scene, "--method", ",".join(methods),
           "--size", size, "--frames", str(frames), "--sss-scale", str(sss_scale)]
    if heatmaps:
        cmd += ["--heatmaps", ",".join(str(f) for f in heatmaps[0]), "--heatmap-dir", heatmaps[1]]
    return read_csv_text(run(cmd, renderer_env(tmp)))


def compact(value):
    """A number as 6 significant digits (the raw CSVs stay small; every table prints 1-4 digits), else as is."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        return value
    return value if x != x or x in (float("inf"), float("-inf")) or str(value).isdigit() else f"{x:.6g}"


def save_rows(name, rows):
    if not rows:
        return
    keys = list(rows[0].keys())
    s = io.StringIO()
    w = csv.DictWriter(s, fieldnames=keys, lineterminator="\n")
    w.writeheader()
    w.writerows({k: compact(v) for k, v in r.items()} for r in rows)
    write_atomically(os.path.join(RAW, name), s.getvalue())


def stage_spread(a, tmp):
    golden = os.path.join(a.build, "bin", "emcv-golden")
    out = os.path.join(tmp, "seed2")
    print("  spread: golden cases with seed 2", flush=True)
    run([golden, "render", "--seed", "2", "--out", out], renderer_env(tmp))
    rows = []
    pattern = re.compile(r"^(\w+): (\d+) of (\d+) pixels over \S+ \(([\d.]+)%.*max ([\d.e+-]+) at .*RMSE ([\d.e+-]+)")
    for name in sorted(os.listdir(out)):
        r = subprocess.run([golden, "compare", os.path.join(out, name),
                            os.path.join(ROOT, "tests", "image", "golden", name)], capture_output=True, text=True)
        m = pattern.match(r.stdout.strip())
        if not m:
            die(f"emcv-golden compare {name}: unexpected output {r.stdout!r} {r.stderr!r}")
        rows.append({"image": name, "verdict": m.group(1), "failing_percent": m.group(4),
                     "max_error": m.group(5), "rmse": m.group(6)})
    return rows


def spread_table(rows):
    """Per method (over scenes): the largest share of pixels over the golden tolerance and the largest RMSE."""
    by = {}
    for r in rows:
        parts = r["image"].split(".")
        kind = "samples" if ".spp." in r["image"] else "display"
        by.setdefault((parts[1], kind), []).append(r)
    lines = ["| method | image | worst failing pixels % (scene) | worst RMSE (x 255) | worst max difference (x 255) |",
             "|---|---|---:|---:|---:|"]
    for (method, kind), rs in sorted(by.items()):
        worst = max(rs, key=lambda r: float(r["failing_percent"]))
        scale = 65535 if kind == "samples" else 255
        lines.append(f"| {method} | {kind} | {float(worst['failing_percent']):.2f} ({worst['image'].split('.')[0]}) | "
                     f"{max(float(r['rmse']) for r in rs) * scale:.2f} | "
                     f"{max(float(r['max_error']) for r in rs) * scale:.0f} |")
    return "\n".join(lines)


# ---------------------------------------------------------------------------------------------------- summaries

def median(xs):
    xs = [x for x in xs if not math.isnan(x)]
    return statistics.median(xs) if xs else math.nan


def mean_finite(xs):
    xs = [x for x in xs if math.isfinite(x)]
    return statistics.fmean(xs) if xs else math.nan


def summarize_quality(rows, first_frame=1, last_frame=None):
    """(scene, method, knobs) -> dict: SSS ms median over frames and seeds (frame 0 is warm-up), PSNR mean."""
    groups = {}
    for r in rows:
        f = int(r["frame"])
        if f < first_frame or (last_frame is not None and f > last_frame) or r["method"] == "reference":
            continue
        groups.setdefault((r["scene"], r["method"], r["knobs"]), []).append(r)
    out = {}
    for k, rs in groups.items():
        out[k] = {
            "sss_ms": median([to_float(r["sss_ms"]) for r in rs]),
            "psnr_db": mean_finite([to_float(r["psnr_db"]) for r in rs]),
            "psnr_sss_db": mean_finite([to_float(r["psnr_sss_db"]) for r in rs]),
            "mean_spp": mean_finite([to_float(r["mean_spp"]) for r in rs]),
            "temporal_error": mean_finite([to_float(r["temporal_error"]) for r in rs]),
            "n": len(rs),
        }
    return out


# ---------------------------------------------------------------------------------------------------- plots

def plt_module():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save_fig(fig, name):
    path = os.path.join(RESULTS, name)
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=110, bbox_inches="tight")
    os.replace(tmp, path)
    plt_module().close(fig)


def plot_pareto(summary, device):
    plt = plt_module()
    colours = {"burley": "tab:blue", "separable": "tab:orange", "spvg": "tab:red", "cv": "tab:green",
               "cv-notex": "tab:purple", "diffuse": "black"}
    for scene in QUALITY_SCENES:
        fig, ax = plt.subplots(figsize=(7.5, 5))
        curves = {
            "burley": [(f"burley-{n}", "fixed", str(n)) for n in (1, 2, 4, 8, 16, 32, 64)],
            "separable": [(f"separable-{t}", "fixed", f"{t} taps") for t in (11, 17, 25)],
        }
        for m in ADAPTIVE:
            curves[m] = [(m, knob_label(t, n), f"{t:g}") for t, n in ADAPTIVE_KNOBS if n == DEFAULT_NMAX]
        for family, points in curves.items():
            xs, ys, labels = [], [], []
            for method, knobs, label in points:
                s = summary.get((scene, method, knobs))
                if s and math.isfinite(s["psnr_db"]):
                    xs.append(s["sss_ms"]); ys.append(s["psnr_db"]); labels.append(label)
            if not xs:
                continue
            ax.plot(xs, ys, "o-", color=colours[family], label=family)
            for x, y, l in zip(xs, ys, labels):
                ax.annotate(l, (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
        for m in ADAPTIVE:  # the N max variants at SPVG's target, as open markers
            for t, n in ADAPTIVE_KNOBS:
                s = summary.get((scene, m, knob_label(t, n)))
                if n != DEFAULT_NMAX and s and math.isfinite(s["psnr_db"]):
                    ax.plot([s["sss_ms"]], [s["psnr_db"]], "s", mfc="none", color=colours[m])
                    ax.annotate(f"N<={n}", (s["sss_ms"], s["psnr_db"]), fontsize=7, xytext=(3, -9),
                                textcoords="offset points", color=colours[m])
        d = summary.get((scene, "diffuse", "fixed"))
        if d and math.isfinite(d["psnr_db"]):
            ax.axhline(d["psnr_db"], color="black", lw=0.8, ls=":", label="diffuse (no SSS)")
        ax.set_xscale("log")
        ax.set_xlabel("SSS pass time, ms (median over frames and seeds; log)")
        ax.set_ylabel("PSNR vs reference, dB (display image, mean over frames)")
        ax.set_title(f"{scene}: time vs quality ({device})", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="lower right")
        save_fig(fig, f"pareto-{scene}.png")


def parse_lights(text):
    out = {}
    for item in text.split(";"):
        if "=" in item:
            k, v = item.split("=", 1)
            out[k] = float(v)
    return out


def plot_switch(rows_by_scene, device):
    plt = plt_module()
    colours = {"separable-17": "tab:orange", "spvg": "tab:red", "cv": "tab:green", "cv-notex": "tab:purple"}
    for scene, rows in rows_by_scene.items():
        fig, axes = plt.subplots(3, 1, figsize=(7.5, 7), sharex=True, gridspec_kw={"height_ratios": [3, 3, 1.4]})
        for m, c in colours.items():
            rs = sorted((r for r in rows if r["method"] == m), key=lambda r: int(r["frame"]))
            fr = [int(r["frame"]) for r in rs]
            axes[0].plot(fr, [to_float(r["mean_spp"]) for r in rs], color=c, label=m)
            # Frame 0 compiles the shaders and warms up (100x a later frame): left out so the rest can be read.
            axes[1].plot(fr[1:], [to_float(r["sss_ms"]) for r in rs[1:]], color=c, label=m)
        rs = sorted((r for r in rows if r["method"] == "cv"), key=lambda r: int(r["frame"]))
        lights = [parse_lights(r["lights"]) for r in rs]
        for name in (lights[0].keys() if lights else []):
            axes[2].step([int(r["frame"]) for r in rs], [l[name] for l in lights], where="post", label=name)
        axes[0].set_ylabel("mean samples\nper SSS pixel")
        axes[1].set_ylabel("SSS pass ms\n(from frame 1)")
        axes[2].set_ylabel("light\nintensity")
        axes[2].set_xlabel("frame")
        axes[0].legend(fontsize=8, ncol=4)
        axes[2].legend(fontsize=7, ncol=3)
        for ax in axes:
            ax.grid(True, alpha=0.3)
        axes[0].set_title(f"{scene}: samples and SSS pass time per frame ({device})", fontsize=10)
        save_fig(fig, f"switch-{scene}.png")


def read_matrix(path):
    import numpy as np
    return np.loadtxt(path, delimiter=",", ndmin=2)


def plot_heatmaps(heat_dir, frames, device):
    import numpy as np
    plt = plt_module()
    fig, axes = plt.subplots(len(frames), len(ADAPTIVE) + 1, figsize=(11, 2.7 * len(frames)))
    for i, f in enumerate(frames):
        for j, m in enumerate(ADAPTIVE):
            counts = read_matrix(os.path.join(heat_dir, f"{m}.f{f}.samples.csv"))
            mask = read_matrix(os.path.join(heat_dir, f"{m}.f{f}.mask.csv")) > 0.5
            shown = np.where(mask, counts, np.nan)
            im = axes[i][j].imshow(shown, cmap="inferno", vmin=0, vmax=DEFAULT_NMAX)
            mean = counts[mask].mean() if mask.any() else 0.0
            axes[i][j].set_title(f"{m}, frame {f}: mean N {mean:.1f}", fontsize=8)
        fig.colorbar(im, ax=list(axes[i][:len(ADAPTIVE)]), shrink=0.8, label="samples")
        alpha = read_matrix(os.path.join(heat_dir, f"cv.f{f}.alpha.csv"))
        mask = read_matrix(os.path.join(heat_dir, f"cv.f{f}.mask.csv")) > 0.5
        im = axes[i][-1].imshow(np.where(mask, alpha, np.nan), cmap="coolwarm", vmin=0, vmax=2)
        axes[i][-1].set_title(f"cv alpha, frame {f}", fontsize=8)
        fig.colorbar(im, ax=axes[i][-1], shrink=0.8)
        for ax in axes[i]:
            ax.set_xticks([]); ax.set_yticks([])
    fig.suptitle(f"light-off: samples per pixel around the switch at frame {SWITCH_FRAME} ({device})", fontsize=10)
    save_fig(fig, "heatmaps-light-off.png")


def plot_scaling(rows, key, xlabel, name, device, pixels=False):
    plt = plt_module()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    groups = {}
    for r in rows:
        if int(r["frame"]) < 2:  # warm-up, and the adaptive methods' first (full-rate) frames
            continue
        x = int(r["width"]) * int(r["height"]) if pixels else to_float(r["sss_scale"])
        groups.setdefault(r["method"], {}).setdefault(x, []).append(r)
    for m, by_x in groups.items():
        xs = sorted(by_x)
        axes[0].plot(xs, [median([to_float(r["sss_ms"]) for r in by_x[x]]) for x in xs], "o-", label=m)
        axes[1].plot(xs, [mean_finite([to_float(r["mean_spp"]) for r in by_x[x]]) for x in xs], "o-", label=m)
    for ax in axes:
        ax.set_xscale("log"); ax.set_xlabel(xlabel); ax.grid(True, which="both", alpha=0.3)
    axes[0].set_yscale("log")
    axes[0].set_ylabel("SSS pass ms (median over frames 2..)")
    axes[1].set_ylabel("mean samples per SSS pixel")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"{name} ({device})", fontsize=10)
    save_fig(fig, f"{key}.png")
    return groups


# ---------------------------------------------------------------------------------------------------- tables

def fmt(x, digits=2):
    return "n/a" if x is None or (isinstance(x, float) and not math.isfinite(x)) else f"{x:.{digits}f}"


def teaser_table(rows):
    """Separable / spvg / cv / cv-notex on light-off after the switch, beside the paper's teaser."""
    after = summarize_quality([r for r in rows if r["scene"] == "light-off"], first_frame=SWITCH_FRAME)
    default = knob_label(DEFAULT_TARGET, DEFAULT_NMAX)
    # SPVG capped at N max 16 too: the simplest way to bound SPVG's spike, the baseline cv has to beat.
    entries = [("separable", "separable-17", "fixed"), ("spvg", "spvg", default), ("cv", "cv", default),
               ("cv-notex", "cv-notex", default), ("spvg, N max 16", "spvg", knob_label(DEFAULT_TARGET, 16))]
    spvg = after.get(("light-off", "spvg", default))
    lines = ["| method | SSS pass ms (ours) | x spvg (ours) | PSNR dB (ours) | dB vs spvg (ours) | mean spp (ours) "
             "| paper ms | x spvg (paper) | paper dB | dB vs spvg (paper) |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for label, method, knobs in entries:
        s = after.get(("light-off", method, knobs))
        if not s:
            continue
        pm, pdb = PAPER.get(label, (None, None))
        ratio = s["sss_ms"] / spvg["sss_ms"] if spvg else math.nan
        ddb = s["psnr_db"] - spvg["psnr_db"] if spvg else math.nan
        pr = pm / PAPER["spvg"][0] if pm else None
        pd = pdb - PAPER["spvg"][1] if pdb else None
        lines.append(f"| {label} | {fmt(s['sss_ms'])} | {fmt(ratio)} | {fmt(s['psnr_db'])} | {fmt(ddb):s} | "
                     f"{fmt(s['mean_spp'], 1)} | {fmt(pm, 1) if pm else '-'} | {fmt(pr) if pr else '-'} | "
                     f"{fmt(pdb, 1) if pdb else '-'} | {fmt(pd, 1) if pd is not None else '-'} |")
    return "\n".join(lines)


def switch_table(rows):
    """The switch plots as numbers: per scene and method, mean samples per SSS pixel, the peak of the per-frame
    mean, and the median SSS pass ms, with their ratios to SPVG; light-off over the 30 frames from the switch,
    flicker and club from frame 2 (frame 0 compiles the shaders; the histories take N max until two frames old)."""
    lines = ["| scene, frames | method | mean spp | peak of the frame mean | x spvg | SSS ms (median) | x spvg |",
             "|---|---|---:|---:|---:|---:|---:|"]
    for scene in ("light-off", "flicker", "club"):
        first = SWITCH_FRAME if scene == "light-off" else 2
        stats = {}
        for m in ["separable-17"] + ADAPTIVE:
            rs = [r for r in rows if r["scene"] == scene and r["method"] == m and int(r["frame"]) >= first]
            if rs:
                spp = [to_float(r["mean_spp"]) for r in rs]
                stats[m] = (statistics.mean(spp), max(spp), statistics.median(to_float(r["sss_ms"]) for r in rs),
                            max(int(r["frame"]) for r in rs))
        ref = stats.get("spvg")
        for m, (spp, peak, ms, last) in stats.items():
            lines.append(f"| {scene}, {first}-{last} | {m} | {fmt(spp)} | {fmt(peak, 1)} | "
                         f"{fmt(spp / ref[0] if ref else math.nan)} | {fmt(ms)} | "
                         f"{fmt(ms / ref[2] if ref else math.nan)} |")
    return "\n".join(lines)


def heatmap_table(heat_dir, frames):
    """Per adaptive method and heatmap frame: mean N over SSS pixels, the share at N max; cv's alpha."""
    import numpy as np
    lines = ["| frame | method | mean N | share of SSS pixels at N max | cv: alpha non-zero | cv: median non-zero alpha |",
             "|---:|---|---:|---:|---:|---:|"]
    for f in frames:
        for m in ADAPTIVE:
            stem = os.path.join(heat_dir, f"{m}.f{f}")
            if not os.path.exists(stem + ".samples.csv"):
                continue
            n, mask = read_matrix(stem + ".samples.csv"), read_matrix(stem + ".mask.csv") != 0
            alpha = ("-", "-")
            if m == "cv" and os.path.exists(stem + ".alpha.csv"):
                a = read_matrix(stem + ".alpha.csv")[mask]
                nz = a[a != 0]
                alpha = (f"{100.0 * nz.size / a.size:.0f}%", fmt(float(np.median(nz))) if nz.size else "-")
            lines.append(f"| {f} | {m} | {fmt(float(n[mask].mean()))} | "
                         f"{100.0 * float((n[mask] == DEFAULT_NMAX).mean()):.0f}% | {alpha[0]} | {alpha[1]} |")
    return "\n".join(lines)


def pareto_table(summary):
    lines = ["| scene | method | knob | SSS ms | mean spp | PSNR dB | PSNR SSS dB | temporal error |",
             "|---|---|---|---:|---:|---:|---:|---:|"]
    for (scene, method, knobs), s in sorted(summary.items(), key=lambda kv: (QUALITY_SCENES.index(kv[0][0]),
                                                                             kv[0][1], kv[0][2])):
        lines.append(f"| {scene} | {method} | {knobs} | {fmt(s['sss_ms'])} | {fmt(s['mean_spp'], 1)} | "
                     f"{fmt(s['psnr_db'])} | {fmt(s['psnr_sss_db'])} | {fmt(s['temporal_error'], 4)} |")
    return "\n".join(lines)


def scaling_table(groups, xname, xfmt):
    methods = sorted(groups)
    xs = sorted({x for g in groups.values() for x in g})
    lines = [f"| {xname} | " + " | ".join(f"{m} ms (spp)" for m in methods) + " |",
             "|---|" + "---:|" * len(methods)]
    for x in xs:
        cells = []
        for m in methods:
            rs = groups[m].get(x, [])
            cells.append(f"{fmt(median([to_float(r['sss_ms']) for r in rs]))} "
                         f"({fmt(mean_finite([to_float(r['mean_spp']) for r in rs]), 1)})")
        lines.append(f"| {xfmt(x)} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def per_sss_pixel_table(groups):
    """SSS pass time per SSS pixel (ns): flat where the cost is proportional to the scattering pixels."""
    methods = sorted(groups)
    xs = sorted({x for g in groups.values() for x in g})
    lines = ["| pixels | SSS pixels | " + " | ".join(f"{m} ns/SSS px" for m in methods) + " |",
             "|---|---:|" + "---:|" * len(methods)]
    for x in xs:
        any_rows = next(groups[m][x] for m in methods if x in groups[m])
        sss = int(any_rows[0]["sss_pixels"])
        cells = [fmt(1e6 * median([to_float(r["sss_ms"]) for r in groups[m].get(x, [])]) / max(sss, 1), 0)
                 for m in methods]
        lines.append(f"| {x} | {sss} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def replace_block(text, name, body):
    begin, end = f"<!-- BEGIN GENERATED: {name} -->", f"<!-- END GENERATED: {name} -->"
    i, j = text.find(begin), text.find(end)
    if i < 0 or j < 0:
        die(f"{DOC}: no {begin} ... {end} block")
    return text[:i + len(begin)] + "\n" + body.strip() + "\n" + text[j:]


# ---------------------------------------------------------------------------------------------------- main

def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--size", default="128x128", help="quality sweep size (default 128x128)")
    p.add_argument("--seeds", default="1,2", help="seeds of the repeated quality runs (default 1,2)")
    p.add_argument("--frames", type=int, default=0, help="frames per quality run (default: the scene's length)")
    p.add_argument("--stages", default="quality,switch,heatmap,scaling,spread")
    p.add_argument("--quick", action="store_true", help="small and short: for checking the script")
    p.add_argument("--plots-only", action="store_true", help="redraw from docs/results/raw without rendering")
    a = p.parse_args()
    a.seeds = [int(s) for s in a.seeds.split(",")]
    stages = set(a.stages.split(","))
    if a.quick:
        a.size, a.seeds, a.frames = "64x64", [1], 0
    for exe in ("emcv-demo", "emcv-eval", "emcv-golden"):
        if not a.plots_only and not os.access(os.path.join(a.build, "bin", exe), os.X_OK):
            die(f"no {exe} in {a.build}/bin (cmake --build {a.build} --target emcv-demo emcv-eval emcv-golden)")
    if os.access(os.path.join(a.build, "bin", "emcv-demo"), os.X_OK):
        ADAPTIVE[:] = methods_from_table(a.build, "adaptive")
    else:  # --plots-only without a build: the adaptive methods the raw quality runs rendered
        ADAPTIVE[:] = sorted({r["method"] for r in read_csv(os.path.join(RAW, "quality.csv")) if r["knobs"] != "fixed"})
    os.makedirs(RAW, exist_ok=True)
    device_file = os.path.join(RAW, "device.txt")
    cost_size = "64x64" if a.quick else "128x128"

    with tempfile.TemporaryDirectory(prefix="emcv-eval-") as tmp:
        if not a.plots_only:
            head = subprocess.run(["git", "-C", ROOT, "describe", "--always", "--dirty"], capture_output=True, text=True)
            write_atomically(os.path.join(RAW, "commit.txt"), (head.stdout.strip() or "unknown") + "\n")
            if "quality" in stages:
                save_rows("quality.csv", stage_quality(a, tmp))
            if "switch" in stages:
                rows = []
                for scene, frames in (("light-off", 60), ("flicker", 48), ("club", 60)):
                    print(f"  switch: {scene}", flush=True)
                    rows += stage_cost(a, tmp, scene, ["separable-17"] + ADAPTIVE, cost_size, frames)
                save_rows("switch.csv", rows)
            if "heatmap" in stages:
                print("  heatmap: light-off", flush=True)
                heat = os.path.join(RAW, "heatmaps")
                os.makedirs(heat, exist_ok=True)
                stage_cost(a, tmp, "light-off", ADAPTIVE, cost_size, SWITCH_FRAME + 4,
                           heatmaps=([SWITCH_FRAME - 1, SWITCH_FRAME + 3], heat))
            if "spread" in stages:
                save_rows("golden-seed-spread.csv", stage_spread(a, tmp))
            if "scaling" in stages:
                rows = []
                sizes = SCALING_SIZES[:2] if a.quick else SCALING_SIZES
                for w, h in sizes:
                    print(f"  scaling: {w}x{h}", flush=True)
                    rows += stage_cost(a, tmp, "static", COST_METHODS, f"{w}x{h}", 8)
                save_rows("scaling-resolution.csv", rows)
                rows = []
                for k in (SCALING_RADII[:2] if a.quick else SCALING_RADII):
                    print(f"  scaling: sss-scale {k}", flush=True)
                    rows += stage_cost(a, tmp, "static", COST_METHODS, "256x256", 8, sss_scale=k)
                save_rows("scaling-radius.csv", rows)

    device = open(device_file).read().strip() if os.path.exists(device_file) else "unknown GL renderer"
    commit_file = os.path.join(RAW, "commit.txt")
    commit = open(commit_file).read().strip() if os.path.exists(commit_file) else "unknown"
    load_file = os.path.join(RAW, "load.txt")
    if not a.plots_only:
        write_atomically(load_file, " ".join(f"{x:.1f}" for x in os.getloadavg()) + f" on {os.cpu_count()} CPUs\n")
    load = open(load_file).read().strip() if os.path.exists(load_file) else "not recorded"
    blocks = {"context": f"Renderer: **{device}** (GL_RENDERER), commit {commit}; load average (1, 5, 15 min) at "
                         f"the end of the run: {load}."}
    if os.path.exists(os.path.join(RAW, "quality.csv")):
        rows = read_csv(os.path.join(RAW, "quality.csv"))
        summary = summarize_quality(rows)
        plot_pareto(summary, device)
        blocks["teaser"] = teaser_table(rows)
        blocks["pareto"] = pareto_table(summary)
        write_atomically(os.path.join(RESULTS, "pareto.md"), blocks["pareto"] + "\n")
    if os.path.exists(os.path.join(RAW, "switch.csv")):
        rows = read_csv(os.path.join(RAW, "switch.csv"))
        plot_switch({s: [r for r in rows if r["scene"] == s] for s in ("light-off", "flicker", "club")}, device)
        blocks["switch"] = switch_table(rows)
    if os.path.isdir(os.path.join(RAW, "heatmaps")):
        plot_heatmaps(os.path.join(RAW, "heatmaps"), [SWITCH_FRAME - 1, SWITCH_FRAME + 3], device)
        blocks["heatmaps"] = heatmap_table(os.path.join(RAW, "heatmaps"), [SWITCH_FRAME - 1, SWITCH_FRAME + 3])
    if os.path.exists(os.path.join(RAW, "golden-seed-spread.csv")):
        blocks["seed-spread"] = spread_table(read_csv(os.path.join(RAW, "golden-seed-spread.csv")))
    if os.path.exists(os.path.join(RAW, "scaling-resolution.csv")):
        g = plot_scaling(read_csv(os.path.join(RAW, "scaling-resolution.csv")), "scaling-resolution",
                         "pixels (log)", "static: cost against resolution", device, pixels=True)
        blocks["scaling-resolution"] = scaling_table(g, "pixels", lambda x: f"{x}") + "\n\n" + \
            per_sss_pixel_table(g)
        g = plot_scaling(read_csv(os.path.join(RAW, "scaling-radius.csv")), "scaling-radius",
                         "mean free path scale (radius on screen, log)", "static at 256x256: cost against the "
                         "scattering radius", device)
        blocks["scaling-radius"] = scaling_table(g, "mfp scale", lambda x: f"{x:g}")
    if os.path.exists(DOC) and not a.quick:
        text = open(DOC).read()
        for name, body in blocks.items():
            if f"<!-- BEGIN GENERATED: {name} -->" in text:
                text = replace_block(text, name, body)
        write_atomically(DOC, text)
    for name, body in blocks.items():
        print(f"\n## {name}\n{body}")


if __name__ == "__main__":
    main()
