#!/usr/bin/python3
"""Turns the GPU runs of scripts/eval/gpu_runs.sh into the generated blocks of docs/results.md, section "GPU":
    /usr/bin/python3 scripts/eval/gpu_report.py docs/results/gpu
The run directory holds glinfo.txt, demo-<size>/metrics.csv (PSNR per frame against the converged reference),
eval-<size>-run<k>.csv (SSS pass ms per frame, three runs) and scaling-<size>.csv. Writes docs/results.md
atomically (the blocks gpu-context, gpu-teaser, gpu-scaling)."""
import glob
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run_eval as ev  # noqa: E402  (the same median / table helpers as the llvmpipe evaluation)

TEASER = ["diffuse", "separable-17", "burley-16", "spvg", "cv", "cv-notex"]
PAPER_LABEL = {"separable-17": "separable", "spvg": "spvg", "cv": "cv"}
SCALING = ["burley-16", "separable-17", "spvg", "cv", "cv-notex"]


def size_key(size):
    w, h = (int(v) for v in size.split("x"))
    return w * h


def teaser(run_dir, size):
    first, last = ev.SWITCH_FRAME, ev.SWITCH_FRAME + 29
    quality = [r for r in ev.read_csv(os.path.join(run_dir, f"demo-{size}", "metrics.csv"))
               if first <= int(r["frame"]) <= last]
    cost = []
    for path in sorted(glob.glob(os.path.join(run_dir, f"eval-{size}-run*.csv"))):
        cost += [r for r in ev.read_csv(path) if first <= int(r["frame"]) <= last]
    rows = {}
    for m in TEASER:
        q = [r for r in quality if r["method"] == m]
        c = [r for r in cost if r["method"] == m]
        rows[m] = {"ms": ev.median([ev.to_float(r["sss_ms"]) for r in c]),
                   "spp": ev.mean_finite([ev.to_float(r["mean_spp"]) for r in c]),
                   "db": ev.mean_finite([ev.to_float(r["psnr_db"]) for r in q]),
                   "frames": len(q), "runs": len(c) // max(len(q), 1)}
    spvg = rows["spvg"]
    lines = [f"**{size}**, light-off frames {first}-{last} (the 30 frames from the switch); SSS ms: median over "
             f"the frames of {rows['spvg']['runs']} emcv-eval runs; PSNR: mean over the frames of the emcv-demo run.",
             "",
             "| method | SSS pass ms | x spvg | mean spp | x spvg | PSNR dB | dB vs spvg | paper ms | paper x spvg "
             "| paper dB vs spvg |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for m in TEASER:
        r = rows[m]
        label = PAPER_LABEL.get(m)
        pm, pdb = ev.PAPER.get(label, (None, None)) if label else (None, None)
        paper_ratio = ev.fmt(pm / ev.PAPER["spvg"][0]) if pm else "-"
        paper_db = ev.fmt(pdb - ev.PAPER["spvg"][1], 1) if pdb else "-"
        ms_ratio = r["ms"] / spvg["ms"] if spvg["ms"] else float("nan")
        spp_ratio = r["spp"] / spvg["spp"] if spvg["spp"] else float("nan")
        lines.append(f"| {m} | {ev.fmt(r['ms'])} | {ev.fmt(ms_ratio)} | {ev.fmt(r['spp'], 1)} | "
                     f"{ev.fmt(spp_ratio)} | {ev.fmt(r['db'])} | {ev.fmt(r['db'] - spvg['db'])} | "
                     f"{ev.fmt(pm, 1) if pm else '-'} | {paper_ratio} | {paper_db} |")
    return "\n".join(lines)


def scaling(run_dir):
    groups = {}
    for path in glob.glob(os.path.join(run_dir, "scaling-*.csv")):
        for r in ev.read_csv(path):
            if int(r["frame"]) < 1:  # frame 0 compiles and warms up
                continue
            groups.setdefault(r["method"], {}).setdefault(f"{r['width']}x{r['height']}", []).append(r)
    methods = [m for m in SCALING if m in groups]
    sizes = sorted({s for g in groups.values() for s in g}, key=size_key)
    lines = ["| size | SSS pixels | " + " | ".join(f"{m} ms" for m in methods) + " | " +
             " | ".join(f"{m} ns/SSS px" for m in methods) + " |",
             "|---|---:|" + "---:|" * (2 * len(methods))]
    for s in sizes:
        sss = int(next(groups[m][s] for m in methods if s in groups[m])[0]["sss_pixels"])
        ms = [ev.median([ev.to_float(r["sss_ms"]) for r in groups[m].get(s, [])]) for m in methods]
        lines.append(f"| {s} | {sss} | " + " | ".join(ev.fmt(x) for x in ms) + " | " +
                     " | ".join(ev.fmt(1e6 * x / max(sss, 1), 2) for x in ms) + " |")
    return "\n".join(lines)


def made_at(run_dir):
    """The commit the runs were made at: commit.txt, which gpu_runs.sh writes; for runs older than that file, the
    last commit that changed the run folder in this repository (the runs were made by the tree just before it)."""
    path = os.path.join(run_dir, "commit.txt")
    if os.path.exists(path):
        return "commit " + open(path).read().strip()
    added = subprocess.run(["git", "-C", ev.ROOT, "log", "-1", "--format=%h", "--", run_dir],
                           capture_output=True, text=True).stdout.split()
    return f"the tree before commit {added[0]}" if added else "an unknown commit"


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit("usage: gpu_report.py RUN_DIR (the folder gpu_runs.sh wrote)")
    run_dir = sys.argv[1]
    info = open(os.path.join(run_dir, "glinfo.txt")).read()
    renderer = re.search(r"renderer:\s*(.*)", info).group(1).strip()
    version = re.search(r"version:\s*(.*)", info).group(1).strip()
    sizes = sorted({re.match(r"demo-(.*)", os.path.basename(p)).group(1)
                    for p in glob.glob(os.path.join(run_dir, "demo-*")) if os.path.isdir(p)}, key=size_key)
    text = open(ev.DOC).read()
    rel = os.path.relpath(run_dir, ev.ROOT)
    made = made_at(run_dir)
    note = f"_Regenerated by `/usr/bin/python3 scripts/eval/gpu_report.py {rel}` from the runs of {made}._\n\n"
    text = ev.replace_block(text, "gpu-context", f"GPU: **{renderer}**, OpenGL {version}, through EGL (device "
                            f"platform); raw output in `{rel}/`, made by `bash scripts/eval/gpu_runs.sh` at {made}.")
    text = ev.replace_block(text, "gpu-teaser", note + "\n\n".join(teaser(run_dir, s) for s in sizes))
    text = ev.replace_block(text, "gpu-scaling", note + scaling(run_dir))
    ev.write_atomically(ev.DOC, text)
    print(f"gpu_report.py: wrote the GPU blocks of {ev.DOC}")


if __name__ == "__main__":
    main()
