# SPDX-License-Identifier: MIT
"""The commit a run or a generated block was made at."""
import subprocess

from . import ROOT

# The evaluation's own outputs: changes to them do not make the tree that rendered them "dirty".
OUTPUTS = ["docs/results", "docs/results.md", "docs/images"]


def commit(root=ROOT):
    """The commit, with -dirty when a tracked file other than the evaluation's outputs and the docs differs from it
    (docs/ holds the generated blocks the scripts write and prose: a run made while a doc was being edited ran
    the committed code); "unknown" outside a git checkout."""
    head = subprocess.run(["git", "-C", root, "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    if head.returncode != 0:
        return "unknown"
    changed = subprocess.run(["git", "-C", root, "status", "--porcelain", "--untracked-files=no", "--", "."] +
                             [f":(exclude){p}" for p in OUTPUTS + ["docs"]], capture_output=True, text=True).stdout
    return head.stdout.strip() + ("-dirty" if changed.strip() else "")
