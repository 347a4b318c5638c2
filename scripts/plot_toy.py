#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Draws supp. Fig. 1 (b-i) and Fig. 2 of Xie & Olano 2021 from emcv-toy's per-frame CSV files.

usage: /usr/bin/python3 scripts/plot_toy.py CSV_DIR OUT_DIR
  CSV_DIR holds static.csv and dynamic.csv written by `build/bin/emcv-toy --csv CSV_DIR`;
  OUT_DIR receives fig1_toy.png and fig2_inframe.png.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

KEYS = ["f", "SF", "SF_EMA", "EMCM", "EMCM_hat", "GT"]
LABELS = {"f": "Res_f", "SF": "Res_SF", "SF_EMA": "Res_SF+EMA", "EMCM": "Res_EMCM", "EMCM_hat": "ResHat_EMCM",
          "GT": "Res_GT"}
COLOURS = {"f": "tab:gray", "SF": "tab:orange", "SF_EMA": "tab:olive", "EMCM": "tab:blue", "EMCM_hat": "tab:red",
           "GT": "black"}


def read_columns(path):
    try:
        with open(path, newline="") as handle:
            rows = list(csv.DictReader(handle))
    except OSError as error:
        sys.exit(f"plot_toy.py: cannot read {path}: {error.strerror}")
    if not rows:
        sys.exit(f"plot_toy.py: {path} has no rows")
    return {name: [float(row[name]) for row in rows] for name in rows[0]}


def scenario_row(axes, data, title, letters):
    frame = data["frame"]
    ax = axes[0]
    ax.plot(frame, data["fbar"], label="fbar (frame mean of f)")
    ax.plot(frame, data["gbar"], label="gbar (frame mean of g)")
    ax.plot(frame, data["G"], "--", label="G(t) = E[g]")
    ax.set_title(f"({letters[0]}) {title}: frame means")
    ax.legend(fontsize=7)

    ax = axes[1]
    for key in ["SF", "SF_EMA", "EMCM", "GT"]:
        label = "alpha_EMCM (Res_EMCM, ResHat_EMCM)" if key == "EMCM" else "alpha " + LABELS[key]
        ax.plot(frame, data["alpha_" + key], color=COLOURS[key], label=label)
    ax.set_title(f"({letters[1]}) {title}: alpha used in frame t")
    ax.set_ylim(-0.5, 2.5)
    ax.legend(fontsize=7)

    ax = axes[2]
    for key in KEYS:
        ax.plot(frame, data["residual_" + key], color=COLOURS[key], label=LABELS[key], lw=1)
    ax.set_title(f"({letters[2]}) {title}: residuals")
    ax.legend(fontsize=7)

    ax = axes[3]
    for key in KEYS:
        ax.plot(frame, data["remse_" + key], color=COLOURS[key], label=LABELS[key], lw=1)
    ax.axvspan(25, frame[-1], color="0.92", zorder=0)
    ax.set_yscale("log")
    ax.set_title(f"({letters[3]}) {title}: ReMSE (shaded: frames 25..100)")
    ax.legend(fontsize=7)
    for ax in axes:
        ax.set_xlabel("frame")


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    csv_dir, out_dir = argv[1], argv[2]
    static = read_columns(os.path.join(csv_dir, "static.csv"))
    dynamic = read_columns(os.path.join(csv_dir, "dynamic.csv"))
    os.makedirs(out_dir, exist_ok=True)

    fig, axes = plt.subplots(2, 4, figsize=(18, 8))
    scenario_row(axes[0], static, "static h1 = 1", "bcde")
    scenario_row(axes[1], dynamic, "dynamic h2", "fghi")
    fig.suptitle("Toy experiment, one run (emcv-toy --seed), static h1 = 1 (top) and dynamic "
                 "h2 = 1 + 3 sin(t/10) (bottom), cf. supp. Fig. 1 (b-i)")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "fig1_toy.png"), dpi=60)
    plt.close(fig)

    frame = dynamic["frame"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    ax = axes[0]
    ax.plot(frame, dynamic["inframe_alpha_emcm"], label="EMCM (Eq. 21)", lw=2)
    ax.plot(frame, dynamic["inframe_alpha_ewma"], "--", label="EWMA (Eq. 22)")
    ax.axhline(2 * math.log(2), color="black", lw=0.8, label="2 ln 2 = 1.386")
    ax.set_ylim(0.5, 2.0)
    ax.set_title("in-frame constant control TG = E(G) T: alpha")
    ax.legend(fontsize=8)
    ax = axes[1]
    ax.plot(frame, dynamic["inframe_var_emcm"], color="tab:blue", label="Var(G), EMCM")
    ax.plot(frame, dynamic["inframe_var_ewma"], "--", color="tab:blue", label="Var(G), EWMA")
    ax.plot(frame, dynamic["inframe_cov_emcm"], color="tab:red", label="Cov(fbar, G), EMCM")
    ax.plot(frame, dynamic["inframe_cov_ewma"], "--", color="tab:red", label="Cov(fbar, G), EWMA")
    ax.set_title("EMCM vs EWMA: EWMA = EMCM / (1 - eta)")
    ax.legend(fontsize=8)
    ax = axes[2]
    ax.plot(frame, dynamic["residual_f"], color=COLOURS["f"], label="fbar (Res_f)")
    ax.plot(frame, dynamic["inframe_residual"], color=COLOURS["EMCM_hat"], label="fbar - alpha G (in-frame constant)")
    ax.set_title("residual with the in-frame constant control")
    ax.legend(fontsize=8)
    for ax in axes:
        ax.set_xlabel("frame")
    fig.suptitle("cf. supp. Fig. 2 (dynamic light, one run)")
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "fig2_inframe.png"), dpi=60)
    plt.close(fig)


if __name__ == "__main__":
    main(sys.argv)
