#!/usr/bin/python3
"""The renderer's evaluation: what each SSS method's accuracy costs, at equal cost, raw and resolved (docs/results.md).

    /usr/bin/python3 scripts/eval/run_eval.py [--build build] [--size 128x128] [--seeds 1,2] [--jobs N]
                                              [--shard I/N] [--merge] [--stages S,...] [--raw-dir DIR]
                                              [--quick] [--check-determinism] [--plots-only]

It needs emcv-demo, emcv-eval, emcv-golden and emcv-light-curves under BUILD/bin and runs them headless (EGL;
Mesa llvmpipe here, so every time is a CPU rasteriser's time: docs/results.md says what that means).

The evaluation is a list of independent jobs. Each job is one invocation of a renderer tool that writes its own
raw CSV under the raw directory (default docs/results/raw/, STAGE/NAME.csv; the first lines, starting with '#',
name the command, the commit and the GL renderer). The list's order, and so each job's index, is fixed:
  1. lights      per scene (the quality scenes, then the variations): the lights per frame (emcv-eval, diffuse)
  2. quality     per quality scene x group x seed: emcv-demo against the reference, raw and resolved (--resolve
                 taa). Groups: "fixed" (diffuse, separable-11/17/25), then "B4", "B8", "B16", "B32" (burley-B,
                 spvg, cv, cv-notex with --spp-budget B: every method spends B samples per SSS pixel), then "B64"
                 (burley-64 alone: the equal-time comparison's reach, REACH_BUDGETS)
  3. variations  per scene file of demo/scenes/variations/, then of demo/scenes/validation/, x B in 8, 16
                 (burley-B, spvg, cv, cv-notex; with separable-17 and diffuse at B = 8), first seed
  4. teaser      per seed: light-off in quality mode (the default target variance), the paper's teaser methods
  5. spread      emcv-golden: the golden cases with seed 2 against the goldens (seed 1)
  6. cost        per round (COST_ROUNDS) x quality scene x group: emcv-eval, SSS pass ms and samples per frame
                 (the time axis: per method the median over rounds of each round's mean over frames 20..)
  7. switch      light-off, flicker, club: emcv-eval in quality mode, samples and SSS ms per frame
  8. heatmap     light-off: per-pixel sample counts around the switch and cv's alpha (emcv-eval)
  9. scaling     static: SSS ms against resolution (one job per size), then against --sss-scale (one per scale)
Jobs 1-5 measure quality (PSNR, samples, lag: no time) and run --jobs N at once (concurrent.futures, one
subprocess each). Jobs 6-9 are the timing stages: they run one at a time after the others, because jobs running
side by side distort each other's times. --shard I/N runs only the jobs whose index % N == I, so that N machines
split the list (their timing jobs then come from different machines: run the timing stages unsharded when the
times are to be compared). Without --shard every job runs.

After running, or with --merge (alias --plots-only) without running anything, the script assembles the tables
and plots from the raw files of every shard: it refuses, naming the missing jobs, when a raw file is absent or
was made with another command (another size, frames or seeds). The tables of quality (from jobs 1-4) are kept
apart from those of time (jobs 6-9): the quality tables from --jobs 2 are byte-identical to those from --jobs 1,
which --check-determinism verifies on the --quick list (64x64, two scenes, one seed). Every output is written to
a temporary name and renamed. With the default raw directory (and not --quick) the GENERATED blocks of
docs/results.md are rewritten and the plots and the long tables (pareto.md, pareto-time.md, worth.md,
equal-time.md, variations.md, switch.md, scaling-resolution.md, scaling-radius.md, seed-spread.md) go to
docs/results/; otherwise they go to RAW_DIR/out/.
"""
import argparse
import concurrent.futures
import csv
import difflib
import io
import math
import os
import re
import shlex
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import ROOT, docs, git, plots, runner  # noqa: E402  (the helpers every script of scripts/eval shares)
from emcv_eval.docs import write_atomically  # noqa: E402,F401
from emcv_eval.plots import COLOURS  # noqa: E402,F401
from emcv_eval.runner import csv_header as header, read_csv, read_csv_text  # noqa: E402,F401
from emcv_eval.tables import fmt, mean_finite, median, sign, to_float  # noqa: E402,F401
RESULTS = os.path.join(ROOT, "docs", "results")
DEFAULT_RAW = os.path.join(RESULTS, "raw")
DOC = os.path.join(ROOT, "docs", "results.md")

QUALITY_SCENES = ["static", "light-off", "flicker", "club", "moving"]
# Frames per quality run: 20 frames of the resolve's warm-up, then light-off's 30 frames on each side of its
# switch; flicker past its last burst (41-42) by 29 frames; club over two periods of its slowest light (30).
QUALITY_FRAMES = {"static": 60, "light-off": 60, "flicker": 72, "club": 60, "moving": 60}
BUDGETS = [4, 8, 16, 32]
# burley-N beyond the largest B, run alone (quality and cost): an adaptive method at B = 16 or 32 takes more SSS time
# than burley-32, and the equal-time comparison interpolates between burley runs, never past the slowest.
REACH_BUDGETS = [64]
COST_ROUNDS = 3  # rounds of the cost stage (not with --quick: one)
VARIATION_BUDGETS = [8, 16]
STORY_BUDGET = 8  # the budget of the switch story, the per-frame plots and the banding crop
SEPARABLE = ["separable-11", "separable-17", "separable-25"]
# The adaptive methods, each a family of its own, and the teaser's methods: from emcv-demo's method table
# (use_methods, --list-methods' "adaptive" rows), never a list of this script's own.
ADAPTIVE, FAMILIES, TEASER_METHODS = [], [], []
METHODS_FILE = "methods.tsv"  # beside the raw files: the --list-methods of the build that rendered them
SWITCH_FRAME = 30  # light-off: the key light's step (demo/scenes/light-off.json)
# The paper's teaser (Xie & Olano 2021, Fig. 1): SSS sampling pass ms and PSNR after the switch.
PAPER = {"separable": (4.0, None), "spvg": (12.9, 48.6), "cv": (5.2, 47.5)}
SCALING_SIZES = [(128, 128), (256, 256), (512, 288), (640, 360), (960, 540), (1280, 720)]
SCALING_RADII = [0.25, 0.5, 1, 2, 4, 8]
COST_METHODS = ["burley-16", "separable-17", "spvg", "cv", "cv-notex"]
DEFAULT_NMAX = 64

MEAN_FROM = 20    # "all frames" means frames 20 .. end: frames 0-19 are the resolve's warm-up from frame 0
WINDOW = 30       # frames after a light change that "after the change" covers
LAG_DB = 1.0      # lag: frames until the PSNR is within 1 dB of its settled value and stays there
STEP = 0.10       # a light step: a steady light's intensity moves by over 10% of its largest value in one frame
MERGE_STEPS = 4   # steps closer than this many frames are one change (a burst's on and off)
MIN_WINDOW = 8    # a change followed by a shorter quiet window gets no lag

QUALITY_STAGES = ["lights", "quality", "variations", "teaser", "spread"]
TIMING_STAGES = ["cost", "switch", "heatmap", "scaling"]
DEMO_COLUMNS = ["frame", "method", "mean_spp", "psnr_db", "psnr_resolved_db", "psnr_sss_db",
                "psnr_sss_resolved_db"]


def shown(path):
    """A path as the messages show it: from the repository root when it is inside it."""
    rel = os.path.relpath(path, ROOT)
    return path if rel.startswith("..") else rel


def die(msg):
    sys.exit(f"run_eval.py: {msg}")


# ---------------------------------------------------------------------------------------------------- files

def number_text(column, value):
    """A raw CSV cell: PSNR to 0.001 dB, samples to 4 decimals, times to 4 significant digits, else as is."""
    x = to_float(value)
    if not math.isfinite(x):
        return value
    if column.startswith("psnr"):
        return f"{x:.3f}"
    if column in ("mean_spp",):
        return f"{x:.4f}"
    if column.endswith("_ms"):
        return f"{x:.4g}"
    return value


def csv_text(rows, columns, comments):
    s = io.StringIO()
    for k, v in comments.items():
        s.write(f"# {k}: {v}\n")
    w = csv.DictWriter(s, fieldnames=columns, lineterminator="\n", extrasaction="ignore")
    w.writeheader()
    w.writerows({k: number_text(k, r.get(k, "")) for k in columns} for r in rows)
    return s.getvalue()


def git_commit():
    """The commit, with -dirty when a tracked file other than the evaluation's outputs and the docs differs from it
    (emcv_eval.git.commit)."""
    return git.commit()


# ---------------------------------------------------------------------------------------------------- jobs

class Job:
    """One renderer invocation and the raw file it writes (RAW/stage/name.csv, or a folder for the heatmaps)."""

    def __init__(self, stage, name, tool, args, columns=None, meta=None):
        self.stage, self.name, self.tool, self.args = stage, name, tool, args
        self.columns = columns
        self.meta = meta or {}
        self.index = -1
        self.serial = stage in TIMING_STAGES

    def raw(self, raw_dir):
        return os.path.join(raw_dir, self.stage, self.name + ("" if self.stage == "heatmap" else ".csv"))

    def command_text(self):
        """The command as recorded in the raw file: machine-independent (the tool's name, paths from the root)."""
        return " ".join([self.tool] + [shlex.quote(a) for a in self.args])

    def label(self):
        return f"{self.index} {self.stage}/{self.name}"


def demo_job(stage, name, scene, methods, size, frames, seed, budget=None, meta=None):
    args = ["--scene", scene, "--method", ",".join(methods), "--size", size, "--frames", str(frames),
            "--seed", str(seed), "--resolve", "taa", "--no-frames"]
    if budget is not None:
        args += ["--spp-budget", str(budget)]
    return Job(stage, name, "emcv-demo", args, DEMO_COLUMNS, meta)


def eval_job(stage, name, scene, methods, size, frames, budget=None, sss_scale=None, columns=None, meta=None):
    args = ["--scene", scene, "--method", ",".join(methods), "--size", size, "--frames", str(frames)]
    if budget is not None:
        args += ["--spp-budget", str(budget)]
    if sss_scale is not None:
        args += ["--sss-scale", f"{sss_scale:g}"]
    return Job(stage, name, "emcv-eval", args,
               columns or ["method", "frame", "sss_ms", "mean_spp", "max_spp", "sss_pixels"], meta)


def group_methods(group):
    if group == "fixed":
        return ["diffuse"] + SEPARABLE
    b = int(group[1:])
    return [f"burley-{b}"] + ([] if b in REACH_BUDGETS else ADAPTIVE)


def scene_name(scene):
    return os.path.splitext(os.path.basename(scene))[0]


class Config:
    def __init__(self, size, seeds, quick, stages):
        self.size, self.seeds, self.quick, self.stages = size, seeds, quick, stages
        if quick:
            self.scenes = ["light-off", "flicker"]
            self.groups = ["fixed", f"B{STORY_BUDGET}"]
            self.variations = ["demo/scenes/variations/switch-on.json"]
            self.variation_budgets = [STORY_BUDGET]
        else:
            self.scenes = QUALITY_SCENES
            self.groups = ["fixed"] + [f"B{b}" for b in BUDGETS + REACH_BUDGETS]
            # The variations of light-off, then the validation scenes (docs/scenes.md): nothing was tuned on either.
            self.variations = [os.path.relpath(os.path.join(ROOT, "demo", "scenes", folder, f), ROOT)
                               for folder in ("variations", "validation")
                               for f in sorted(os.listdir(os.path.join(ROOT, "demo", "scenes", folder)))
                               if f.endswith(".json")]
            self.variation_budgets = VARIATION_BUDGETS

    def frames(self, scene):
        return QUALITY_FRAMES.get(scene, 0)


def job_list(c):
    """Every job of the evaluation in its documented order; a job's index is its position here."""
    jobs = []
    frames_of = {}
    for scene in c.scenes:
        frames_of[scene] = c.frames(scene)
    for v in c.variations:
        frames_of[v] = scene_frames(v)
    if "lights" in c.stages:
        for scene, frames in frames_of.items():
            jobs.append(eval_job("lights", scene_name(scene), scene, ["diffuse"], "16x16", frames,
                                 columns=["frame", "lights"]))
    if "quality" in c.stages:
        for scene in c.scenes:
            for group in c.groups:
                for seed in c.seeds:
                    b = None if group == "fixed" else int(group[1:])
                    jobs.append(demo_job("quality", f"{scene}-{group}-s{seed}", scene, group_methods(group), c.size,
                                         frames_of[scene], seed, b, meta={"scene": scene, "group": group,
                                                                          "seed": seed}))
    if "variations" in c.stages:
        for v in c.variations:
            for b in c.variation_budgets:
                methods = group_methods(f"B{b}") + (["separable-17", "diffuse"] if b == STORY_BUDGET else [])
                jobs.append(demo_job("variations", f"{scene_name(v)}-B{b}-s{c.seeds[0]}", v, methods, c.size,
                                     frames_of[v], c.seeds[0], b,
                                     meta={"scene": scene_name(v), "group": f"B{b}", "seed": c.seeds[0]}))
    if "teaser" in c.stages:
        for seed in c.seeds:
            jobs.append(demo_job("teaser", f"light-off-s{seed}", "light-off", TEASER_METHODS, c.size, 60, seed,
                                 meta={"scene": "light-off", "group": "target", "seed": seed}))
    if "spread" in c.stages:
        jobs.append(Job("spread", "golden-seed-spread", "emcv-golden", ["render", "--seed", "2"],
                        ["image", "verdict", "failing_percent", "max_error", "rmse"]))
    if "cost" in c.stages:
        # COST_ROUNDS rounds of every scene and group, one after the other: each time is the median over the rounds
        # (cost_ms), so one slow stretch of the machine moves one round, not the table.
        for r in range(1 if c.quick else COST_ROUNDS):
            for scene in c.scenes:
                for group in c.groups:
                    b = None if group == "fixed" else int(group[1:])
                    jobs.append(eval_job("cost", f"{scene}-{group}" + (f"-r{r + 1}" if r else ""), scene,
                                         group_methods(group), c.size, frames_of[scene], b,
                                         meta={"scene": scene, "group": group}))
    cost_size = "64x64" if c.quick else "128x128"
    if "switch" in c.stages:
        for scene, frames in (("light-off", 60), ("flicker", 48), ("club", 60)):
            jobs.append(eval_job("switch", scene, scene, ["separable-17"] + ADAPTIVE, cost_size, frames,
                                 columns=["scene", "method", "frame", "sss_ms", "mean_spp", "max_spp", "sss_pixels",
                                          "lights"]))
    if "heatmap" in c.stages:
        frames = [SWITCH_FRAME - 1, SWITCH_FRAME + 3]
        jobs.append(eval_job("heatmap", "heatmaps", "light-off", ADAPTIVE, cost_size, SWITCH_FRAME + 4,
                             meta={"frames": frames}))
        jobs[-1].args += ["--heatmaps", ",".join(str(f) for f in frames)]
    if "scaling" in c.stages:
        columns = ["method", "frame", "width", "height", "sss_scale", "sss_ms", "mean_spp", "sss_pixels"]
        for w, h in (SCALING_SIZES[:2] if c.quick else SCALING_SIZES):
            jobs.append(eval_job("scaling-resolution", f"{w}x{h}", "static", COST_METHODS, f"{w}x{h}", 8,
                                 sss_scale=1, columns=columns))
        for k in (SCALING_RADII[:2] if c.quick else SCALING_RADII):
            jobs.append(eval_job("scaling-radius", f"k{k:g}", "static", COST_METHODS, "256x256", 8, sss_scale=k,
                                 columns=columns))
    for j in jobs:
        j.serial = j.stage in TIMING_STAGES or j.stage.startswith("scaling")
    # The documented order: quality-side stages first, then the timing stages, each in the order built above.
    jobs = [j for j in jobs if not j.serial] + [j for j in jobs if j.serial]
    for i, j in enumerate(jobs):
        j.index = i
    return jobs


def scene_frames(scene_file):
    """A scene file's own length (its "frames" key)."""
    import json
    with open(os.path.join(ROOT, scene_file)) as f:
        return int(json.load(f).get("frames", 1))


# ---------------------------------------------------------------------------------------------------- running

class Context:
    def __init__(self, build, raw_dir, tmp):
        self.build, self.raw_dir, self.tmp = build, raw_dir, tmp
        self.commit = git_commit()
        # Snapshots of shaders/ and include/ taken once, before any job starts: every job compiles the same GLSL
        # even while the source tree changes under the run.
        self.env = dict(os.environ)
        for name, var in (("shaders", "EMCV_SHADER_DIR"), ("include", "EMCV_INCLUDE_DIR")):
            d = os.path.join(tmp, name)
            shutil.copytree(os.path.join(ROOT, name), d)
            self.env[var] = d


def run_tool(ctx, job, extra):
    cmd = [runner.tool_path(ctx.build, job.tool)] + job.args + extra
    r = subprocess.run(cmd, capture_output=True, text=True, env=ctx.env, cwd=ROOT)
    if r.returncode != 0:
        raise RuntimeError(f"job {job.label()}: {' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()[-800:]}")
    return r.stdout


def run_job(ctx, job):
    """Runs one job and writes its raw file atomically; returns the job."""
    out = os.path.join(ctx.tmp, "jobs", f"{job.index}")
    os.makedirs(out, exist_ok=True)
    comments = {"job": f"{job.stage}/{job.name}", "cmd": job.command_text(), "commit": ctx.commit}
    if job.tool == "emcv-demo":
        first = run_tool(ctx, job, ["--out", out]).splitlines()[0]  # "scene S, WxH, N frames, seed S, ..., <GL>"
        rest = first.split(", seed ", 1)[-1].split(", ", 1)[-1]
        comments["device"] = rest.split(", ", 1)[-1] if rest.startswith("adaptive sampling") else rest
        rows = [r for r in read_csv(os.path.join(out, "metrics.csv")) if r["method"] != "reference"]
        text = csv_text(rows, job.columns, comments)
    elif job.stage == "heatmap":
        run_tool(ctx, job, ["--heatmap-dir", out])
        with open(os.path.join(out, "job.txt"), "w") as f:
            f.write("".join(f"# {k}: {v}\n" for k, v in comments.items()))
        dest = job.raw(ctx.raw_dir)
        os.makedirs(os.path.dirname(dest), exist_ok=True)
        old = dest + f".old{os.getpid()}"
        if os.path.exists(dest):
            os.replace(dest, old)
        shutil.move(out, dest)
        shutil.rmtree(old, ignore_errors=True)
        return job
    elif job.tool == "emcv-golden":
        text = csv_text(spread_rows(ctx, job, out), job.columns, comments)
    else:
        text = csv_text(read_csv_text(run_tool(ctx, job, [])), job.columns, comments)
    write_atomically(job.raw(ctx.raw_dir), text)
    shutil.rmtree(out, ignore_errors=True)
    return job


def spread_rows(ctx, job, out):
    golden = os.path.join(ctx.build, "bin", "emcv-golden")
    run_tool(ctx, job, ["--out", out])
    rows = []
    pattern = re.compile(r"^(\w+): (\d+) of (\d+) pixels over \S+ \(([\d.]+)%.*max ([\d.e+-]+) at .*RMSE ([\d.e+-]+)")
    for name in sorted(os.listdir(out)):
        r = subprocess.run([golden, "compare", os.path.join(out, name),
                            os.path.join(ROOT, "tests", "image", "golden", name)], capture_output=True, text=True)
        m = pattern.match(r.stdout.strip())
        if not m:
            raise RuntimeError(f"emcv-golden compare {name}: unexpected output {r.stdout!r} {r.stderr!r}")
        rows.append({"image": name, "verdict": m.group(1), "failing_percent": m.group(4),
                     "max_error": m.group(5), "rmse": m.group(6)})
    return rows


def run_jobs(ctx, jobs, workers):
    """The quality-side jobs `workers` at a time, then the timing jobs one at a time. Stops at the first failure
    (the jobs already running finish; their raw files are complete)."""
    pool_jobs = [j for j in jobs if not j.serial]
    serial_jobs = [j for j in jobs if j.serial]
    done = 0
    total = len(jobs)
    with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as ex:
        futures = [ex.submit(run_job, ctx, j) for j in pool_jobs]
        try:
            for f in concurrent.futures.as_completed(futures):
                j = f.result()
                done += 1
                print(f"  [{done}/{total}] {j.label()}", flush=True)
        except Exception as e:
            for f in futures:
                f.cancel()
            die(str(e))
    for j in serial_jobs:
        try:
            run_job(ctx, j)
        except RuntimeError as e:
            die(str(e))
        done += 1
        print(f"  [{done}/{total}] {j.label()} (timing: one job at a time)", flush=True)


def missing_jobs(jobs, raw_dir):
    """Jobs whose raw file is absent or was made by another command."""
    out = []
    for j in jobs:
        path = j.raw(raw_dir)
        meta = os.path.join(path, "job.txt") if j.stage == "heatmap" else path
        if not os.path.exists(meta):
            out.append(f"{j.label()} (no {shown(path)})")
        elif header(meta).get("cmd") != j.command_text():
            out.append(f"{j.label()} ({shown(path)} was made by `{header(meta).get('cmd')}`, "
                       f"this list needs `{j.command_text()}`)")
    return out


# ---------------------------------------------------------------------------------------------------- data

def method_family(method):
    for f in ("burley", "separable"):
        if method.startswith(f + "-"):
            return f
    return method


class Data:
    """The raw files of a job list, read in job order."""

    def __init__(self, jobs, raw_dir):
        self.jobs, self.raw_dir = jobs, raw_dir
        self.lights = {}   # scene -> frame -> {light: intensity}
        self.series = {}   # (stage, scene, group, method) -> frame -> {column: mean over seeds}
        self.seeds = {}
        for j in jobs:
            if j.stage == "lights":
                per = {}
                for r in read_csv(j.raw(raw_dir)):
                    per[int(r["frame"])] = parse_lights(r["lights"])
                self.lights[j.name] = per
        by = {}
        for j in jobs:
            if j.stage not in ("quality", "variations", "teaser"):
                continue
            for r in read_csv(j.raw(raw_dir)):
                key = (j.stage, j.meta["scene"], j.meta["group"], r["method"])
                by.setdefault(key, {}).setdefault(int(r["frame"]), []).append(r)
        for key, frames in by.items():
            self.series[key] = {f: {c: mean_finite([to_float(r[c]) for r in rs]) for c in DEMO_COLUMNS[2:]}
                                for f, rs in sorted(frames.items())}
            self.seeds[key] = max(len(rs) for rs in frames.values())

    def methods(self, stage, scene, group):
        return [k[3] for k in self.series if k[:3] == (stage, scene, group)]

    def window_mean(self, key, column, first, last=None):
        s = self.series.get(key, {})
        return mean_finite([v[column] for f, v in s.items() if f >= first and (last is None or f <= last)])


def parse_lights(text):
    out = {}
    for item in text.split(";"):
        if "=" in item:
            k, v = item.split("=", 1)
            out[k] = float(v)
    return out


def light_changes(lights):
    """(first change, [changes]): the first frame whose lights differ from the frame before, and the light steps
    (a light that held its intensity over the two frames before, or stepped into the frame before, moving by over
    STEP of its largest value: a step, not a point of a curve that moves every frame; a burst that ends where the
    next begins is two steps), steps closer than MERGE_STEPS frames merged into one change at the first of them.
    Each change is (frame, end of its quiet window, text)."""
    frames = sorted(lights)
    names = sorted({n for f in frames for n in lights[f]})
    top = {n: max(lights[f].get(n, 0.0) for f in frames) for n in names}
    first, steps, stepped = None, [], set()
    for i, (a, b) in enumerate(zip(frames, frames[1:])):
        moved = [n for n in names if lights[b].get(n, 0.0) != lights[a].get(n, 0.0)]
        if moved and first is None:
            first = b
        steady = [n for n in moved
                  if i > 0 and (n in stepped or lights[a].get(n, 0.0) == lights[frames[i - 1]].get(n, 0.0))]
        big = [n for n in steady if top[n] > 0 and abs(lights[b][n] - lights[a][n]) > STEP * top[n]]
        stepped = set(big)
        if big:
            steps.append((b, ", ".join(f"{n} {lights[a][n]:g}->{lights[b][n]:g}" for n in big)))
    groups = []
    for f, text in steps:
        if groups and f - groups[-1][-1][0] < MERGE_STEPS:
            groups[-1].append((f, text))
        else:
            groups.append([(f, text)])
    changes = []
    for i, g in enumerate(groups):
        # The quiet window ends at the next change, or WINDOW frames on (the settled value of a longer window
        # would be a mean over a long stretch whose single noisy frames then decide the lag).
        end = min(groups[i + 1][0][0] if i + 1 < len(groups) else frames[-1] + 1, g[0][0] + WINDOW)
        changes.append((g[0][0], end, "; ".join(f"{f}: {t}" for f, t in g)))
    return first, changes


def lag(series, column, change, end):
    """Frames from the change until the PSNR comes within LAG_DB of its settled value (the mean over the last
    third of the quiet window, at least 3 frames) and stays there to the window's end; None for a window shorter
    than MIN_WINDOW frames."""
    if end - change < MIN_WINDOW:
        return None
    settled_from = end - max(3, (end - change) // 3)
    settled = mean_finite([series[f][column] for f in range(settled_from, end) if f in series])
    if not math.isfinite(settled):
        return None
    for k in range(end - change):
        if all(f in series and series[f][column] >= settled - LAG_DB for f in range(change + k, end)):
            return k
    return end - change


# ---------------------------------------------------------------------------------------------------- quality tables

def setting_of(group, method):
    if group == "fixed":
        return "-"
    return group[1:]


def quality_points(d, scene):
    """(method, group, mean spp, raw dB, resolved dB, raw SSS dB, resolved SSS dB) over frames MEAN_FROM..."""
    points = []
    for group in d.groups:
        for m in d.methods("quality", scene, group):
            key = ("quality", scene, group, m)
            points.append((m, group) + tuple(d.window_mean(key, c, MEAN_FROM) for c in DEMO_COLUMNS[2:]))
    return points


def pareto_table(d):
    lines = ["| scene | method | B | mean spp | PSNR raw | PSNR resolved | SSS px raw | SSS px resolved |",
             "|---|---|---:|---:|---:|---:|---:|---:|"]
    for scene in d.scenes:
        for m, group, spp, raw, res, sraw, sres in quality_points(d, scene):
            lines.append(f"| {scene} | {m} | {setting_of(group, m)} | {fmt(spp, 1)} | {fmt(raw)} | {fmt(res)} | "
                         f"{fmt(sraw)} | {fmt(sres)} |")
    return "\n".join(lines)


def ranked(values):
    """[(method, dB)] best first; ties broken by name so the order is stable."""
    return sorted(((m, v) for m, v in values.items() if math.isfinite(v)), key=lambda mv: (-mv[1], mv[0]))


def equal_samples_table(d):
    """Per scene and B: the best of burley-B, spvg, cv, cv-notex (all B samples per SSS pixel), raw and resolved."""
    lines = ["| scene | B | raw: best (dB) | over next | cv - spvg | cv - burley | "
             "resolved: best (dB) | over next | cv - spvg | cv - burley |",
             "|---|---:|---|---:|---:|---:|---|---:|---:|---:|"]
    for scene in d.scenes:
        for group in d.groups:
            if group == "fixed" or int(group[1:]) in REACH_BUDGETS:  # burley alone: nothing to compare
                continue
            cells = []
            for column in ("psnr_db", "psnr_resolved_db"):
                vals = {m: d.window_mean(("quality", scene, group, m), column, MEAN_FROM)
                        for m in d.methods("quality", scene, group)}
                r = ranked(vals)
                burley = vals.get(f"burley-{group[1:]}", math.nan)
                cv, spvg = vals.get("cv", math.nan), vals.get("spvg", math.nan)
                cells += [f"{r[0][0]} ({fmt(r[0][1])})" if r else "n/a",
                          sign(r[0][1] - r[1][1]) if len(r) > 1 else "n/a", sign(cv - spvg), sign(cv - burley)]
            lines.append(f"| {scene} | {group[1:]} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def story_methods(d, stage, scene):
    b = f"B{STORY_BUDGET}"
    return [(m, b) for m in d.methods(stage, scene, b)] + \
           [(m, "fixed") for m in d.methods(stage, scene, "fixed") if m in ("separable-17", "diffuse")]


def lag_table(d):
    """After each light change of the quality scenes, per method at B = STORY_BUDGET: the resolved image's lag
    (the raw image's in brackets)."""
    methods = [f"burley-{STORY_BUDGET}"] + ADAPTIVE + ["separable-17", "diffuse"]
    lines = [f"Cells: frames until the resolved image is within {LAG_DB:g} dB of its settled PSNR (the raw image's in "
             f"brackets), B = {STORY_BUDGET}.", "",
             "| scene | change at frame (light steps) | quiet window | " + " | ".join(methods) +
             " | cv - spvg (resolved) |", "|---|---|---|" + "---:|" * (len(methods) + 1)]
    for scene in d.scenes:
        if scene not in d.lights:
            continue
        first, changes = light_changes(d.lights[scene])
        if not changes:
            if first is not None:
                lines.append(f"| {scene} | no step: the lights move every frame from frame {first} | - |" +
                             " - |" * (len(methods) + 1))
            continue
        series = {m: d.series.get(("quality", scene, g, m)) for m, g in story_methods(d, "quality", scene)}
        for change, end, text in changes:
            cells, lags = [], {}
            for m in methods:
                s = series.get(m)
                if not s:
                    cells.append("n/a")
                    continue
                res, raw = lag(s, "psnr_resolved_db", change, end), lag(s, "psnr_db", change, end)
                lags[m] = res
                cells.append("-" if res is None else f"{res} ({raw})")
            diff = (f"{lags['cv'] - lags['spvg']:+d}" if lags.get("cv") is not None and lags.get("spvg") is not None
                    else "-")
            lines.append(f"| {scene} | {text} | {change}-{end - 1} | " + " | ".join(cells) + f" | {diff} |")
    return "\n".join(lines)


def variations_table(d):
    lines = ["| scene | B | method | 30 after: raw | resolved | all frames: raw | resolved | lag resolved (raw) |",
             "|---|---:|---|---:|---:|---:|---:|---:|"]
    for v in d.variations:
        scene = scene_name(v)
        first, changes = light_changes(d.lights[scene])
        for b in d.variation_budgets:
            group = f"B{b}"
            for m in d.methods("variations", scene, group):
                key = ("variations", scene, group, m)
                s = d.series[key]
                after = [d.window_mean(key, c, first, first + WINDOW - 1) if first is not None else math.nan
                         for c in ("psnr_db", "psnr_resolved_db")]
                whole = [d.window_mean(key, c, MEAN_FROM) for c in ("psnr_db", "psnr_resolved_db")]
                if changes:
                    change, end, _ = changes[0]
                    res, raw = lag(s, "psnr_resolved_db", change, end), lag(s, "psnr_db", change, end)
                    lagtext = "-" if res is None else f"{res} ({raw})"
                else:
                    lagtext = "no step"
                lines.append(f"| {scene} | {b} | {m} | {fmt(after[0])} | {fmt(after[1])} | {fmt(whole[0])} | "
                             f"{fmt(whole[1])} | {lagtext} |")
    return "\n".join(lines)


def variations_summary(d):
    """Per variation and B: cv's and cv-notex's margin over spvg and over burley-B, 30 frames after, resolved."""
    lines = ["| scene | B | first change | cv - spvg raw | cv - spvg resolved | cv - burley raw | cv - burley "
             "resolved | best resolved, 30 after (dB) |", "|---|---:|---:|---:|---:|---:|---:|---|"]
    for v in d.variations:
        scene = scene_name(v)
        first, _ = light_changes(d.lights[scene])
        if first is None:
            continue
        for b in d.variation_budgets:
            group = f"B{b}"
            val = {(m, c): d.window_mean(("variations", scene, group, m), c, first, first + WINDOW - 1)
                   for m in d.methods("variations", scene, group) for c in ("psnr_db", "psnr_resolved_db")}
            g = lambda m, c: val.get((m, c), math.nan)  # noqa: E731
            best = ranked({m: g(m, "psnr_resolved_db") for m in d.methods("variations", scene, group)})
            burley = f"burley-{b}"
            lines.append(f"| {scene} | {b} | {first} | {sign(g('cv', 'psnr_db') - g('spvg', 'psnr_db'))} | "
                         f"{sign(g('cv', 'psnr_resolved_db') - g('spvg', 'psnr_resolved_db'))} | "
                         f"{sign(g('cv', 'psnr_db') - g(burley, 'psnr_db'))} | "
                         f"{sign(g('cv', 'psnr_resolved_db') - g(burley, 'psnr_resolved_db'))} | "
                         f"{best[0][0] + ' (' + fmt(best[0][1]) + ')' if best else 'n/a'} |")
    return "\n".join(lines)


def teaser_table(d):
    """light-off in quality mode over the 30 frames from the switch, beside the paper's teaser (samples, PSNR)."""
    keys = {m: ("teaser", "light-off", "target", m) for m in TEASER_METHODS}
    if not all(k in d.series for k in keys.values()):
        return None
    w = {m: {c: d.window_mean(k, c, SWITCH_FRAME, SWITCH_FRAME + WINDOW - 1)
             for c in ("mean_spp", "psnr_db", "psnr_resolved_db")} for m, k in keys.items()}
    spvg = w["spvg"]
    lines = ["| method | mean spp | x spvg | PSNR raw | dB vs spvg | PSNR resolved | dB vs spvg | paper dB vs spvg |",
             "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for m in TEASER_METHODS:
        s = w[m]
        label = "separable" if m.startswith("separable") else m
        pdb = PAPER.get(label, (None, None))[1]
        lines.append(f"| {m} | {fmt(s['mean_spp'], 1)} | {fmt(s['mean_spp'] / spvg['mean_spp'])} | "
                     f"{fmt(s['psnr_db'])} | {sign(s['psnr_db'] - spvg['psnr_db'])} | {fmt(s['psnr_resolved_db'])} | "
                     f"{sign(s['psnr_resolved_db'] - spvg['psnr_resolved_db'])} | "
                     f"{sign(pdb - PAPER['spvg'][1], 1) if pdb else '-'} |")
    return "\n".join(lines)


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


def quality_blocks(d):
    """Every table that depends on quality only (no time): byte-identical whatever --jobs was."""
    blocks = {}
    if any(j.stage == "quality" for j in d.jobs):
        blocks["equal-samples"] = equal_samples_table(d)
        blocks["lag"] = lag_table(d)
        blocks["pareto-quality"] = pareto_table(d)
    if any(j.stage == "variations" for j in d.jobs):
        blocks["variations"] = variations_summary(d)
        blocks["variations-methods"] = variations_table(d)  # every method's row: docs/results/variations.md
    if any(j.stage == "teaser" for j in d.jobs):
        t = teaser_table(d)
        if t:
            blocks["teaser"] = t
    spread = [j for j in d.jobs if j.stage == "spread"]
    if spread:
        blocks["seed-spread"] = spread_table(read_csv(spread[0].raw(d.raw_dir)))
    return blocks


# ---------------------------------------------------------------------------------------------------- time tables

def cost_ms(d):
    """(scene, group, method) -> SSS ms: the median over the cost stage's rounds of each round's mean over frames
    MEAN_FROM.., the frames the quality tables average: the mean, because a budget's frames that reuse a plan cost
    less than the frame that updates (docs/renderer.md, "Updating one frame in M")."""
    rounds = {}
    for j in d.jobs:
        if j.stage != "cost":
            continue
        by = {}
        for r in read_csv(j.raw(d.raw_dir)):
            if int(r["frame"]) >= MEAN_FROM:
                by.setdefault(r["method"], []).append(to_float(r["sss_ms"]))
        for m, xs in by.items():
            rounds.setdefault((j.meta["scene"], j.meta["group"], m), []).append(statistics.fmean(xs))
    return {key: median(xs) for key, xs in rounds.items()}


def family_curve(d, ms, scene, family, column):
    """[(ms, dB)] of a method family over its settings, sorted by time."""
    pts = []
    for m, group, *vals in quality_points(d, scene):
        if method_family(m) == family and (scene, group, m) in ms:
            v = vals[DEMO_COLUMNS[2:].index(column)]
            if math.isfinite(v) and ms[(scene, group, m)] > 0:
                pts.append((ms[(scene, group, m)], v))
    return sorted(pts)


def linear_at(points, x):
    """y at x on the line through the two of `points` [(x, y), ...] (sorted by x) that bracket x; None outside them
    (no extrapolation)."""
    if not points or x < points[0][0] or x > points[-1][0]:
        return None
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        if x0 <= x <= x1:
            return y0 if x1 == x0 else y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    return points[0][1]


def at_time(curve, t):
    """The curve's PSNR at time t (> 0), linear in log time between its two neighbouring points; None outside."""
    return linear_at([(math.log(ti), p) for ti, p in curve], math.log(t))


def equal_time_gap(curve, t, value):
    """(gap, text): `value` (an adaptive method's PSNR at its own SSS time t) minus the burley curve's PSNR at t
    (at_time: linear in log time between the two burley runs that bracket t), and its text; outside the burley
    runs' times no gap (None) and the words "beyond range" (slower than the slowest run) or "below range" (faster
    than the fastest), not an extrapolation; "n/a" without a curve, a time or a value."""
    if not curve or t is None or not math.isfinite(t) or t <= 0 or value is None or not math.isfinite(value):
        return None, "n/a"
    if t > curve[-1][0]:
        return None, "beyond range"
    if t < curve[0][0]:
        return None, "below range"
    gap = value - at_time(curve, t)
    return gap, sign(gap)


def equal_time_table(d, ms):
    lines = ["| scene | SSS ms (burley-B's) | raw: best (dB) | over next | over burley | resolved: best (dB) | "
             "over next | over burley | in range |", "|---|---|---|---:|---:|---|---:|---:|---|"]
    for scene in d.scenes:
        for b in BUDGETS + REACH_BUDGETS:
            t = ms.get((scene, f"B{b}", f"burley-{b}"))
            if t is None or not math.isfinite(t):
                continue
            cells, present = [], set()
            for column in ("psnr_db", "psnr_resolved_db"):
                vals = {}
                for f in FAMILIES:
                    v = at_time(family_curve(d, ms, scene, f, column), t)
                    if v is not None:
                        vals[f] = v
                        present.add(f)
                r = ranked(vals)
                cells += [f"{r[0][0]} ({fmt(r[0][1])})" if r else "n/a",
                          sign(r[0][1] - r[1][1]) if len(r) > 1 else "-",
                          sign(r[0][1] - vals["burley"]) if "burley" in vals else "-"]
            lines.append(f"| {scene} | {fmt(t)} (B {b}) | " + " | ".join(cells) +
                         f" | {', '.join(f for f in FAMILIES if f in present)} |")
    return "\n".join(lines)


def burley_samples_at(points, x):
    """Burley's sample count at value x of a curve [(x_N, y_N, N)] over its runs, y linear in x between the two runs
    that bracket x (PSNR: y = ln N, linear in dB; time: y = N, linear in ms, as a pass's time is affine in N);
    (None, "> N_max") or (None, "< N_min") outside the runs: no extrapolation."""
    pts = sorted(p for p in points if math.isfinite(p[0]))
    if not pts or x is None or not math.isfinite(x):
        return None, "n/a"
    if x > pts[-1][0]:
        return None, f"> {pts[-1][2]}"
    if x < pts[0][0]:
        return None, f"< {pts[0][2]}"
    return linear_at([(xi, yi) for xi, yi, _ in pts], x), None


def worth_table(d, ms, methods, lead_db=None, budgets=None):
    """Per scene, B and adaptive method: the burley-N its image is worth (the N of equal PSNR, raw and resolved,
    interpolated in log N between the burley runs) beside the burley-N that its SSS time buys (the N of equal time).
    The first is quality alone, so it holds on any device: the method wins at equal time wherever its pass costs less
    than that many samples of burley's. With `lead_db`, a column more: the burley-N of the raw PSNR lead_db under
    the method's, which its pass must cost less than for it to lead burley-N by lead_db at equal time. `budgets`:
    the rows' B (default BUDGETS)."""
    lead = f" | raw, {lead_db:g} dB under" if lead_db else ""
    lines = [f"| scene | B | method | worth burley-N, raw{lead} | resolved | its SSS time buys burley-N |",
             "|---|---:|---|---:|" + ("---:|" if lead_db else "") + "---:|---:|"]

    def cell(value, text):
        return text if value is None else fmt(value, 1)

    for scene in d.scenes:
        runs = [b for b in BUDGETS + REACH_BUDGETS if f"B{b}" in d.groups]
        burley = {c: [(d.window_mean(("quality", scene, f"B{b}", f"burley-{b}"), c, MEAN_FROM), math.log(b), b)
                      for b in runs] for c in ("psnr_db", "psnr_resolved_db")}
        times = [(ms[(scene, f"B{b}", f"burley-{b}")], b, b) for b in runs if (scene, f"B{b}", f"burley-{b}") in ms]
        for b in budgets or BUDGETS:
            for m in methods:
                key = ("quality", scene, f"B{b}", m)
                if key not in d.series:
                    continue
                cells = []
                targets = [("psnr_db", 0.0)] + ([("psnr_db", lead_db)] if lead_db else []) + [("psnr_resolved_db", 0.0)]
                for c, under in targets:
                    log_n, text = burley_samples_at(burley[c], d.window_mean(key, c, MEAN_FROM) - under)
                    cells.append(cell(None if log_n is None else math.exp(log_n), text))
                cells.append(cell(*burley_samples_at(times, ms.get((scene, f"B{b}", m)))))
                lines.append(f"| {scene} | {b} | {m} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def pareto_time_table(d, ms):
    """Per scene, setting and method: the SSS ms, its ratio to burley-B's, and for the adaptive methods the PSNR
    gap (raw, resolved; frames MEAN_FROM..) to the burley runs interpolated at the method's own SSS time."""
    lines = ["| scene | method | B | SSS ms (mean, frames 20..) | x burley-B | dB vs burley at equal time, raw | "
             "resolved |", "|---|---|---:|---:|---:|---:|---:|"]
    curves = {}
    for (scene, group, m), t in sorted(ms.items(), key=lambda kv: (d.scenes.index(kv[0][0]) if kv[0][0] in d.scenes
                                                                  else 99, d.groups.index(kv[0][1]), kv[0][2])):
        ref = ms.get((scene, group, f"burley-{group[1:]}")) if group != "fixed" else None
        gaps = ["-", "-"]
        if m in ADAPTIVE:
            key = ("quality", scene, group, m)
            for i, column in enumerate(("psnr_db", "psnr_resolved_db")):
                if (scene, column) not in curves:
                    curves[(scene, column)] = family_curve(d, ms, scene, "burley", column)
                gaps[i] = equal_time_gap(curves[(scene, column)], t, d.window_mean(key, column, MEAN_FROM))[1]
        lines.append(f"| {scene} | {m} | {setting_of(group, m)} | {fmt(t)} | "
                     f"{fmt(t / ref) if ref else '-'} | {gaps[0]} | {gaps[1]} |")
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


def teaser_time_table(rows):
    """light-off after the switch (emcv-eval in quality mode): SSS ms beside the paper's teaser times."""
    after = [r for r in rows if r["scene"] == "light-off" and int(r["frame"]) >= SWITCH_FRAME]
    ms = {m: median([to_float(r["sss_ms"]) for r in after if r["method"] == m]) for m in TEASER_METHODS}
    if not math.isfinite(ms.get("spvg", math.nan)):
        return None
    lines = ["| method | SSS pass ms (ours) | x spvg (ours) | paper ms | x spvg (paper) |", "|---|---:|---:|---:|---:|"]
    for m in TEASER_METHODS:
        label = "separable" if m.startswith("separable") else m
        pm = PAPER.get(label, (None, None))[0]
        lines.append(f"| {m} | {fmt(ms[m])} | {fmt(ms[m] / ms['spvg'])} | {fmt(pm, 1) if pm else '-'} | "
                     f"{fmt(pm / PAPER['spvg'][0]) if pm else '-'} |")
    return "\n".join(lines)


def read_matrix(path):
    import numpy as np
    return np.loadtxt(path, delimiter=",", ndmin=2)


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


def scaling_groups(rows, pixels):
    groups = {}
    for r in rows:
        if int(r["frame"]) < 2:  # warm-up, and the adaptive methods' first (full-rate) frames
            continue
        x = int(r["width"]) * int(r["height"]) if pixels else to_float(r["sss_scale"])
        groups.setdefault(r["method"], {}).setdefault(x, []).append(r)
    return groups


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


def stage_rows(d, stage):
    rows = []
    for j in d.jobs:
        if j.stage == stage:
            rows += read_csv(j.raw(d.raw_dir))
    return rows


# ---------------------------------------------------------------------------------------------------- plots

def plt_module():
    return plots.pyplot()


def save_fig(fig, out_dir, name):
    plots.save(fig, os.path.join(out_dir, name), tight=True)


def plot_pareto(d, ms, out_dir, device):
    """Per scene: PSNR raw and resolved against SSS ms (when the cost stage ran) and against mean samples."""
    plt = plt_module()
    for scene in d.scenes:
        points = quality_points(d, scene)
        xs_kinds = [("spp", "mean samples per SSS pixel (log)")] + ([("ms", "SSS pass ms (mean; log)")] if ms else [])
        fig, axes = plt.subplots(2, len(xs_kinds), figsize=(6 * len(xs_kinds), 8), squeeze=False)
        for col, (kind, xlabel) in enumerate(xs_kinds):
            for row, (column, title) in enumerate((("psnr_db", "raw"), ("psnr_resolved_db", "resolved (taa)"))):
                ax = axes[row][col]
                vi = DEMO_COLUMNS[2:].index(column)
                burley = family_curve(d, ms, scene, "burley", column) if kind == "ms" else []
                for family in FAMILIES:
                    pts = []
                    for m, group, *vals in points:
                        if method_family(m) != family:
                            continue
                        x = vals[0] if kind == "spp" else ms.get((scene, group, m), math.nan)
                        if math.isfinite(x) and x > 0 and math.isfinite(vals[vi]):
                            label = m.split("-")[-1] if family in ("burley", "separable") else group[1:]
                            if kind == "ms" and m in ADAPTIVE:  # the pareto-time table's equal-time column
                                gap, text = equal_time_gap(burley, x, vals[vi])
                                if gap is not None:  # outside burley's times the point's place says it
                                    label += f": {text} dB"
                            pts.append((x, vals[vi], label))
                    pts.sort()
                    if pts:
                        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", color=COLOURS[family], label=family)
                        for x, y, l in pts:
                            ax.annotate(l, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
                for m, group, *vals in points:
                    if m == "diffuse" and math.isfinite(vals[vi]):
                        ax.axhline(vals[vi], color="black", lw=0.8, ls=":", label="diffuse (no SSS)")
                ax.set_xscale("log")
                ax.set_xlabel(xlabel)
                ax.set_ylabel(f"PSNR {title}, dB (mean, frames {MEAN_FROM}..)")
                ax.grid(True, which="both", alpha=0.3)
                ax.legend(fontsize=7, loc="lower right")
        fig.suptitle(f"{scene}: quality at equal cost; labels: B, or separable's taps; against SSS ms, an adaptive "
                     f"method's B: its dB over burley at its own time, where burley's times reach it ({device})",
                     fontsize=10)
        save_fig(fig, out_dir, f"pareto-{scene}.png")


def plot_frames(d, out_dir, device):
    """Per quality scene with lights that change: PSNR per frame, raw (dashed) and resolved (solid), at B = 8."""
    plt = plt_module()
    for scene in d.scenes:
        if scene not in d.lights or light_changes(d.lights[scene])[0] is None:
            continue
        fig, ax = plt.subplots(figsize=(8, 4.5))
        for m, g in story_methods(d, "quality", scene):
            s = d.series[("quality", scene, g, m)]
            fr = sorted(s)
            c = COLOURS[method_family(m)]
            ax.plot(fr, [s[f]["psnr_resolved_db"] for f in fr], "-", color=c, label=f"{m} resolved")
            ax.plot(fr, [s[f]["psnr_db"] for f in fr], "--", color=c, lw=0.8, label=f"{m} raw")
        for change, _end, _ in light_changes(d.lights[scene])[1]:
            ax.axvline(change, color="grey", lw=0.8)
        ax.set_xlabel("frame (grey: light changes)")
        ax.set_ylabel("PSNR vs reference, dB")
        ax.set_title(f"{scene}, B = {STORY_BUDGET}: raw (dashed) and resolved (solid) per frame ({device})",
                     fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6, ncol=3, loc="lower right")
        save_fig(fig, out_dir, f"frames-{scene}.png")


def plot_switch(rows_by_scene, out_dir, device):
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
        axes[0].set_title(f"{scene}: samples and SSS pass time per frame, quality mode ({device})", fontsize=10)
        save_fig(fig, out_dir, f"switch-{scene}.png")


def plot_heatmaps(heat_dir, frames, out_dir, device):
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
    fig.suptitle(f"light-off: samples per pixel around the switch at frame {SWITCH_FRAME}, quality mode ({device})",
                 fontsize=10)
    save_fig(fig, out_dir, "heatmaps-light-off.png")


def plot_scaling(groups, key, xlabel, name, out_dir, device):
    plt = plt_module()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
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
    save_fig(fig, out_dir, f"{key}.png")


# ---------------------------------------------------------------------------------------------------- assembling

def replace_block(text, name, body, path=DOC):
    return docs.replace_block(text, name, body, path, "run_eval.py")


def load_data(jobs, raw_dir, c):
    d = Data(jobs, raw_dir)
    d.scenes, d.groups, d.variations, d.variation_budgets = c.scenes, c.groups, c.variations, c.variation_budgets
    return d


def provenance(jobs, raw_dir):
    """The commits, devices and runs the raw files name."""
    commits, devices = [], []
    for j in jobs:
        path = os.path.join(j.raw(raw_dir), "job.txt") if j.stage == "heatmap" else j.raw(raw_dir)
        h = header(path)
        for lst, v in ((commits, h.get("commit")), (devices, h.get("device"))):
            if v and v not in lst:
                lst.append(v)
    runs = []
    for name in sorted(os.listdir(raw_dir)):
        if name.startswith("run-") and name.endswith(".txt"):
            with open(os.path.join(raw_dir, name)) as f:
                runs.extend(line for line in f.read().splitlines() if line.strip())  # a resumed run adds a line
    return commits, devices, runs


def assemble(jobs, raw_dir, c, out_dir, write_doc):
    missing = missing_jobs(jobs, raw_dir)
    if missing:
        die(f"cannot merge: {len(missing)} of {len(jobs)} jobs have no raw file from this job list in "
            f"{shown(raw_dir)}; run them (--shard, or without it) first:\n  " + "\n  ".join(missing))
    commits, devices, runs = provenance(jobs, raw_dir)
    device = devices[0] if devices else "unknown GL renderer"
    d = load_data(jobs, raw_dir, c)
    blocks = quality_blocks(d)
    stages = {j.stage for j in jobs}
    ms = cost_ms(d) if "cost" in stages else {}
    if "quality" in stages:
        plot_pareto(d, ms, out_dir, device)
        plot_frames(d, out_dir, device)
    if ms:
        blocks["equal-time"] = equal_time_table(d, ms)
        blocks["pareto-time"] = pareto_time_table(d, ms)
        blocks["worth"] = worth_table(d, ms, ["cv"], budgets=[STORY_BUDGET, BUDGETS[-1]])  # results.md: B = 8, 32
        blocks["worth-methods"] = worth_table(d, ms, ADAPTIVE, lead_db=1.0)
    if "switch" in stages:
        rows = stage_rows(d, "switch")
        plot_switch({s: [r for r in rows if r["scene"] == s] for s in ("light-off", "flicker", "club")}, out_dir,
                    device)
        blocks["switch"] = switch_table(rows)
        t = teaser_time_table(rows)
        if t:
            blocks["teaser-time"] = t
    heat = [j for j in jobs if j.stage == "heatmap"]
    if heat:
        frames = heat[0].meta["frames"]
        plot_heatmaps(heat[0].raw(raw_dir), frames, out_dir, device)
        blocks["heatmaps"] = heatmap_table(heat[0].raw(raw_dir), frames)
    if "scaling-resolution" in stages:
        g = scaling_groups(stage_rows(d, "scaling-resolution"), pixels=True)
        plot_scaling(g, "scaling-resolution", "pixels (log)", "static: cost against resolution", out_dir, device)
        blocks["scaling-resolution"] = scaling_table(g, "pixels", lambda x: f"{x}") + "\n\n" + per_sss_pixel_table(g)
    if "scaling-radius" in stages:
        g = scaling_groups(stage_rows(d, "scaling-radius"), pixels=False)
        plot_scaling(g, "scaling-radius", "mean free path scale (radius on screen, log)",
                     "static at 256x256: cost against the scattering radius", out_dir, device)
        blocks["scaling-radius"] = scaling_table(g, "mfp scale", lambda x: f"{x:g}")
    made = f"raw files made at commit {', '.join(commits) or 'unknown'}, assembled at {git_commit()}"
    context = (f"Renderer: **{device}** (GL_RENDERER), {made}. Runs (command, shard, jobs, wall time, load average "
               f"1/5/15 min at the end):\n\n" + "\n".join(f"- {r}" for r in runs))
    # The long tables go to files of their own beside the plots; docs/results.md holds the rest and links to them.
    for name, file in (("pareto-quality", "pareto.md"), ("pareto-time", "pareto-time.md"),
                       ("worth-methods", "worth.md"), ("equal-time", "equal-time.md"),
                       ("variations-methods", "variations.md"), ("switch", "switch.md"),
                       ("scaling-resolution", "scaling-resolution.md"), ("scaling-radius", "scaling-radius.md"),
                       ("seed-spread", "seed-spread.md")):
        if name in blocks:
            write_atomically(os.path.join(out_dir, file),
                             f"<!-- Generated by scripts/eval/run_eval.py at {made}: do not edit. -->\n\n"
                             + blocks.pop(name) + "\n")
    if write_doc and os.path.exists(DOC):
        text = open(DOC).read()
        note = (f"_Regenerated by `/usr/bin/python3 scripts/eval/run_eval.py --merge` from the raw files ({made}); "
                f"the runs that made them: the context block._\n\n")
        text = replace_block(text, "context", context)
        for name, body in blocks.items():
            if f"<!-- BEGIN GENERATED: {name} -->" in text:
                text = replace_block(text, name, note + body)
            else:
                print(f"run_eval.py: docs/results.md has no GENERATED block '{name}' (printed below only)")
        write_atomically(DOC, text)
    print(f"\n## context\n{context}")
    for name, body in blocks.items():
        print(f"\n## {name}\n{body}")


# ---------------------------------------------------------------------------------------------------- main

def parse_shard(text):
    m = re.fullmatch(r"(\d+)/(\d+)", text or "")
    if not m:
        die(f"--shard must be I/N with whole numbers 0 <= I < N (got '{text}')")
    i, n = int(m.group(1)), int(m.group(2))
    if n < 1 or i >= n:
        die(f"--shard I/N needs N >= 1 and 0 <= I < N (got {i}/{n})")
    return i, n


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--size", default="128x128", help="size of the quality and cost jobs (default 128x128)")
    p.add_argument("--seeds", default="1,2", help="seeds of the quality runs (default 1,2)")
    p.add_argument("--stages", default=",".join(QUALITY_STAGES + TIMING_STAGES),
                   help="stages to run and assemble (default: all)")
    p.add_argument("--jobs", default="1", help="quality jobs run at once (default 1); timing jobs always one")
    p.add_argument("--shard", default=None, help="I/N: run only the jobs whose index %% N == I")
    p.add_argument("--raw-dir", default=None, help="raw CSVs (default docs/results/raw; with --quick a temp dir)")
    p.add_argument("--merge", action="store_true", help="render nothing: assemble tables and plots from the raw "
                                                        "files of every shard")
    p.add_argument("--plots-only", action="store_true", help="the same as --merge")
    p.add_argument("--resume", action="store_true", help="run only the selected jobs whose raw file is missing "
                                                         "or was made by another command")
    p.add_argument("--list", action="store_true", help="print the job list (index, stage/name, kind, command; "
                                                      "with --shard, that shard's) and exit")
    p.add_argument("--quick", action="store_true", help="64x64, light-off and flicker, one seed: for checks")
    p.add_argument("--check-determinism", action="store_true",
                   help="run the --quick quality jobs with --jobs 1 and --jobs 2 into two temporary raw folders "
                        "and require byte-identical quality tables")
    a = p.parse_args(argv)
    try:
        a.jobs = int(a.jobs)
    except ValueError:
        die(f"--jobs must be a whole number >= 1 (got '{a.jobs}')")
    if a.jobs < 1:
        die(f"--jobs must be >= 1 (got {a.jobs})")
    a.shard = parse_shard(a.shard) if a.shard is not None else None
    try:
        a.seeds = [int(s) for s in a.seeds.split(",")]
    except ValueError:
        die(f"--seeds must be whole numbers separated by commas (got '{a.seeds}')")
    if not re.fullmatch(r"[1-9]\d*x[1-9]\d*", a.size):
        die(f"--size must be WxH (got '{a.size}')")
    a.stages = a.stages.split(",")
    known = QUALITY_STAGES + TIMING_STAGES
    bad = [s for s in a.stages if s not in known]
    if bad:
        die(f"--stages: unknown {', '.join(bad)} (known: {', '.join(known)})")
    if "quality" in a.stages or "variations" in a.stages:
        if "lights" not in a.stages:
            a.stages.insert(0, "lights")  # the light changes the quality tables are measured from
    if a.quick:
        a.size, a.seeds = "64x64", a.seeds[:1]
    a.merge = a.merge or a.plots_only
    return a


def check_tools(build, jobs):
    for tool in sorted({j.tool for j in jobs}):
        if not os.access(os.path.join(build, "bin", tool), os.X_OK):
            die(f"no {tool} in {build}/bin (cmake --build {build} --target emcv-demo emcv-eval emcv-golden)")


def use_methods(listing):
    """Sets ADAPTIVE (the rows of `emcv-demo --list-methods` whose passes are "adaptive", in its order), FAMILIES
    (burley, separable, then each adaptive method) and TEASER_METHODS (separable-17, then the adaptive methods)."""
    global ADAPTIVE, FAMILIES, TEASER_METHODS
    ADAPTIVE = [line.split("\t")[0] for line in listing.splitlines() if line.split("\t")[1:2] == ["adaptive"]]
    if not ADAPTIVE:
        die("the method listing names no adaptive method (emcv-demo --list-methods: <name> TAB <passes> TAB <what>)")
    FAMILIES = ["burley", "separable"] + ADAPTIVE
    TEASER_METHODS = ["separable-17"] + ADAPTIVE


def method_listing(build, raw_dir, merge):
    """emcv-demo's --list-methods: for a merge, the one stored beside the raw files by the run that rendered them
    (METHODS_FILE), else the build's, which a render stores there."""
    stored = os.path.join(raw_dir, METHODS_FILE) if raw_dir else None
    if merge and stored and os.path.isfile(stored):
        with open(stored, encoding="utf-8") as f:
            return f.read()
    demo = os.path.join(build, "bin", "emcv-demo")
    if not os.access(demo, os.X_OK):
        die(f"no emcv-demo in {build}/bin to list the methods (cmake --build {build} --target emcv-demo)"
            + (f", and no {METHODS_FILE} in {shown(raw_dir)}" if merge and raw_dir else ""))
    r = subprocess.run([demo, "--list-methods"], capture_output=True, text=True)
    if r.returncode != 0:
        die(f"emcv-demo --list-methods failed: {r.stderr.strip()}")
    if stored and not merge:
        os.makedirs(raw_dir, exist_ok=True)
        with open(stored, "w", encoding="utf-8") as f:
            f.write(r.stdout)
    return r.stdout


def shard_jobs(a, jobs):
    """The jobs of --shard I/N: those whose index % N == I (every job without --shard)."""
    return [j for j in jobs if a.shard is None or j.index % a.shard[1] == a.shard[0]]


def render(a, jobs, raw_dir, workers):
    selected = shard_jobs(a, jobs)
    if a.resume:
        stale = {m.split(" ", 1)[0] for m in missing_jobs(selected, raw_dir)}
        selected = [j for j in selected if str(j.index) in stale]
    check_tools(a.build, selected)
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="emcv-eval-") as tmp:
        ctx = Context(a.build, raw_dir, tmp)
        print(f"run_eval.py: {len(selected)} of {len(jobs)} jobs"
              f"{'' if a.shard is None else f' (shard {a.shard[0]}/{a.shard[1]})'}, {workers} at a time "
              f"(timing jobs one at a time), raw files in {shown(raw_dir)}", flush=True)
        run_jobs(ctx, selected, workers)
    return selected, time.monotonic() - start


def check_determinism(a):
    use_methods(method_listing(a.build, None, False))
    c = Config("64x64", a.seeds[:1], True, ["lights", "quality", "variations"])
    jobs = job_list(c)
    tables = []
    with tempfile.TemporaryDirectory(prefix="emcv-eval-check-") as tmp:
        for workers in (1, 2):
            raw = os.path.join(tmp, f"jobs{workers}")
            a.shard, a.resume = None, False
            render(a, jobs, raw, workers)
            blocks = quality_blocks(load_data(jobs, raw, c))
            tables.append("".join(f"## {k}\n{v}\n" for k, v in blocks.items()))
    if tables[0] != tables[1]:
        sys.stdout.writelines(difflib.unified_diff(tables[0].splitlines(True), tables[1].splitlines(True),
                                                   "--jobs 1", "--jobs 2"))
        die("the quality tables of --jobs 2 differ from those of --jobs 1 (diff above)")
    print(f"run_eval.py: the quality tables of --jobs 1 and --jobs 2 are byte-identical "
          f"({len(tables[0])} bytes, {len(jobs)} jobs at {c.size})")


def run_file_name(shard, stages, raw_dir, resume):
    """The file that records a run (its command, jobs, time and load) for the context block. A run of some
    stages (--stages) gets a name of its own, so that it does not replace the record of the run that made the
    other stages' raw files; a run of every stage (not --resume) remade all of its shard's raw files, so the
    records of this shard's earlier stage runs are removed."""
    if set(stages) == set(QUALITY_STAGES + TIMING_STAGES):
        if not resume:
            for name in os.listdir(raw_dir):
                if name.startswith(f"run-{shard}-stages-") and name.endswith(".txt"):
                    os.remove(os.path.join(raw_dir, name))
        return f"run-{shard}.txt"
    return f"run-{shard}-stages-{'+'.join(stages)}.txt"


def write_run_record(raw_dir, shard, stages, resume, line):
    """Records a run (one line) in its file (run_file_name). A resumed run made only the raw files that were
    missing, so the runs that made the others stay on record, its line after theirs; any other run replaces the
    record. The context block lists every line (provenance)."""
    record = os.path.join(raw_dir, run_file_name(shard, stages, raw_dir, resume))
    earlier = ""
    if resume and os.path.exists(record):
        with open(record) as f:
            earlier = f.read()
        if earlier and not earlier.endswith("\n"):
            earlier += "\n"
    write_atomically(record, earlier + line + "\n")


def main(argv):
    a = parse_args(argv)
    if a.check_determinism:
        check_determinism(a)
        return
    c = Config(a.size, a.seeds, a.quick, a.stages)
    raw_dir = os.path.abspath(a.raw_dir or (os.path.join(tempfile.gettempdir(), "emcv-eval-quick") if a.quick
                                            else DEFAULT_RAW))
    use_methods(method_listing(a.build, None if a.list else raw_dir, a.merge))
    jobs = job_list(c)
    if a.list:
        for j in shard_jobs(a, jobs):
            print(f"{j.index}\t{j.stage}/{j.name}\t{'timing' if j.serial else 'quality'}\t{j.command_text()}")
        return
    default = raw_dir == DEFAULT_RAW and not a.quick
    out_dir = RESULTS if default else os.path.join(raw_dir, "out")
    if not a.merge:
        selected, wall = render(a, jobs, raw_dir, a.jobs)
        shard = "all" if a.shard is None else f"{a.shard[0]}-of-{a.shard[1]}"
        load = " ".join(f"{x:.1f}" for x in os.getloadavg())
        write_run_record(raw_dir, shard, a.stages, a.resume,
                         f"`{' '.join(['/usr/bin/python3 scripts/eval/run_eval.py'] + argv)}`: shard {shard}, "
                         f"{len(selected)} jobs, --jobs {a.jobs}, {wall / 60:.1f} min, load {load} on "
                         f"{os.cpu_count()} CPUs")
        if a.shard is not None and missing_jobs(jobs, raw_dir):
            print(f"run_eval.py: shard {a.shard[0]}/{a.shard[1]} done; once every shard's raw files are in "
                  f"{shown(raw_dir)}, assemble with --merge")
            return
    assemble(jobs, raw_dir, c, out_dir, default)


if __name__ == "__main__":
    main(sys.argv[1:])
