# SPDX-License-Identifier: MIT
"""PYTHONPATH=scripts/eval /usr/bin/python3 -m emcv_eval SUBCOMMAND ...: the same as scripts/eval/emcv-eval-tools."""
import sys

from .cli import main

sys.exit(main(sys.argv[1:]))
