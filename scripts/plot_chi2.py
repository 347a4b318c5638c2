#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Plots the histogram of an emcv::testing chi-square test (after Mitsuba's chi2 tests, which show theirs).

usage: /usr/bin/python3 scripts/plot_chi2.py HISTOGRAM_CSV [OUT_PNG]
  HISTOGRAM_CSV is the file chi2_options::histogram_csv named (columns cell, kind, x_lo, x_hi, y_lo, y_hi,
  observed, expected, contribution, pooled; docs/testing.md); OUT_PNG defaults to the CSV's name with .png.
  A 1-D test (chi2_test_1d_cdf, chi2_test_1d_pdf) gives observed and expected counts per bin and each bin's
  signed deviation (O - E) / sqrt(E); a 2-D test (chi2_test_2d_pdf) gives the observed and expected grids and
  the deviation grid; a caller's histogram (chi2_test) gives the counts per cell index. The cell outside the
  binned region is reported in the title, not drawn.
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def number(text):
    return float(text) if text != "" else None


def read_cells(path):
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    if not rows:
        raise SystemExit(f"plot_chi2: {path} has no cells")
    for row in rows:
        for key in ("x_lo", "x_hi", "y_lo", "y_hi", "observed", "expected", "contribution"):
            row[key] = number(row[key])
    return rows


def deviation(row):
    e = row["expected"]
    return (row["observed"] - e) / math.sqrt(e) if e > 0 else 0.0


def plot_1d(axes, bins):
    # infinite end bins (chi2_test_1d_cdf) are drawn one neighbouring width wide
    edges = []
    for k, row in enumerate(bins):
        lo, hi = row["x_lo"], row["x_hi"]
        if math.isinf(lo):
            lo = hi - (bins[k + 1]["x_hi"] - bins[k + 1]["x_lo"]) if len(bins) > 1 else hi - 1.0
        if math.isinf(hi):
            hi = lo + (edges[-1][1] - edges[-1][0] if edges else 1.0)
        edges.append((lo, hi))
    lefts = [lo for lo, _ in edges]
    widths = [hi - lo for lo, hi in edges]
    # counts per unit of x: bins of unequal width (equal probability) then read as densities
    observed = [r["observed"] / w for r, w in zip(bins, widths)]
    expected = [r["expected"] / w for r, w in zip(bins, widths)]
    axes[0].bar(lefts, observed, widths, align="edge", color="tab:blue", alpha=0.5, label="observed")
    axes[0].step(lefts + [edges[-1][1]], expected + [expected[-1]], where="post", color="black", label="expected")
    axes[0].set_ylabel("samples per unit x")
    axes[0].legend()
    axes[1].bar(lefts, [deviation(r) for r in bins], widths, align="edge", color="tab:red")
    axes[1].axhline(0.0, color="black", linewidth=0.5)
    axes[1].set_ylabel("(O - E) / sqrt(E)")
    axes[1].set_xlabel("x")


def plot_2d(figure, bins):
    xs = sorted({r["x_lo"] for r in bins})
    ys = sorted({r["y_lo"] for r in bins})
    extent = [xs[0], max(r["x_hi"] for r in bins), ys[0], max(r["y_hi"] for r in bins)]
    grids = {name: [[0.0] * len(xs) for _ in ys] for name in ("observed", "expected", "deviation")}
    for r in bins:
        i, j = xs.index(r["x_lo"]), ys.index(r["y_lo"])
        grids["observed"][j][i] = r["observed"]
        grids["expected"][j][i] = r["expected"]
        grids["deviation"][j][i] = deviation(r)
    for k, (name, colours) in enumerate((("observed", "viridis"), ("expected", "viridis"), ("deviation", "RdBu_r"))):
        axis = figure.add_subplot(1, 3, k + 1)
        image = axis.imshow(grids[name], origin="lower", extent=extent, cmap=colours, aspect="auto")
        axis.set_title(name if name != "deviation" else "(O - E) / sqrt(E)")
        figure.colorbar(image, ax=axis)


def main(argv):
    if len(argv) not in (2, 3):
        raise SystemExit(__doc__)
    source = argv[1]
    target = argv[2] if len(argv) == 3 else (source[:-4] if source.endswith(".csv") else source) + ".png"
    rows = read_cells(source)
    bins = [r for r in rows if r["kind"] == "bin"]
    outside = [r for r in rows if r["kind"] == "outside"]
    chi2 = sum(r["contribution"] for r in rows if r["contribution"] is not None)
    title = f"chi2 over the unpooled cells = {chi2:.4g}"
    if outside:
        title += f"; outside: observed {outside[0]['observed']:g}, expected {outside[0]['expected']:.4g}"
    if bins and bins[0]["y_lo"] is not None:
        figure = plt.figure(figsize=(15, 4.5))
        plot_2d(figure, bins)
    else:
        figure, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True, gridspec_kw={"height_ratios": [3, 1]})
        if bins:
            plot_1d(axes, bins)
        else:  # a caller's histogram: cells by index
            cells = [r["cell"] for r in rows]
            for axis, values, label in ((axes[0], [r["observed"] for r in rows], "observed"),
                                        (axes[1], [deviation(r) for r in rows], "(O - E) / sqrt(E)")):
                axis.bar(cells, values)
                axis.set_ylabel(label)
            axes[0].plot(cells, [r["expected"] for r in rows], "k_", markersize=12, label="expected")
            axes[0].legend()
    figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(target, dpi=100)
    print(f"wrote {target}: {len(bins) if bins else len(rows)} cells")


if __name__ == "__main__":
    main(sys.argv)
