#!/usr/bin/python3
"""scripts/eval/run_eval.py's equal-time column (each adaptive method's PSNR gap to the burley runs interpolated in
log SSS time at its own SSS time), on data made up here (no renderer):
  - the pareto-time table's two new cells, raw and resolved, worked by hand in the comments;
  - "beyond range" past the slowest burley run and "below range" under the fastest, not an extrapolation;
  - "-" for the methods that are not adaptive;
  - the Pareto plot's SSS-ms panel labels each adaptive point with the same gap where there is one;
  - the worth table: the burley-N of equal PSNR (log N linear in dB between the burley runs that bracket it) and
    the burley-N of equal SSS time (N linear in ms), and the burley-N of 1 dB under (lead_db), worked by hand;
    outside the runs "> N" or "< N";
  - the time axis (cost_ms): the median over rounds of each round's mean over frames MEAN_FROM.., worked by hand.

    /usr/bin/python3 tests/eval/test_run_eval_equal_time.py
"""
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from script_checks import check, finish  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts", "eval"))
import run_eval  # noqa: E402

# The method table's adaptive rows as emcv-demo --list-methods prints them (run_eval takes its lists from there).
run_eval.use_methods("burley-16\tburley\t...\nspvg\tadaptive\t...\ncv\tadaptive\t...\ncv-notex\tadaptive\t...\n")
SCENE = "static"
# (group, method) -> (SSS ms, raw dB, resolved dB), the same every frame from MEAN_FROM on.
POINTS = {
    ("B8", "burley-8"): (2.0, 40.0, 50.0),
    ("B32", "burley-32"): (8.0, 46.0, 53.0),
    ("B4", "burley-4"): (1.0, 37.0, 47.0),
    ("B8", "cv"): (3.0, 44.0, 52.0),        # between burley-8 and burley-32
    ("B8", "spvg"): (20.0, 49.0, 56.0),     # slower than burley-32, the slowest
    ("B4", "cv-notex"): (0.5, 30.0, 40.0),  # faster than burley-4, the fastest
    ("B32", "cv"): (8.0, 45.5, 54.0),       # at burley-32's own time
    ("fixed", "separable-17"): (4.0, 45.0, 45.0),
}


def made_up_data():
    """A run_eval.Data with POINTS as its quality series (frames MEAN_FROM..MEAN_FROM+9), and the cost stage's ms."""
    d = object.__new__(run_eval.Data)
    d.jobs, d.raw_dir, d.lights, d.seeds = [], None, {}, {}
    d.scenes, d.groups = [SCENE], ["fixed", "B4", "B8", "B32"]
    d.series, ms = {}, {}
    for (group, method), (t, raw, resolved) in POINTS.items():
        frame = {c: math.nan for c in run_eval.DEMO_COLUMNS[2:]}
        frame.update(psnr_db=raw, psnr_resolved_db=resolved, mean_spp=8.0)
        d.series[("quality", SCENE, group, method)] = {f: dict(frame) for f in range(run_eval.MEAN_FROM,
                                                                                     run_eval.MEAN_FROM + 10)}
        ms[(SCENE, group, method)] = t
    return d, ms


def table_cells(table):
    """(method, B) -> the row's cells."""
    rows = {}
    for line in table.splitlines()[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        rows[(cells[1], cells[2])] = cells
    return rows


def main():
    d, ms = made_up_data()
    table = run_eval.pareto_time_table(d, ms)
    header = table.splitlines()[0]
    check("dB vs burley at equal time, raw" in header and header.rstrip().endswith("resolved |"),
          f"the pareto-time table has the equal-time columns (header: {header})")
    rows = table_cells(table)
    # cv at 3 ms lies between burley-8 (t1 = 2 ms, p1 = 40 dB) and burley-32 (t2 = 8 ms, p2 = 46 dB):
    #   p(3) = p1 + (p2 - p1) ln(t / t1) / ln(t2 / t1) = 40 + 6 ln(1.5) / ln(4) = 40 + 6 x 0.292481 = 41.754888,
    #   cv's gap 44 - 41.754888 = +2.25 dB (linear in time: 41.0, +3.00; t1 and t2 swapped: 44.245, -0.25).
    # Resolved: 50 + 3 x 0.292481 = 50.877444, cv 52: +1.12 dB.
    check(rows[("cv", "8")][5:7] == ["+2.25", "+1.12"], f"cv at B = 8: +2.25 raw, +1.12 resolved (got {rows[('cv', '8')]})")
    # cv at B = 32 takes burley-32's own 8 ms: 45.5 - 46 = -0.50, 54 - 53 = +1.00.
    check(rows[("cv", "32")][5:7] == ["-0.50", "+1.00"], f"cv at B = 32: -0.50, +1.00 (got {rows[('cv', '32')]})")
    check(rows[("spvg", "8")][5:7] == ["beyond range", "beyond range"],
          f"spvg, slower than burley-32: beyond range (got {rows[('spvg', '8')]})")
    check(rows[("cv-notex", "4")][5:7] == ["below range", "below range"],
          f"cv-notex, faster than burley-4: below range (got {rows[('cv-notex', '4')]})")
    for key in (("burley-8", "8"), ("separable-17", "-")):
        check(rows[key][5:7] == ["-", "-"], f"{key[0]} is not adaptive: no equal-time cells (got {rows[key]})")
    check(run_eval.equal_time_gap([], 3.0, 44.0) == (None, "n/a"), "no burley curve: n/a")

    worth = {}
    for line in run_eval.worth_table(d, ms, run_eval.ADAPTIVE).splitlines()[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        worth[(cells[2], cells[1])] = cells[3:]
    # cv at B = 8, raw 44 dB between burley-8 (40) and burley-32 (46): ln N = ln 8 + (4 / 6) ln 4, N = 8 x 4^(2/3)
    # = 20.16 (linear in N instead: 24.0; the runs swapped: 8 x 4^(1/3) = 12.7); resolved 52 between 50 and 53: the
    # same 2/3, 20.16. Its 3 ms between burley-8's 2 ms and burley-32's 8 ms: N = 8 + 24 (1 / 6) = 12.0.
    check(worth.get(("cv", "8")) == ["20.2", "20.2", "12.0"], f"cv at B = 8 is worth burley-20.2 and buys burley-12.0 "
          f"(got {worth.get(('cv', '8'))})")
    # cv at B = 32: raw 45.5, N = 8 x 4^(5.5 / 6) = 28.51; resolved 54 over burley-32's 53: "> 32"; its 8 ms is
    # burley-32's own: 32.0.
    check(worth.get(("cv", "32")) == ["28.5", "> 32", "32.0"], f"cv at B = 32 (got {worth.get(('cv', '32'))})")
    check(worth.get(("spvg", "8")) == ["> 32", "> 32", "> 32"], f"spvg past every run (got {worth.get(('spvg', '8'))})")
    check(worth.get(("cv-notex", "4")) == ["< 4", "< 4", "< 4"],
          f"cv-notex under every run (got {worth.get(('cv-notex', '4'))})")
    check(("burley-8", "8") not in worth and ("separable-17", "-") not in worth, "only the adaptive methods have rows")
    # With lead_db = 1 a column more after the raw worth: cv at B = 8, 44 - 1 = 43 dB, halfway between burley-8 (40)
    # and burley-32 (46): N = 8 x 4^(1/2) = 16.0, the N its pass must cost less than to lead by 1 dB at equal time.
    lead = run_eval.worth_table(d, ms, ["cv"], lead_db=1.0).splitlines()
    check("raw, 1 dB under" in lead[0], f"the lead column is named (header: {lead[0]})")
    row = next((line for line in lead[2:] if "| cv | " in line and "| 8 |" in line), "")
    check([c.strip() for c in row.strip("|").split("|")][3:] == ["20.2", "16.0", "20.2", "12.0"],
          f"cv at B = 8 with the 1 dB column: 20.2, 16.0, 20.2, 12.0 (got {row})")

    # The time axis (cost_ms): per round the mean over frames MEAN_FROM.. (a budget's update frame costs more than
    # the frames that reuse its plan), then the median over rounds. Round 1: frames 0-19 at 100 ms (left out),
    # frames 20-27 at 1 ms and 28-29 at 9 ms: mean (8 + 18) / 10 = 2.6 (the median would be 1.0, frames from 0
    # on 70.78). Rounds 2 and 3 at 2.0 and 5.0 every frame: the median of 2.6, 2.0, 5.0 is 2.6.
    with tempfile.TemporaryDirectory() as raw:
        cost = object.__new__(run_eval.Data)
        cost.raw_dir, cost.jobs = raw, []
        os.makedirs(os.path.join(raw, "cost"))
        for r, times in enumerate(([100.0] * 20 + [1.0] * 8 + [9.0] * 2, [2.0] * 30, [5.0] * 30)):
            job = run_eval.Job("cost", f"static-B8-r{r + 1}", "emcv-eval", [], meta={"scene": SCENE, "group": "B8"})
            with open(job.raw(raw), "w") as f:
                f.write("method,frame,sss_ms\n" + "".join(f"cv,{i},{t}\n" for i, t in enumerate(times)))
            cost.jobs.append(job)
        got = run_eval.cost_ms(cost).get((SCENE, "B8", "cv"))
        check(got is not None and abs(got - 2.6) < 1e-9, f"cost_ms: the median over rounds of the mean over frames "
              f"{run_eval.MEAN_FROM}.. is 2.6 (got {got})")

    # The plot's SSS-ms panel: the adaptive points' labels carry the same words (matplotlib's Agg backend).
    labels = []
    plt = run_eval.plt_module()
    original = plt.Axes.annotate

    def record(ax, text, *args, **kwargs):
        labels.append(text)
        return original(ax, text, *args, **kwargs)

    plt.Axes.annotate = record
    try:
        with tempfile.TemporaryDirectory() as out:
            run_eval.plot_pareto(d, ms, out, "made-up device")
            check(os.path.exists(os.path.join(out, f"pareto-{SCENE}.png")), "the Pareto plot is written")
    finally:
        plt.Axes.annotate = original
    for want in ("8: +2.25 dB", "8: +1.12 dB", "32: -0.50 dB"):
        check(want in labels, f"the plot labels an adaptive point '{want}' (labels: {labels})")
    # spvg and cv-notex, outside burley's times, keep their plain B: their place on the time axis says it.
    check(not any("range" in label or label.startswith("4:") for label in labels),
          f"no gap on a point outside burley's times (labels: {labels})")
    return finish("eval.run_eval_equal_time")


if __name__ == "__main__":
    sys.exit(main())
