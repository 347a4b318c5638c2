#!/usr/bin/python3
# Reads emcv-demo's metrics.csv (and emcv-light-curves' lights.csv) per scene under WORK, writes a plot per scene
# into OUT (mean N per frame, SSS ms per frame and PSNR per frame for spvg, cv, cv-notex, the light curves
# underneath) and prints the Markdown table: per scene, over the frames from FIRST on, mean N, SSS ms, PSNR
# and the ratios of cv and cv-notex against spvg. Run through tools/cvstudy/adaptive_report.sh.
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METHODS = ["spvg", "cv", "cv-notex"]


def read_metrics(path):
    rows = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            rows.setdefault(r["method"], []).append(r)
    return rows


def column(rows, key):
    out = []
    for r in rows:
        v = r[key]
        out.append(float(v) if v not in ("", "inf", "nan") else math.nan)
    return out


def mean(values):
    finite = [v for v in values if not math.isnan(v)]
    return sum(finite) / len(finite) if finite else math.nan


def main():
    if len(sys.argv) < 5:
        sys.stderr.write("usage: adaptive_report.py WORK OUT SIZE SCENE:FIRST_FRAME...\n")
        sys.exit(2)
    work, out, size = sys.argv[1], sys.argv[2], sys.argv[3]
    print(f"| scene ({size}), frames | method | mean N | SSS ms | PSNR dB | N / spvg's | SSS ms / spvg's | PSNR - spvg's dB |")
    print("|---|---|---|---|---|---|---|---|")
    for spec in sys.argv[4:]:
        name, first = spec.split(":")
        first = int(first)
        metrics = read_metrics(os.path.join(work, name, "metrics.csv"))
        lights = {}
        with open(os.path.join(work, name, "lights.csv"), newline="") as f:
            for r in csv.DictReader(f):
                lights.setdefault(r["light"], []).append(float(r["intensity"]))
        frames = len(metrics["spvg"])
        summary = {}
        for m in METHODS:
            rows = metrics[m][first:]
            summary[m] = (mean(column(rows, "mean_spp")), mean(column(rows, "sss_ms")), mean(column(rows, "psnr_db")))
        for m in METHODS:
            n, ms, db = summary[m]
            n0, ms0, db0 = summary["spvg"]
            print(f"| {name}, {first}-{frames - 1} | {m} | {n:.2f} | {ms:.2f} | {db:.2f} | {n / n0:.3f} | "
                  f"{ms / ms0:.3f} | {db - db0:+.2f} |")

        fig, axes = plt.subplots(4, 1, figsize=(7, 8.5), sharex=True)
        for m in METHODS:
            x = column(metrics[m], "frame")
            axes[0].plot(x, column(metrics[m], "mean_spp"), label=m)
            axes[1].plot(x, column(metrics[m], "sss_ms"), label=m)
            axes[2].plot(x, column(metrics[m], "psnr_db"), label=m)
        for light, values in lights.items():
            axes[3].plot(range(len(values)), values, label=light)
        axes[0].set_ylabel("mean N")
        axes[1].set_ylabel("SSS ms")
        axes[2].set_ylabel("PSNR dB")
        axes[3].set_ylabel("light intensity")
        axes[3].set_xlabel("frame")
        for ax in axes:
            ax.axvline(first, color="grey", lw=0.5, ls=":")
            ax.legend(fontsize=7, loc="upper right")
        axes[0].set_title(f"{name} at {size} (llvmpipe): spvg, cv, cv-notex")
        fig.tight_layout()
        tmp = os.path.join(out, f".{name}.png.tmp.png")
        fig.savefig(tmp, dpi=80)
        plt.close(fig)
        os.replace(tmp, os.path.join(out, f"{name}.png"))


if __name__ == "__main__":
    main()
