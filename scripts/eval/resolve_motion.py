# SPDX-License-Identifier: MIT
"""What a moving camera leaves the resolve: the history's resampling against this frame's noise, and the best a
plain exponential blend does there (docs/frame.md, "A moving camera still costs the resolve most of its gain").

`moving` (the camera orbits the statuette; still lights), frames 0-29, PSNR of the whole frame against the
reference, mean over frames 5-29, at four image sizes, for `burley-8` (the noisy input the resolve is for) and
`burley-256` (nearly noise free: its raw frame is within about 60 dB of the reference, so what its resolved image
loses is the history's own error, not noise). Resolves:

  as built     this tree's resolve (the guide, clip box, noise box, its weights).
  no guide     the same without the guide (--define EMCV_RESOLVE_GUIDE=0): the history as reprojected.
  plain w      a variant of this tree's shaders (a copy with a text replacement, read through EMCV_SHADER_DIR): no
               clip at all and no guide, the reprojected history blended with the current value at the fixed weight
               w (EMCV_RESOLVE_BLEND = w), for w = 0.1, 0.25, 0.5. On independent noise alone it would gain
               10 log10((2 - w) / w): 12.8, 8.5 and 4.8 dB; what it gains less is the history's error. Its best w
               is an upper reference for any resolve that blends a reprojected history at one weight.

For `burley-256` under `plain 0.5` the resolved image's error is about one frame's worth of the history's
resampling and lag (the lag of an exponential blend of weight w behind a steady change d a frame is
d (1 - w) / w, d at w = 0.5): the "history drift" column, in dB of PSNR. Where it is near `burley-8`'s raw PSNR,
the history a frame old is as far off as this frame's noise and no reprojecting blend can gain much.

A second table, the gain the resolve as built gives each stochastic method under this moving camera once it has
warmed up: `moving`'s 60 frames, mean over frames 20-59 (the same span as docs/frame.md's guide table), the
adaptive methods at --spp-budget B beside burley-B, for B = 8, 16 and 32, at the four sizes. The still-camera
target of the resolve is a gain of at least 6 dB; the table shows where a moving camera keeps it.

    /usr/bin/python3 scripts/eval/resolve_motion.py [--build build] [--write-doc]

With --write-doc the tables replace the GENERATED blocks "resolve-motion" and "resolve-motion-gain" of
docs/frame.md.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

from adaptive_overhead import make_variant
from resolve_guide import NO_GUIDE
from resolve_table import SETTLED_FROM, run_scene, summary
from run_eval import git_commit, replace_block, write_atomically

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DOC = os.path.join(ROOT, "docs", "frame.md")
RESOLVE = "render/resolve.comp.glsl"
# The resolve without any clip or weight rule: the reprojected history blended at EMCV_RESOLVE_BLEND.
PLAIN = [(RESOLVE, "        resolved = emcv_resolve_blend(emcv_resolve_clip(history, target, lo, hi), current, weight);\n",
          "        resolved = emcv_resolve_blend(history, current, float(EMCV_RESOLVE_BLEND));\n")]
SIZES = ["96x96", "128x128", "192x192", "256x256"]
PLAIN_WEIGHTS = ["0.1", "0.25", "0.5"]
FRAMES, FIRST = 30, 5
METHODS = ["burley-8", "burley-256"]
GAIN_BUDGETS = [8, 16, 32]
ADAPTIVE = ["spvg", "cv", "cv-notex"]


def gain(resolved, raw):
    """A resolved PSNR with its gain over the raw one, as the tables show it."""
    return f"{resolved:.2f} ({resolved - raw:+.2f})"


def run(build, size, shader_dir, defines, out, scene="moving", methods=METHODS, frames=FRAMES, first=FIRST):
    """emcv-demo on `scene` with the shaders of `shader_dir`: per method, its mean raw and resolved PSNR over the
    frames from `first` on (resolve_floor.py runs it on its own scenes)."""
    cmd = [os.path.join(build, "bin", "emcv-demo"), "--scene", scene, "--method", ",".join(methods), "--size",
           size, "--frames", str(frames), "--resolve", "taa", "--no-frames", "--out", out]
    for d in defines:
        cmd += ["--define", d]
    done = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, EMCV_SHADER_DIR=shader_dir))
    if done.returncode != 0:
        sys.exit("resolve_motion: %s failed:\n%s" % (" ".join(cmd), done.stderr))
    with open(os.path.join(out, "metrics.csv")) as f:
        rows = [r for r in csv.DictReader(f) if int(r["frame"]) >= first]
    result = {}
    for m in methods:
        own = [r for r in rows if r["method"] == m]
        if len(own) != frames - first:
            sys.exit(f"resolve_motion: {m} has {len(own)} frames from {first} on, not {frames - first}")
        raw = [float(r["psnr_db"]) for r in own]
        resolved = [float(r["psnr_resolved_db"]) for r in own]
        if not all(math.isfinite(v) for v in raw + resolved):
            sys.exit(f"resolve_motion: {m} has a non-finite PSNR")
        result[m] = (sum(raw) / len(raw), sum(resolved) / len(resolved))
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--write-doc", action="store_true")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="emcv-resolve-motion-") as tmp:
        plain_dir = make_variant(os.path.join(tmp, "plain"), PLAIN)
        built_dir = os.path.join(ROOT, "shaders")
        lines = ["| size | burley-8 raw | as built | no guide | plain 0.1 | plain 0.25 | plain 0.5 | burley-256 raw | "
                 "as built | no guide | history drift (plain 0.5) |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
        for size in SIZES:
            built = run(a.build, size, built_dir, [], os.path.join(tmp, f"built-{size}"))
            unguided = run(a.build, size, built_dir, [NO_GUIDE], os.path.join(tmp, f"unguided-{size}"))
            plain = {w: run(a.build, size, plain_dir, [f"EMCV_RESOLVE_BLEND={w}", NO_GUIDE],
                            os.path.join(tmp, f"plain-{w}-{size}"))
                     for w in PLAIN_WEIGHTS}
            raw8, raw256 = built["burley-8"][0], built["burley-256"][0]
            lines.append("| " + " | ".join([size, f"{raw8:.2f}", gain(built["burley-8"][1], raw8),
                                           gain(unguided["burley-8"][1], raw8)]
                                          + [gain(plain[w]["burley-8"][1], raw8) for w in PLAIN_WEIGHTS]
                                          + [f"{raw256:.2f}", gain(built["burley-256"][1], raw256),
                                             gain(unguided["burley-256"][1], raw256),
                                             f"{plain['0.5']['burley-256'][1]:.2f}"]) + " |")
            print(lines[-1], flush=True)
        gain_lines = ["| size | B | " + " | ".join(["burley-B"] + ADAPTIVE) + " |",
                      "|---|---:|" + "---:|" * (1 + len(ADAPTIVE))]
        for size in SIZES:
            for budget in GAIN_BUDGETS:
                methods = [f"burley-{budget}"] + ADAPTIVE
                rows, _ = run_scene(a.build, "moving", methods, size, budget, os.path.join(tmp, f"gain-{size}-{budget}"))
                last_frame = max(int(r["frame"]) for r in rows)  # the scene's length decides it
                cells = []
                for m in methods:
                    raw, resolved = summary(rows, None, m)[:2]
                    if raw is None or resolved is None:
                        sys.exit(f"resolve_motion: no frames of {m} from {SETTLED_FROM} on at {size}, B = {budget}")
                    cells.append(gain(resolved, raw))
                gain_lines.append(f"| {size} | {budget} | " + " | ".join(cells) + " |")
                print(gain_lines[-1], flush=True)
    command = "`/usr/bin/python3 scripts/eval/resolve_motion.py --write-doc`"
    made = f"made at commit {git_commit()}"
    body = "\n".join([f"Regenerated by {command}, {made}. PSNR (dB, whole frame), mean over frames {FIRST}-{FRAMES - 1} "
                      "of `moving`; resolved columns with their gain over the raw frames.", ""] + lines)
    gain_body = "\n".join([f"Regenerated by {command}, {made}. Resolved PSNR (dB, whole frame) and its gain over the "
                           f"raw frames, mean over frames {SETTLED_FROM}-{last_frame} of `moving`, the adaptive "
                           "methods at --spp-budget B.", ""] + gain_lines)
    print(body + "\n\n" + gain_body)
    if a.write_doc:
        with open(DOC) as f:
            text = f.read()
        text = replace_block(text, "resolve-motion", body, DOC)
        write_atomically(DOC, replace_block(text, "resolve-motion-gain", gain_body, DOC))
        print(f"wrote {os.path.relpath(DOC, ROOT)}")


if __name__ == "__main__":
    main()
