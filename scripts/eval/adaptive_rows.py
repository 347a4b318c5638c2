#!/usr/bin/python3
"""The rows of scripts/eval/adaptive_tables.sh for one emcv-demo run (its metrics.csv and its summary beside it).

Usage: adaptive_rows.py budget RUN_DIR SCENE B
       adaptive_rows.py quality RUN_DIR SCENE
"""
import collections
import csv
import re
import sys


def load(run_dir):
    """Rows per method, and the first light change emcv-demo's summary names (None without one)."""
    found = re.search(r"from the first light change at frame (\d+)", open(run_dir + ".summary").read())
    by = collections.defaultdict(list)
    for r in csv.DictReader(open(run_dir + "/metrics.csv")):
        by[r["method"]].append(r)
    return by, int(found.group(1)) if found else None


def mean(values):
    values = [v for v in values if v != float("inf")]
    return f"{sum(values) / len(values):.2f}" if values else "-"


def budget_rows(run_dir, scene, budget):
    by, change = load(run_dir)
    for method, rs in by.items():
        if method == "reference":  # the comparison's ground truth, not a row
            continue
        db = [float(r["psnr_db"]) for r in rs]
        spp = [float(r["mean_spp"]) for r in rs]
        before = mean(db[2:change] if change is not None else db[2:])
        after = mean(db[change:change + 30]) if change is not None else "-"
        later = mean(db[change + 30:]) if change is not None else "-"
        deviation = max(abs(s - budget) / budget for s in spp[2:])
        ms = sorted(float(r["sss_ms"]) for r in rs[2:])
        steady = ms[int(0.95 * (len(ms) - 1))] / ms[len(ms) // 2] if ms and ms[len(ms) // 2] > 0 else float("nan")
        print(f"| {scene} | {budget:g} | {method} | {before} | {after} | {later} | {mean(db[2:])} | "
              f"{sum(spp) / len(spp):.2f} | {100 * deviation:.2f}% | {steady:.2f} |")


def quality_rows(run_dir, scene):
    by, change = load(run_dir)
    if change is None:
        sys.exit(f"adaptive_rows.py: {scene} has no light change")

    def window(method, last):
        rs = by[method][change:last]
        return sum(float(r["mean_spp"]) for r in rs) / len(rs), sum(float(r["psnr_db"]) for r in rs) / len(rs)

    end = len(by["spvg"])
    for method in ("spvg", "cv", "cv-notex"):
        n30, db30 = window(method, change + 30)
        nall, dball = window(method, end)
        s30, sall = window("spvg", change + 30)[0], window("spvg", end)[0]
        print(f"| {scene} | {method} | {n30:.2f} | {n30 / s30:.2f} | {db30:.2f} | {nall:.2f} | {nall / sall:.2f} | "
              f"{dball:.2f} |")


def main(argv):
    if len(argv) == 5 and argv[1] == "budget":
        budget_rows(argv[2], argv[3], float(argv[4]))
    elif len(argv) == 4 and argv[1] == "quality":
        quality_rows(argv[2], argv[3])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
