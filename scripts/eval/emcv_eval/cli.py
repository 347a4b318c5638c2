# SPDX-License-Identifier: MIT
"""One command line over the evaluation's scripts: each subcommand runs one script's main with the arguments that
follow it (so `SUBCOMMAND --help` is that script's help), and `list` says what each regenerates.

    /usr/bin/python3 scripts/eval/emcv-eval-tools [--help] SUBCOMMAND [ARGS...]
    /usr/bin/python3 scripts/eval/emcv-eval-tools list
(the same as PYTHONPATH=scripts/eval /usr/bin/python3 -m emcv_eval ...). Every script stays runnable on its own as
/usr/bin/python3 scripts/eval/NAME.py (bash for the .sh one) with the same arguments.
"""
import importlib
import os
import subprocess
import sys

from . import EVAL_DIR, ROOT

PROG = "emcv-eval-tools"


class Command:
    def __init__(self, name, script, summary, regenerates, prefix=(), folder=EVAL_DIR):
        self.name, self.script, self.summary, self.regenerates = name, script, summary, regenerates
        self.prefix = list(prefix)  # arguments put before the user's (merge: --merge)
        self.folder = folder

    @property
    def path(self):
        return os.path.join(self.folder, self.script)

    @property
    def module(self):
        return os.path.splitext(self.script)[0]


_RUN_EVAL = ("docs/results.md blocks context, equal-samples, worth, lag, variations, teaser, teaser-time, "
             "heatmaps; docs/results/*.md (pareto, pareto-time, worth, equal-time, variations, switch, "
             "scaling-resolution, scaling-radius, seed-spread) and docs/results/*.png (with the default raw folder; "
             "else RAW_DIR/out/)")

COMMANDS = [
    Command("run", "run_eval.py", "the evaluation on this machine's renderer: render the job list (or a shard of "
            "it), then assemble the tables and plots", _RUN_EVAL),
    Command("merge", "run_eval.py", "run_eval.py --merge: render nothing, assemble the tables and plots from the "
            "raw files of every shard", _RUN_EVAL, prefix=["--merge"]),
    Command("gpu-runs", "gpu_runs.sh", "the runs a lent GPU machine makes (bash; --smoke: 48x48)",
            "a run folder OUT_DIR (the stored one: docs/results/gpu/), which gpu-report reads"),
    Command("gpu-report", "gpu_report.py", "turn a gpu-runs folder into docs/results.md's GPU section and judge "
            "issue 18's GPU targets", "docs/results.md blocks gpu-context, gpu-teaser, gpu-scaling, gpu-cost, "
            "gpu-equal-time, gpu-targets (or --doc PATH's)"),
    Command("sss-cost", "sss_cost.py", "the SSS passes' cost at equal samples, builds or --variant tunables "
            "interleaved", "a printed table (docs/notebook/2026-12-07-results-adaptive-cost.md); with --save-raw "
            "DIR, the cost-*/ folders of a gpu-runs folder"),
    Command("cost-model", "cost_model.py", "each SSS pass's bytes and SFU operations, floors on a GPU",
            "a printed table (docs/results.md, \"Cost model\")"),
    Command("bench-tables", "bench_tables.py", "the statistics' cost tables from emcv-bench (scripts/, not "
            "scripts/eval/)", "docs/results/accuracy-vs-time.md blocks context, reference-bound, compensated-cost, "
            "one-stream, scalar-float, scalar-double, batch, targets; docs/numerics.md block raw-moments; "
            "docs/integration.md block batch-summary", folder=os.path.join(ROOT, "scripts")),
    Command("oracle", "oracle.py", "the headroom of per-pixel sample allocation on a static scene",
            "a printed table, --csv FILE (docs/results.md, \"Allocation headroom\")"),
    Command("switch-crops", "switch_crops.py", "side-by-side crops per method around light-off's switch",
            "docs/images/switch-crops.png (or --out)"),
    Command("banding-crops", "banding_crops.py", "separable's bands against burley's noise on static",
            "docs/images/banding-static.png (or --out)"),
    Command("resolve-guide", "resolve_guide.py", "the resolve's guide: its effect and its cost",
            "docs/frame.md block resolve-guide-cost (with --write-doc); the effect table printed"),
    Command("resolve-table", "resolve_table.py", "the temporal resolve's effect per method, raw against resolved",
            "printed tables (docs/notebook/2026-12-07-frame-resolve-effect.md)"),
    Command("jitter-aa", "jitter_aa.py", "the resolve with and without jitter against an anti-aliased reference",
            "printed tables (docs/frame.md, \"Jitter and an anti-aliased reference\")"),
    Command("block-size", "block_size.py", "the statistics' grain EMCV_HISTORY_BLOCK (or --tunable) at equal samples",
            "a printed table (docs/notebook/2026-12-07-renderer-block-size.md)"),
    Command("warp-efficiency", "warp_efficiency.py", "warp efficiency of the SSS sampling loop; --steady: the "
            "work's spread from frame to frame", "printed tables (docs/notebook/2026-12-07-renderer-steady-work.md)"),
]
BY_NAME = {c.name: c for c in COMMANDS}


def usage(prog):
    width = max(len(c.name) for c in COMMANDS)
    lines = [f"usage: {prog} [-h] SUBCOMMAND [ARGS...]", "",
             "The evaluation's scripts (scripts/eval/) behind one command line. `SUBCOMMAND --help` is the "
             "script's own help.", "", "subcommands:",
             f"  {'list'.ljust(width)}  what each subcommand runs and regenerates (list --help)"]
    lines += [f"  {c.name.ljust(width)}  {c.summary} ({c.script})" for c in COMMANDS]
    return "\n".join(lines) + "\n"


def list_commands(prog, args):
    if args and args[0] in ("-h", "--help"):
        print(f"usage: {prog} list\n\nPrints, per subcommand, the script it runs and what it regenerates: the "
              "docs block, file or picture it writes, or where a printed table is kept.")
        return 0
    if args:
        sys.stderr.write(f"{prog} list: takes no arguments (got {' '.join(args)})\n")
        return 2
    for c in COMMANDS:
        script = os.path.relpath(c.path, ROOT) + (" " + " ".join(c.prefix) if c.prefix else "")
        print(f"{c.name}\t{script}\t{c.regenerates}")
    return 0


def shell_help(path):
    """The comment block at the top of a shell script (its usage), without the #! line and the '# '."""
    lines = []
    with open(path) as f:
        for line in f:
            if line.startswith("#!"):
                continue
            if not line.startswith("#"):
                break
            lines.append(line[2:].rstrip("\n") if line.startswith("# ") else line[1:].rstrip("\n"))
    return "\n".join(lines) + "\n"


def run_command(c, args, prog):
    """Runs subcommand `c` with `args`: a Python script's main(ARGS) (argparse naming the program "PROG NAME"), or a
    shell script under bash. Its exit status."""
    if c.script.endswith(".sh"):
        if any(a in ("-h", "--help") for a in args):
            sys.stdout.write(f"usage: {prog} {c.name} ARGS... (bash {os.path.relpath(c.path, ROOT)} ARGS...)\n\n"
                             + shell_help(c.path))
            return 0
        return subprocess.call(["bash", c.path] + c.prefix + args)
    if c.folder not in sys.path:
        sys.path.insert(0, c.folder)  # the scripts import one another (gpu_report: run_eval, sss_cost)
    module = importlib.import_module(c.module)
    saved = sys.argv
    sys.argv = [f"{prog} {c.name}"] + c.prefix + args  # argparse's usage line names the subcommand
    try:
        status = module.main(c.prefix + args)
    finally:
        sys.argv = saved
    return status if isinstance(status, int) else 0


def main(argv=None, prog=PROG):
    args = sys.argv[1:] if argv is None else list(argv)
    if not args or args[0] in ("-h", "--help"):
        sys.stdout.write(usage(prog))
        return 0 if args else 2
    name, rest = args[0], args[1:]
    if name == "list":
        return list_commands(prog, rest)
    if name not in BY_NAME:
        sys.stderr.write(usage(prog) + f"\n{prog}: unknown subcommand '{name}' (known: list, "
                         f"{', '.join(BY_NAME)})\n")
        return 2
    return run_command(BY_NAME[name], rest, prog)
