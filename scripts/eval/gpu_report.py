#!/usr/bin/python3
"""Turns the GPU runs of scripts/eval/gpu_runs.sh into the generated blocks of docs/results.md, section "GPU":
    /usr/bin/python3 scripts/eval/gpu_report.py [--doc PATH] docs/results/gpu
The run directory holds glinfo.txt, demo-<size>/metrics.csv (PSNR per frame against the converged reference),
eval-<size>-run<k>.csv (SSS pass ms per frame, three runs), scaling-<size>.csv (each CSV may be stored gzip-compressed
as NAME.csv.gz, as in docs/results/gpu/) and, from the runs that have them,
cost-<setting>/ (scripts/eval/sss_cost.py --save-raw: the SSS passes at equal samples), clocks.txt (nvidia-smi)
and steps.txt (each step's seconds), equal-time.txt (emcv-demo's summary). Writes the document (docs/results.md unless
--doc) atomically: the blocks gpu-context, gpu-teaser, gpu-scaling, gpu-cost (with the statistics' grain K),
gpu-equal-time and gpu-targets (issue 18's GPU targets, judged only where the
runs' automatic clock was GPU timestamps, i.e. on a hardware renderer)."""
import argparse
import glob
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_eval as ev  # noqa: E402  (the llvmpipe evaluation's switch frame, the paper's numbers, docs/results.md)
import sss_cost  # noqa: E402  (the equal-samples tables, recomputed from the runs' CSVs)
from emcv_eval import ROOT, docs  # noqa: E402
from emcv_eval.runner import read_csv  # noqa: E402,F401  (a run's CSV, or its gzip-compressed copy PATH.gz)
from emcv_eval.tables import fmt, mean_finite, median, to_float  # noqa: E402

TEASER = ["diffuse", "separable-17", "burley-16", "spvg", "cv", "cv-notex"]
PAPER_LABEL = {"separable-17": "separable", "spvg": "spvg", "cv": "cv"}
SCALING = ["burley-16", "separable-17", "spvg", "cv", "cv-notex"]


def csvs(pattern):
    """The CSVs matching PATTERN (ending in .csv), plain or gzip-compressed, by their plain name."""
    return sorted({p[:-3] if p.endswith(".gz") else p for p in glob.glob(pattern) + glob.glob(pattern + ".gz")})


def size_key(size):
    w, h = (int(v) for v in size.split("x"))
    return w * h


def teaser(run_dir, size):
    first, last = ev.SWITCH_FRAME, ev.SWITCH_FRAME + 29
    quality = [r for r in read_csv(os.path.join(run_dir, f"demo-{size}", "metrics.csv"))
               if first <= int(r["frame"]) <= last]
    cost = []
    for path in csvs(os.path.join(run_dir, f"eval-{size}-run*.csv")):
        cost += [r for r in read_csv(path) if first <= int(r["frame"]) <= last]
    rows = {}
    for m in TEASER:
        q = [r for r in quality if r["method"] == m]
        c = [r for r in cost if r["method"] == m]
        rows[m] = {"ms": median([to_float(r["sss_ms"]) for r in c]),
                   "spp": mean_finite([to_float(r["mean_spp"]) for r in c]),
                   "db": mean_finite([to_float(r["psnr_db"]) for r in q]),
                   "frames": len(q), "runs": len(c) // max(len(q), 1)}
    spvg = rows["spvg"]
    lines = [f"**{size}**, light-off frames {first}-{last} (the 30 frames from the switch); SSS ms: median over "
             f"the frames of {rows['spvg']['runs']} emcv-eval runs, clock {clock_of(cost)}; PSNR: mean over the "
             f"frames of the emcv-demo run.",
             "",
             "| method | SSS pass ms | x spvg | mean spp | x spvg | PSNR dB | dB vs spvg | paper ms | paper x spvg "
             "| paper dB vs spvg |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for m in TEASER:
        r = rows[m]
        label = PAPER_LABEL.get(m)
        pm, pdb = ev.PAPER.get(label, (None, None)) if label else (None, None)
        paper_ratio = fmt(pm / ev.PAPER["spvg"][0]) if pm else "-"
        paper_db = fmt(pdb - ev.PAPER["spvg"][1], 1) if pdb else "-"
        ms_ratio = r["ms"] / spvg["ms"] if spvg["ms"] else float("nan")
        spp_ratio = r["spp"] / spvg["spp"] if spvg["spp"] else float("nan")
        lines.append(f"| {m} | {fmt(r['ms'])} | {fmt(ms_ratio)} | {fmt(r['spp'], 1)} | "
                     f"{fmt(spp_ratio)} | {fmt(r['db'])} | {fmt(r['db'] - spvg['db'])} | "
                     f"{fmt(pm, 1) if pm else '-'} | {paper_ratio} | {paper_db} |")
    return "\n".join(lines)


def clock_of(rows):
    """The clock of emcv-eval rows: their timing column; runs from before --timing have none and took the wall
    clock with glFinish at every pass boundary."""
    return "/".join(sorted({r.get("timing") or "wall" for r in rows})) or "none"


def scaling(run_dir):
    rows = [r for path in csvs(os.path.join(run_dir, "scaling-*.csv")) for r in read_csv(path)]
    groups = {}
    for r in rows:
        if int(r["frame"]) < 1:  # frame 0 compiles and warms up
            continue
        groups.setdefault(r["method"], {}).setdefault(f"{r['width']}x{r['height']}", []).append(r)
    methods = [m for m in SCALING if m in groups]
    sizes = sorted({s for g in groups.values() for s in g}, key=size_key)
    lines = [f"Clock {clock_of(rows)}.", "",
             "| size | SSS pixels | " + " | ".join(f"{m} ms" for m in methods) + " | " +
             " | ".join(f"{m} ns/SSS px" for m in methods) + " |",
             "|---|---:|" + "---:|" * (2 * len(methods))]
    for s in sizes:
        sss = int(next(groups[m][s] for m in methods if s in groups[m])[0]["sss_pixels"])
        ms = [median([to_float(r["sss_ms"]) for r in groups[m].get(s, [])]) for m in methods]
        lines.append(f"| {s} | {sss} | " + " | ".join(fmt(x) for x in ms) + " | " +
                     " | ".join(fmt(1e6 * x / max(sss, 1), 2) for x in ms) + " |")
    return "\n".join(lines)


# The equal-samples runs of gpu_runs.sh, in the order the cost block shows them.
COST_RUNS = ["cost-budget8-gpu", "cost-budget8-wall", "cost-budget16-gpu", "cost-budget16-wall", "cost-quality-gpu",
             "cost-blocks-gpu"]


def load_cost(run_dir):
    """{run name: (settings, {label: [one summary per run]}, clocks)} for the cost runs present."""
    return {name: sss_cost.load_saved(os.path.join(run_dir, name)) for name in COST_RUNS
            if os.path.exists(os.path.join(run_dir, name, sss_cost.SETTINGS))}


def cost_block(cost, rel):
    if not cost:
        return (f"No equal-samples runs in `{rel}/`: these runs predate step 3 of `gpu_runs.sh` (`sss_cost.py "
                f"--save-raw`, the folders `cost-*/`).")
    return "\n\n".join(sss_cost.table(st["setting"], res, st["methods"], st["baseline"], st["label_column"])
                        for st, res, _ in cost.values())


def equal_time_block(run_dir, rel):
    """The adaptive methods against burley-N at their own SSS time: the equal-time lines of gpu_runs.sh's
    emcv-demo run (equal-time.txt), with the run's header line that names its size, budget and clock."""
    path = os.path.join(run_dir, "equal-time.txt")
    if not os.path.isfile(path):
        return (f"No equal-time run in `{rel}/`: these runs predate the `equal-time` step of `gpu_runs.sh` "
                f"(`equal-time.txt`).")
    lines = open(path).read().splitlines()
    header = [line for line in lines if line.startswith("scene ") or line.startswith("times: ")]
    equal = [line for line in lines if " vs burley-N at " in line]
    if not equal:
        sys.exit(f"gpu_report.py: {path} has no equal-time line (' vs burley-N at '): not emcv-demo's summary")
    fence = "`" * 3
    return f"`{rel}/equal-time.txt`:\n\n{fence}text\n" + "\n".join(header + equal) + f"\n{fence}"


def method_ms(run, method):
    """The median over runs of a method's median SSS ms in one cost run, and the median of its ratios to the
    run's baseline (both as sss_cost.table shows them)."""
    st, res, _ = run
    row = next(r for r in sss_cost.table_rows(res, st["methods"], st["baseline"]) if r[1] == method)
    return row[2], row[3], row[5]


def fixed_ms(b8, b16, method_at):
    """The SSS time that does not scale with samples, from two budgets: t(B) = F + c B gives F = 2 t(8) - t(16)."""
    return 2.0 * method_ms(b8, method_at(8))[0] - method_ms(b16, method_at(16))[0]


def targets(cost, hardware, why_not):
    """Issue 18's GPU targets, measured from the cost runs: (target, measured, met) rows. Judged only when the
    runs were on a hardware renderer (its automatic clock is GPU timestamps) and the run's own clock is gpu."""
    rows = []

    def judge(run_names, ok):
        if not hardware:
            return f"not judged: {why_not}"
        if any(cost[n][2] != {"gpu"} for n in run_names):
            return "not judged: the runs' clock is not gpu"
        return "yes" if ok else "no"

    def missing(names):
        gone = [n for n in names if n not in cost]
        return f"not measured (no {', '.join(gone)})" if gone else None

    def size(name):
        return cost[name][0]["size"]

    need = ["cost-budget16-gpu"]
    if missing(need):
        rows.append(("burley-16's SSS time at most 0.20 ms", missing(need), "-"))
    else:
        ms = method_ms(cost["cost-budget16-gpu"], "burley-16")[0]
        rows.append((f"burley-16's SSS time at most 0.20 ms ({size(need[0])})", f"{ms:.3f} ms",
                     judge(need, ms <= 0.20)))
    need = ["cost-budget8-gpu"]
    if missing(need):
        rows.append(("cv at budget 8 at most 1.1x burley-8", missing(need), "-"))
    else:
        for m in ("cv", "spvg", "cv-notex"):
            ratio = method_ms(cost["cost-budget8-gpu"], m)[1]
            rows.append((f"{m} at budget 8 at most 1.1x burley-8 ({size(need[0])})", f"{ratio:.2f}x",
                         judge(need, ratio <= 1.1)))
    need = ["cost-budget8-gpu", "cost-budget16-gpu"]
    if missing(need):
        rows.append(("the SSS time that does not scale with samples at most 20 us", missing(need), "-"))
    else:
        for m in ("burley", "cv", "spvg", "cv-notex"):
            at = (lambda b: f"burley-{b}") if m == "burley" else (lambda b, m=m: m)
            f_us = 1000.0 * fixed_ms(cost[need[0]], cost[need[1]], at)
            label = "burley-B" if m == "burley" else m
            rows.append((f"{label}'s SSS time that does not scale with samples at most 20 us "
                         f"(2 t(8) - t(16), {size(need[0])})", f"{f_us:.1f} us", judge(need, f_us <= 20.0)))
    need = ["cost-quality-gpu"]
    if missing(need):
        rows.append(("after the switch (quality target), cv's time ratio to spvg within 0.1 of its sample ratio",
                     missing(need), "-"))
    else:
        _, time_ratio, spp_ratio = method_ms(cost[need[0]], "cv")
        rows.append((f"after the switch (quality target, frames {cost[need[0]][0]['first']}-"
                     f"{cost[need[0]][0]['last']}), cv's time ratio to spvg within 0.1 of its sample ratio "
                     f"({size(need[0])})", f"{time_ratio:.2f} against {spp_ratio:.2f}",
                     judge(need, abs(time_ratio - spp_ratio) <= 0.1)))
    return rows


def targets_block(rows):
    return "\n".join(["| target (issue 18, on a GPU) | measured | met |", "|---|---|---|"] +
                      [f"| {t} | {m} | {ok} |" for t, m, ok in rows])


def clock_state(run_dir):
    """One line on the GPU's clocks from nvidia-smi -q -d CLOCK,PERFORMANCE (clocks.txt), where the run has it."""
    path = os.path.join(run_dir, "clocks.txt")
    if not os.path.exists(path):
        return "clock state not recorded (no nvidia-smi output in the run)"
    text = open(path).read()
    state = re.search(r"Performance State\s*:\s*(\S+)", text)
    section = {}
    for name in ("Clocks", "Max Clocks"):
        m = re.search(rf"^\s*{name}\s*$(.*?)(?=^\s*\S[^:]*$|\Z)", text, re.M | re.S)
        if m:
            section[name] = dict(re.findall(r"^\s*(Graphics|SM|Memory)\s*:\s*(\d+ MHz)", m.group(1), re.M))
    now, top = section.get("Clocks", {}), section.get("Max Clocks", {})
    parts = [f"{k} {now[k]}" + (f" of {top[k]}" if k in top else "") for k in ("Graphics", "SM", "Memory") if k in now]
    return (f"performance state {state.group(1) if state else 'unknown'}"
            + (", clocks after the runs: " + ", ".join(parts) if parts else ""))


def steps(run_dir):
    path = os.path.join(run_dir, "steps.txt")
    if not os.path.exists(path):
        return None
    pairs = [line.split() for line in open(path) if line.strip()]
    return sum(int(t) for _, t in pairs), ", ".join(f"{n} {t} s" for n, t in pairs)


def made_at(run_dir):
    """The commit the runs were made at: commit.txt, which gpu_runs.sh writes; for runs older than that file, the
    last commit that changed the run folder in this repository (the runs were made by the tree just before it)."""
    path = os.path.join(run_dir, "commit.txt")
    if os.path.exists(path):
        return "commit " + open(path).read().strip()
    added = subprocess.run(["git", "-C", ROOT, "log", "-1", "--format=%h", "--", run_dir],
                           capture_output=True, text=True).stdout.split()
    return f"the tree before commit {added[0]}" if added else "an unknown commit"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--doc", default=ev.DOC, help="the document whose GPU blocks are replaced (docs/results.md)")
    p.add_argument("run_dir", help="the folder gpu_runs.sh wrote")
    a = p.parse_args(argv)
    run_dir = a.run_dir
    if not os.path.isdir(run_dir):
        sys.exit(f"gpu_report.py: {run_dir}: no such folder (the one gpu_runs.sh wrote)")
    info = open(os.path.join(run_dir, "glinfo.txt")).read()
    renderer = re.search(r"renderer:\s*(.*)", info).group(1).strip()
    version = re.search(r"version:\s*(.*)", info).group(1).strip()
    sizes = sorted({re.match(r"demo-(.*)", os.path.basename(p)).group(1)
                    for p in glob.glob(os.path.join(run_dir, "demo-*")) if os.path.isdir(p)}, key=size_key)
    # The renderer's own choice of clock (--timing auto) decides whether these are a GPU's times.
    auto_clock = clock_of([r for path in csvs(os.path.join(run_dir, "eval-*-run*.csv"))
                           for r in read_csv(path)])
    hardware = auto_clock == "gpu"
    why_not = f"the runs' automatic clock (--timing auto on {renderer}) is {auto_clock}, not GPU timestamps"
    text = open(a.doc).read()
    rel = os.path.relpath(os.path.abspath(run_dir), ROOT)
    made = made_at(run_dir)
    note = f"_Regenerated by `/usr/bin/python3 scripts/eval/gpu_report.py {rel}` from the runs of {made}._\n\n"
    took = steps(run_dir)
    context = (f"GPU: **{renderer}**, OpenGL {version}, through EGL (device platform); {clock_state(run_dir)}; raw "
               f"output in `{rel}/`, made by `bash scripts/eval/gpu_runs.sh` at {made}"
               + (f", in {took[0]} s ({took[1]})." if took else "."))
    cost = load_cost(run_dir)
    blocks = [("gpu-context", context),
              ("gpu-teaser", note + "\n\n".join(teaser(run_dir, s) for s in sizes)),
              ("gpu-scaling", note + scaling(run_dir)),
              ("gpu-cost", note + cost_block(cost, rel)),
              ("gpu-equal-time", note + equal_time_block(run_dir, rel)),
              ("gpu-targets", note + targets_block(targets(cost, hardware, why_not)))]
    for name, body in blocks:
        text = docs.replace_block(text, name, body, a.doc, "gpu_report.py")
    docs.write_atomically(a.doc, text)
    print(f"gpu_report.py: wrote the GPU blocks of {a.doc}")


if __name__ == "__main__":
    main()
