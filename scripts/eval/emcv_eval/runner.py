# SPDX-License-Identifier: MIT
"""The build's executables, running them, and reading what they write.

emcv-demo writes OUT/metrics.csv and OUT/metrics.json (and, without --no-frames, OUT/METHOD/frame-NNNN.png and
resolved-NNNN.png); emcv-eval prints a CSV (SSS ms and samples per method and frame) and with --heatmaps dumps
per-pixel counts under --heatmap-dir. The evaluation's raw files are CSVs whose first lines, starting with '#',
say how they were made.
"""
import csv
import gzip
import io
import json
import os
import subprocess
import sys

from . import ROOT

DEFAULT_BUILD = os.path.join(ROOT, "build")


def tool_path(build, tool):
    """BUILD/bin/TOOL."""
    return os.path.join(build, "bin", tool)


def find_tool(build, tool, prog):
    """BUILD/bin/TOOL when it is an executable; otherwise exits "PROG: no PATH (build first)"."""
    path = tool_path(build, tool)
    if not os.access(path, os.X_OK):
        sys.exit(f"{prog}: no {path} (build first)")
    return path


def command(exe, scene=None, methods=None, size=None, frames=None, seed=None, budget=None, defines=(), extra=()):
    """An emcv-demo or emcv-eval command line: EXE, then the flags given (--scene, --method a,b, --size WxH,
    --frames N, --seed S, --spp-budget B, one --define NAME=VALUE per tunable) and `extra` as it is."""
    cmd = [exe]
    for flag, value in (("--scene", scene), ("--method", ",".join(methods) if methods else None), ("--size", size),
                        ("--frames", frames), ("--seed", seed), ("--spp-budget", budget)):
        if value is not None:
            cmd += [flag, str(value)]
    for d in defines:
        cmd += ["--define", d]
    return cmd + list(extra)


def run(cmd, prog, **kwargs):
    """Runs `cmd` capturing its output; exits "PROG: CMD failed:\\nSTDERR" when it fails. The finished process."""
    done = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
    if done.returncode != 0:
        sys.exit(f"{prog}: {' '.join(cmd)} failed:\n{done.stderr}")
    return done


def read_csv_text(text):
    """The rows (dicts) of a CSV's text, its '#' comment lines left out."""
    return list(csv.DictReader(io.StringIO("\n".join(l for l in text.splitlines() if not l.startswith("#")))))


def read_csv(path):
    """The rows of a CSV file, its '#' comment lines left out; PATH.gz (gzip) where only that exists."""
    if not os.path.exists(path) and os.path.exists(path + ".gz"):
        with gzip.open(path + ".gz", "rt") as f:
            return read_csv_text(f.read())
    with open(path) as f:
        return read_csv_text(f.read())


def csv_header(path):
    """The '# key: value' lines at the top of a raw file, as a dict."""
    out = {}
    with open(path) as f:
        for line in f:
            if not line.startswith("# "):
                break
            k, _, v = line[2:].rstrip("\n").partition(": ")
            out[k] = v
    return out


def metrics_csv(out):
    """emcv-demo's OUT/metrics.csv: one dict per method and frame."""
    with open(os.path.join(out, "metrics.csv")) as f:
        return list(csv.DictReader(f))


def metrics_json(out):
    """emcv-demo's OUT/metrics.json rows (numbers as numbers, a PSNR without error as None, per-pass times)."""
    with open(os.path.join(out, "metrics.json")) as f:
        return json.load(f)["rows"]


def by_method_frame(rows):
    """Rows keyed by (method, frame)."""
    return {(r["method"], int(r["frame"])): r for r in rows}


def run_demo(prog, cmd):
    """Runs emcv-demo (`cmd` ends with --out DIR) and returns its metrics.csv rows keyed by (method, frame); a
    failed run exits with its stderr."""
    run(cmd, prog)
    return by_method_frame(metrics_csv(cmd[-1]))
