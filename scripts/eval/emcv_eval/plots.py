# SPDX-License-Identifier: MIT
"""matplotlib as the evaluation uses it: no display (Agg), one colour per method family, figures saved atomically."""
import os

from . import ROOT

COLOURS = {"burley": "tab:blue", "separable": "tab:orange", "spvg": "tab:red", "cv": "tab:green",
           "cv-notex": "tab:purple", "diffuse": "black"}
DPI = 110


def pyplot():
    """matplotlib.pyplot on the Agg backend (imported here: the maths of the scripts needs no matplotlib)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig, path, tight=False, dpi=DPI):
    """Writes `fig` to `path` (PNG) under a temporary name and renames it (no half-written image); closes it. The
    PNG is palette-encoded (256 colours, Pillow, which matplotlib itself needs): a plot's flat colours survive it, and
    it is about a third of the RGBA file's size (docs/ stays under its 2 MB)."""
    from PIL import Image
    folder = os.path.dirname(path)
    if folder:
        os.makedirs(folder, exist_ok=True)
    tmp = f"{path}.tmp{os.getpid()}.png"
    fig.savefig(tmp, dpi=dpi, **({"bbox_inches": "tight"} if tight else {}))
    with Image.open(tmp) as image:
        image.convert("RGB").quantize(256).save(tmp, optimize=True)
    os.replace(tmp, path)
    pyplot().close(fig)


def save_demo_figure(prog, fig, out, cmd):
    """Saves a picture made from one emcv-demo run (`cmd`, ending with --out DIR) and prints the command it came
    from, the build folder as build/ and the output as DIR."""
    save(fig, out)
    print("%s: wrote %s (%s)" % (prog, os.path.relpath(out, ROOT),
                                 " ".join(["build/bin/emcv-demo"] + cmd[1:-2] + ["--out", "DIR"])))
