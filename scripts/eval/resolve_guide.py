# SPDX-License-Identifier: MIT
"""The resolve's guide: what moving the reprojected history by the change of the noise-free guide gains, and what
it costs (docs/frame.md, "The guide").

The resolve moves its reprojected history by slope (guide - guide_history) (include/emcv/port/resolve.h,
emcv_resolve_guided_history): the guide is, at a scattering pixel, a fixed Burley estimate of the scattered light
(EMCV_RESOLVE_GUIDE_TAPS taps at one rotation, the same every frame) times the albedo in display YCoCg, and
elsewhere the resolved value; `guide_history` is last frame's guide resampled with the history's own weights, and
the slope the least-squares slope of the current values on the guide over the pixel's 3x3 neighbourhood
(emcv_resolve_guide_slope). The same binary runs with the guide (as built), with the guide of the unscattered
light (the albedo times the lighting pass's diffuse light, `--define EMCV_RESOLVE_GUIDE_TAPS=0`, the guide until
the taps were added) and without a guide (`--define EMCV_RESOLVE_GUIDE=0`). Two tables:

  effect  resolve_table.py's columns for the three (PSNR of the whole frame, mean over frames 20 up to the
          scene's first light change, "before", and over the 30 frames from it, "after"; lag: frames after the
          change until the resolved PSNR stays within 1 dB of its settled value), 96x96, the adaptive methods at
          a budget of 8, on the scenes of resolve_table.py's set
          (docs/notebook/2026-12-07-frame-resolve-effect.md):
          still cameras (`static`, light-off, the burst, the fade, the skin close-up, the tabletop), moving ones
          (`moving`, the camera move during the switch, the skin orbit). The stochastic methods only: nothing in
          diffuse's and separable's frames is sampled, so the noise box closes on the current value (to within
          half an 8-bit step, emcv_resolve_clip's floor: there the guide moves their resolved images by hundredths
          of a dB under a moving camera).
  cost    the resolve pass's time (wall clock, llvmpipe: work, not GPU time) without a guide, with the unscattered
          guide and as built, `burley-8` at 256x256 on `static` (a still camera: one history texel per pixel) and
          on `moving` (16), 5 rounds alternating the order, the pass's median over frames 4-29, the median round.

    /usr/bin/python3 scripts/eval/resolve_guide.py [--build build] [--write-doc]

Both tables are printed. With --write-doc the cost table also replaces the GENERATED block "resolve-guide-cost"
of docs/frame.md; the effect table is printed only (docs/frame.md is a reference page without room for it: the
table as made at commit ce71b41 and its reading are in docs/notebook/2026-12-07-resolve-guide-weight.md and
docs/notebook/2026-12-07-frame-resolve-guide.md).
"""
import argparse
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import ROOT, docs, git, runner  # noqa: E402
from emcv_eval.tables import cell  # noqa: E402,F401
from resolve_table import run_scene, summary  # noqa: E402

DOC = os.path.join(ROOT, "docs", "frame.md")
NO_GUIDE = "EMCV_RESOLVE_GUIDE=0"
# The guide of the unscattered light (the albedo times the lighting pass's diffuse) instead of the fixed estimate
# of the scattered light (EMCV_RESOLVE_GUIDE_TAPS taps, include/emcv/port/resolve.h).
UNSCATTERED_GUIDE = "EMCV_RESOLVE_GUIDE_TAPS=0"
SCENES = ["static", "light-off", "demo/scenes/variations/burst-3.json", "demo/scenes/variations/fade.json",
          "demo/scenes/validation/skin-close.json", "demo/scenes/validation/mixed-off.json", "moving",
          "demo/scenes/variations/camera-switch.json", "demo/scenes/validation/skin-orbit.json"]
BUDGET = 8
METHODS = [f"burley-{BUDGET}", "spvg", "cv", "cv-notex"]
COST_SCENES = ["static", "moving"]
COST_ROUNDS = 5


def effect_table(build, tmp):
    lines = ["| scene | method | raw before | resolved before: no guide | unscattered guide | guide | gain | "
             "raw after | resolved after: no guide | unscattered guide | guide | gain | lag: no guide | "
             "unscattered | guide |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for scene in SCENES:
        name = os.path.splitext(os.path.basename(scene))[0]
        guided, change = run_scene(build, scene, METHODS, "96x96", BUDGET, os.path.join(tmp, f"guide-{name}"))
        unguided, change_unguided = run_scene(build, scene, METHODS, "96x96", BUDGET,
                                              os.path.join(tmp, f"no-guide-{name}"), [NO_GUIDE])
        unscattered, change_unscattered = run_scene(build, scene, METHODS, "96x96", BUDGET,
                                                    os.path.join(tmp, f"unscattered-{name}"), [UNSCATTERED_GUIDE])
        if not change == change_unguided == change_unscattered:
            sys.exit(f"resolve_guide.py: {scene}: the light change moved with the guide "
                     f"({change_unguided}, {change_unscattered} -> {change})")
        for m in METHODS:
            if not any(r["method"] == m for r in guided + unguided + unscattered):
                sys.exit(f"resolve_guide.py: no rows of {m} on {scene}")
            g, u, s = (summary(rows, change, m) for rows in (guided, unguided, unscattered))
            gain_before = None if g[1] is None or s[1] is None else g[1] - s[1]
            gain_after = None if g[3] is None or s[3] is None else g[3] - s[3]
            lines.append("| " + " | ".join([name, m, cell(g[0]), cell(u[1]), cell(s[1]), cell(g[1]),
                                            cell(gain_before, sign=True), cell(g[2]), cell(u[3]), cell(s[3]),
                                            cell(g[3]), cell(gain_after, sign=True),
                                            "-" if u[4] is None else str(u[4]),
                                            "-" if s[4] is None else str(s[4]),
                                            "-" if g[4] is None else str(g[4])]) + " |")
            print(lines[-1], flush=True)
    return "\n".join(lines)


def resolve_median(build, scene, defines, out):
    """The resolve pass's median time over frames 4-29 of burley-8 on `scene`, 256x256."""
    cmd = runner.command(runner.tool_path(build, "emcv-demo"), scene=scene, methods=[f"burley-{BUDGET}"],
                         size="256x256", frames=30, defines=defines,
                         extra=["--resolve", "taa", "--timing", "wall", "--no-frames", "--out", out])
    runner.run(cmd, "resolve_guide.py")
    rows = runner.metrics_json(out)
    times = [p["ms"] for r in rows if r["method"] == f"burley-{BUDGET}" and r["frame"] >= 4
             for p in r["passes"] if p["name"] == "resolve"]
    if len(times) != 26:
        sys.exit(f"resolve_guide.py: {len(times)} resolve times on {scene}, not 26")
    return statistics.median(times)


def cost_table(build, tmp):
    lines = ["| scene | camera | resolve without the guide (ms) | unscattered guide (ms) | guide (ms) | "
             "unscattered / without | guide / without |", "|---|---|---:|---:|---:|---:|---:|"]
    for scene in COST_SCENES:
        variants = [("without", [NO_GUIDE]), ("unscattered", [UNSCATTERED_GUIDE]), ("with", [])]
        rounds = {name: [] for name, _ in variants}
        for k in range(COST_ROUNDS):
            for name, defines in (variants if k % 2 == 0 else list(reversed(variants))):
                rounds[name].append(resolve_median(build, scene, defines, os.path.join(tmp, f"cost-{scene}-{name}-{k}")))
        without, unscattered, with_guide = (statistics.median(rounds[n]) for n in ("without", "unscattered", "with"))
        camera = "moving" if scene == "moving" else "still"
        lines.append(f"| {scene} | {camera} | {without:.3f} | {unscattered:.3f} | {with_guide:.3f} | "
                     f"{unscattered / without:.2f} | {with_guide / without:.2f} |")
        print(lines[-1], flush=True)
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--write-doc", action="store_true",
                    help="also put the cost table in docs/frame.md's GENERATED block resolve-guide-cost")
    a = ap.parse_args(argv)
    commit = git.commit()
    made = f"made at commit {commit}"
    with tempfile.TemporaryDirectory(prefix="emcv-resolve-guide-") as tmp:
        effect = effect_table(a.build, tmp)
        cost = cost_table(a.build, tmp)
    command = docs.script_command("scripts/eval/resolve_guide.py", ["--write-doc"])
    effect_body = "\n".join([f"Made by `/usr/bin/python3 scripts/eval/resolve_guide.py`, {made}. PSNR (dB, whole frame), 96x96, the adaptive methods "
                             f"at a budget of {BUDGET}; unscattered guide: the guide of the unscattered light "
                             f"(`--define {UNSCATTERED_GUIDE}`); guide: as built (the fixed "
                             "estimate of the scattered light); gain: as built less the unscattered guide.", "", effect])
    cost_body = "\n".join([docs.provenance(command, commit) + " Wall clock on llvmpipe (work, not GPU time), "
                           f"burley-{BUDGET} at 256x256, median over frames 4-29, the median of {COST_ROUNDS} "
                           "alternating rounds.", "", cost])
    print(effect_body + "\n\n" + cost_body)
    if a.write_doc:
        with open(DOC) as f:
            text = f.read()
        text = docs.replace_block(text, "resolve-guide-cost", cost_body, DOC, "resolve_guide.py")
        docs.write_atomically(DOC, text)
        print(f"wrote {os.path.relpath(DOC, ROOT)}")


if __name__ == "__main__":
    main()
