#!/usr/bin/python3
"""Separable's banding beside its PSNR: zoomed crops of `static`, separable-17 against burley-16 and the reference.

Renders `static` with emcv-demo (--resolve taa) and assembles one PNG: one column per image (separable-17 raw and
resolved, burley-B raw and resolved, the reference); above, a zoomed crop of the face (nose shadow, lips, chin,
where separable's error concentrates), below, the same crop's error against the reference, |image - reference|
scaled by --gain. Each column is labelled with the whole frame's PSNR from metrics.csv. Separable's error has
structure (bands along the shadow edges), burley's is noise; the PSNR says the opposite of what the eye sees.

    /usr/bin/python3 scripts/eval/banding_crops.py [--build build] [--size 256x256] [--budget 16] [--frame 39]
                                                   [--gain 8] [--out docs/images/banding-static.png]
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import ROOT, plots, runner  # noqa: E402  (the emcv-demo run, the atomic save)

plt = plots.pyplot()
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--size", default="256x256")
    p.add_argument("--budget", type=int, default=16, help="burley's samples per SSS pixel (default 16)")
    p.add_argument("--frame", type=int, default=39, help="the frame shown (default 39: the resolve has settled)")
    p.add_argument("--gain", type=float, default=8.0, help="the error column's scale (default 8)")
    p.add_argument("--out", default=os.path.join(ROOT, "docs", "images", "banding-static.png"))
    a = p.parse_args(argv)
    if a.frame < 0 or a.gain <= 0:
        sys.exit("banding_crops.py: --frame must be >= 0 and --gain > 0")
    burley = "burley-%d" % a.budget
    methods = ["separable-17", burley]
    demo = os.path.join(a.build, "bin", "emcv-demo")
    with tempfile.TemporaryDirectory(prefix="emcv-banding-") as tmp:
        cmd = [demo, "--scene", "static", "--method", ",".join(methods), "--size", a.size, "--frames",
               str(a.frame + 1), "--resolve", "taa", "--out", tmp]
        rows = runner.run_demo("banding_crops.py", cmd)

        def image(method, kind):
            stem = "frame" if kind == "raw" else "resolved"
            return mpimg.imread(os.path.join(tmp, method, "%s-%04d.png" % (stem, a.frame)))[..., :3]

        reference = image("reference", "raw")
        h, w = reference.shape[:2]
        # the face's lower half: the nose's shadow edge, the lips and the chin (Igea at 256x256: y 90-220, x 90-200)
        y0, y1, x0, x1 = int(h * 0.35), int(h * 0.86), int(w * 0.35), int(w * 0.78)
        entries = [(m, k) for m in methods for k in ("raw", "resolved")] + [("reference", "raw")]
        fig, columns = plt.subplots(2, len(entries), figsize=(2.6 * len(entries), 7.2))
        axes = list(zip(columns[0], columns[1]))  # per entry: the crop above its error
        for i, (m, kind) in enumerate(entries):
            img = image(m, kind)
            crop = img[y0:y1, x0:x1]
            error = np.clip(np.abs(crop - reference[y0:y1, x0:x1]).mean(axis=-1) * a.gain, 0.0, 1.0)
            axes[i][0].imshow(crop, interpolation="nearest")
            axes[i][1].imshow(error, cmap="magma", vmin=0.0, vmax=1.0, interpolation="nearest")
            if m == "reference":
                title = "reference (1024 spp)"
            else:
                column = "psnr_db" if kind == "raw" else "psnr_resolved_db"
                title = "%s %s: %.2f dB" % (m, kind, float(rows[(m, a.frame)][column]))
            axes[i][0].set_title(title, fontsize=8)
            axes[i][1].set_title("|image - reference| x %g" % a.gain, fontsize=8)
            for ax in axes[i]:
                ax.set_xticks([])
                ax.set_yticks([])
        fig.suptitle("static %s, frame %d: separable's bands against burley's noise (PSNR: whole frame)"
                     % (a.size, a.frame), fontsize=9)
        fig.tight_layout(rect=(0, 0, 1, 0.98))
        plots.save_demo_figure("banding_crops.py", fig, a.out, cmd)


if __name__ == "__main__":
    main()
