#!/usr/bin/python3
"""scripts/eval/gpu_runs.sh, the one script a lent GPU machine runs, run whole here at 48x48 over 34 frames (--smoke) on the
built renderer, and its output turned into docs/results.md's GPU blocks (a copy) by scripts/eval/gpu_report.py:
  - every step runs and leaves its files (glinfo, the teaser's emcv-demo metrics and emcv-eval runs, the scaling
    runs, the five equal-samples runs with each run's CSV and settings, steps.txt with each step's seconds);
  - the report fills every GPU block from them: the teaser and cost tables at 48x48 with their clocks, and one row
    per target, each measured and, the renderer here choosing the wall clock, "not judged";
  - bad usage exits 2 and names the problem.
So a GPU session spends its device time on runs, not on a script that stopped at a renamed option.

    /usr/bin/python3 tests/eval/test_gpu_runs_smoke.py BUILD_DIR   (BUILD_DIR/bin holds emcv-glinfo, -demo, -eval)

Exit 77 (CTest's SKIP_RETURN_CODE here) when there is no OpenGL context, unless EMCV_REQUIRE_GL=1.
"""
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RUNS = os.path.join(ROOT, "scripts", "eval", "gpu_runs.sh")
REPORT = os.path.join(ROOT, "scripts", "eval", "gpu_report.py")
COST = ["cost-budget8-gpu", "cost-budget8-wall", "cost-budget16-gpu", "cost-budget16-wall", "cost-quality-gpu"]
STEPS = ["teaser-48x48", "scaling"] + COST + ["cost-blocks-gpu", "equal-time"]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from script_checks import check, finish, no_gl  # noqa: E402


def block(text, name):
    return text.split(f"<!-- BEGIN GENERATED: {name} -->")[1].split(f"<!-- END GENERATED: {name} -->")[0]


def main(build):
    bin_dir = os.path.join(os.path.abspath(build), "bin")
    for args, needle in (([], "usage"), (["--smoke"], "usage"), (["--smoke", "a", "b", "c"], "usage"),
                         (["--smoke", "OUT", "/nonexistent/bin"], "/nonexistent/bin/emcv-glinfo not found")):
        r = subprocess.run(["bash", RUNS, *args], capture_output=True, text=True)
        check(r.returncode == 2 and needle in r.stderr,
              f"gpu_runs.sh {' '.join(args)} exits 2 naming {needle!r} (got {r.returncode}: {r.stderr.strip()})")

    info = subprocess.run([os.path.join(bin_dir, "emcv-glinfo")], capture_output=True, text=True)
    if info.returncode != 0:
        return no_gl("emcv-glinfo: " + info.stderr.strip())

    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "runs")
        r = subprocess.run(["bash", RUNS, "--smoke", out, bin_dir], capture_output=True, text=True, cwd=tmp)
        check(r.returncode == 0, f"gpu_runs.sh --smoke runs (got {r.returncode}: {r.stderr.strip()[-1500:]})")
        expected = ["commit.txt", "glinfo.txt", "demo-48x48/metrics.csv", "eval-48x48-run1.csv", "scaling-32x32.csv",
                    "scaling-48x48.csv", "steps.txt"]
        expected += [f"{c}/{f}" for c in COST for f in ("settings.json", "build-run1.csv")] + [f"{c}.md" for c in COST]
        expected += ["cost-blocks-gpu.md", "cost-blocks-gpu/settings.json", "cost-blocks-gpu/K2-run1.csv",
                     "equal-time.txt", "equal-time/metrics.csv"]
        for f in expected:
            path = os.path.join(out, f)
            check(os.path.isfile(path) and os.path.getsize(path) > 0, f"gpu_runs.sh --smoke writes {f}")
        steps = [line.split()[0] for line in open(os.path.join(out, "steps.txt"))] if os.path.exists(
            os.path.join(out, "steps.txt")) else []
        check(steps == STEPS, f"steps.txt names every step in order (got {steps})")

        doc = os.path.join(tmp, "results.md")
        shutil.copy(os.path.join(ROOT, "docs", "results.md"), doc)
        r = subprocess.run(["/usr/bin/python3", REPORT, "--doc", doc, out], capture_output=True, text=True)
        check(r.returncode == 0, f"gpu_report.py reads the runs (got {r.returncode}: {r.stderr.strip()[-1500:]})")
        text = open(doc).read()
        check("**48x48**, light-off frames 30-59" in block(text, "gpu-teaser") and "| cv |" in block(text, "gpu-teaser") and
              "clock wall" in block(text, "gpu-teaser"), "the teaser block is the 48x48 run's, its clock named")
        cost = block(text, "gpu-cost")
        for setting in ("budget 8 spp, frames 2-33, 1 runs, clock gpu", "budget 8 spp, frames 2-33, 1 runs, clock wall",
                        "budget 16 spp, frames 2-33, 1 runs, clock gpu", "budget 16 spp, frames 2-33, 1 runs, clock wall",
                        "target variance 0.0001, frames 30-33, 1 runs, clock gpu"):
            check(f"light-off, 48x48, {setting}" in cost, f"the cost block has the table of {setting}")
        check("K2" in cost and "K4" in cost, "the cost block has the statistics' grain table (K1, K2, K4)")
        equal = block(text, "gpu-equal-time")
        for method in ("spvg", "cv", "cv-notex"):
            check(f"{method} vs burley-N at {method}'s SSS time" in equal,
                  f"the equal-time block has {method}'s line from the run's summary")
        check("scene light-off, 48x48" in equal, "the equal-time block names the run's scene and size")
        rows = [line for line in block(text, "gpu-targets").splitlines() if line.startswith("| ") and
                not line.startswith("| target")]
        check(len(rows) == 9 and all("| not judged:" in row and "not measured" not in row for row in rows),
              "every target is measured and, on llvmpipe, not judged: " + "\n".join(rows))

    return finish("test_gpu_runs_smoke")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
