# SPDX-License-Identifier: MIT
"""emcv's evaluation tools as one package: what the scripts of scripts/eval/ share, and one command line over them.

    runner  the build's executables (emcv-demo, emcv-eval, ...), running them, reading their metrics CSV / JSON
    tables  number and markdown table formatting, the means and medians the tables take
    docs    a GENERATED block of a markdown file replaced under its provenance line; writing a file atomically
    plots   matplotlib without a display, the method colours, a figure saved atomically
    git     the commit a run was made at ("<hash>" or "<hash>-dirty")
    cli     /usr/bin/python3 scripts/eval/emcv-eval-tools SUBCOMMAND ... (or, with PYTHONPATH=scripts/eval,
            /usr/bin/python3 -m emcv_eval SUBCOMMAND ...): each subcommand runs one script's main; `list` says what
            each regenerates

Python 3.11's standard library, numpy and matplotlib (Debian's); no other dependency. The scripts of scripts/eval/
stay runnable as `/usr/bin/python3 scripts/eval/NAME.py` with their own command lines.
"""
import os

EVAL_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # scripts/eval
ROOT = os.path.dirname(os.path.dirname(EVAL_DIR))                       # the repository
