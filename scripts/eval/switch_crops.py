#!/usr/bin/python3
"""Side-by-side crops per method around light-off's switch, raw and after the temporal resolve.

Renders light-off with emcv-demo (--resolve taa, the adaptive methods at --spp-budget B) and assembles one PNG:
a row per method (the reference last), columns: the raw and the resolved frame just before the switch, then the
raw and the resolved frame K frames after it; each crop is labelled with its whole-frame PSNR from
metrics.csv. PSNR does not see what the eye does (separable's banding, the resolve's ghost): the picture is
there to show it.

    /usr/bin/python3 scripts/eval/switch_crops.py [--build build] [--size 256x256] [--budget 8] [--after 3]
                                                  [--out docs/images/switch-crops.png]
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import ROOT, plots, runner  # noqa: E402  (the emcv-demo run, the atomic save)

plt = plots.pyplot()
import matplotlib.image as mpimg  # noqa: E402

SWITCH = 30  # light-off's key light switches off at frame 30 (demo/scenes/light-off.json)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--size", default="256x256")
    p.add_argument("--budget", type=int, default=8)
    p.add_argument("--after", type=int, default=3, help="frames after the switch of the second pair of columns")
    p.add_argument("--out", default=os.path.join(ROOT, "docs", "images", "switch-crops.png"))
    a = p.parse_args(argv)
    methods = ["burley-%d" % a.budget, "separable-17", "spvg", "cv", "cv-notex"]
    before, after = SWITCH - 1, SWITCH + a.after
    demo = os.path.join(a.build, "bin", "emcv-demo")
    with tempfile.TemporaryDirectory(prefix="emcv-crops-") as tmp:
        cmd = [demo, "--scene", "light-off", "--method", ",".join(methods), "--spp-budget", str(a.budget),
               "--size", a.size, "--frames", str(after + 1), "--resolve", "taa", "--out", tmp]
        rows = runner.run_demo("switch_crops.py", cmd)

        def crop(path):
            img = mpimg.imread(path)[..., :3]
            h, w = img.shape[:2]
            # the statuette's face: the middle half of the frame, a little above the centre
            y0, x0 = int(h * 0.2), int(w * 0.25)
            return img[y0:y0 + h // 2, x0:x0 + w // 2]

        columns = [("raw", before), ("resolved", before), ("raw", after), ("resolved", after)]
        fig, axes = plt.subplots(len(methods) + 1, len(columns), figsize=(2.2 * len(columns), 2.3 * (len(methods) + 1)))
        for i, m in enumerate(methods + ["reference"]):
            for j, (kind, frame) in enumerate(columns):
                ax = axes[i][j]
                ax.set_xticks([])
                ax.set_yticks([])
                if m == "reference" and kind == "resolved":
                    ax.axis("off")  # the reference is not resolved
                    continue
                stem = "frame" if kind == "raw" else "resolved"
                ax.imshow(crop(os.path.join(tmp, m, "%s-%04d.png" % (stem, frame))), interpolation="nearest")
                column = "psnr_db" if kind == "raw" else "psnr_resolved_db"
                value = rows[(m, frame)][column]
                label = "" if m == "reference" else "%.1f dB" % float(value)
                ax.set_title("%s %s\n%s" % (m, kind, label), fontsize=8)
            axes[i][0].set_ylabel(m, fontsize=8)
        fig.suptitle("light-off %s, budget %d: frame %d (before the switch) and frame %d (%d after); "
                     "PSNR of the whole frame" % (a.size, a.budget, before, after, a.after), fontsize=9)
        fig.tight_layout(rect=(0, 0, 1, 0.97))
        plots.save_demo_figure("switch_crops.py", fig, a.out, cmd)


if __name__ == "__main__":
    main()
