"""What the picture scripts (switch_crops.py, banding_crops.py) share: one emcv-demo run whose frames and
metrics they read, and the figure written under a temporary name and renamed (no half-written image)."""
import csv
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def render(prog, cmd):
    """Runs emcv-demo (cmd ends with --out DIR) and returns its metrics.csv rows keyed by (method, frame)."""
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit("%s: %s failed:\n%s" % (prog, " ".join(cmd), done.stderr))
    with open(os.path.join(cmd[-1], "metrics.csv")) as f:
        return {(r["method"], int(r["frame"])): r for r in csv.DictReader(f)}


def save(prog, fig, out, cmd):
    """Writes the figure to `out` atomically and prints the emcv-demo command it came from."""
    import matplotlib.pyplot as plt

    fig.savefig(out + ".tmp.png", dpi=110)
    plt.close(fig)
    os.replace(out + ".tmp.png", out)
    print("%s: wrote %s (%s)" % (prog, os.path.relpath(out, ROOT),
                                 " ".join(["build/bin/emcv-demo"] + cmd[1:-2] + ["--out", "DIR"])))
