#!/usr/bin/python3
"""Regenerates the tables of docs/accuracy-vs-time.md (and the raw-moment table of docs/numerics.md) from
one run of emcv-bench.

Usage (from the repository root, after building emcv-bench):
    /usr/bin/python3 scripts/bench_tables.py [--bench build/bin/emcv-bench] [--min-time 0.1] [--repetitions 3]

It runs the benchmark with --benchmark_format=json, keeps the median of the repetitions, and replaces the text
between the markers <!-- BEGIN GENERATED: name --> and <!-- END GENERATED: name --> in the two documents.
Both files are written only after every table was built (a failed run leaves them untouched).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC_TIME = os.path.join(ROOT, "docs", "accuracy-vs-time.md")
DOC_NUMERICS = os.path.join(ROOT, "docs", "numerics.md")

# which Boost variant a variant of ours is compared with (same statistic, same stream)
BOOST_EQUIVALENT = {
    "emcm": "Boost rolling_variance (window 39)",
    "moving_stats": "Boost rolling_variance (window 39)",
    "running_covariance": "Boost variance (immediate)",
    "weighted_covariance 2-D": "Boost weighted_covariance",
}
# ours computes the whole 2x2 matrix (both variances and the covariance); Boost's weighted_covariance only the
# covariance, so the like-for-like comparison also adds Boost's two weighted variances
BOOST_SAME_OUTPUTS = {
    "weighted_covariance 2-D": "Boost weighted_covariance + 2 weighted_variance (same 2x2 matrix)",
}


def run_bench(bench, min_time, repetitions):
    if not os.path.isfile(bench) or not os.access(bench, os.X_OK):
        sys.exit(f"bench_tables.py: no executable emcv-bench at {bench} (build the emcv-bench target first)")
    cmd = [bench, "--benchmark_format=json", f"--benchmark_min_time={min_time}",
           f"--benchmark_repetitions={repetitions}", "--benchmark_report_aggregates_only=true"]
    out = subprocess.run(cmd, check=False, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"bench_tables.py: {' '.join(cmd)} failed with status {out.returncode}:\n{out.stderr}")
    return json.loads(out.stdout), " ".join(cmd)


def medians(report):
    rows = {}
    for b in report["benchmarks"]:
        if b.get("aggregate_name", "median") != "median":
            continue
        name = b.get("run_name", b["name"])
        scale = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}[b.get("time_unit", "ns")]
        rows[name] = dict(b, real_ns=b["real_time"] * scale)
    return rows


def fmt_err(e):
    if e is None:
        return "-"
    if e != e or e == float("inf"):
        return "**inf**"
    if e == 0:
        return "0"
    s = f"{e:.1e}"
    return f"**{s}**" if e >= 1e-2 else s


def scalar_table(rows, precision):
    lines = ["| variant | ns / update | rel. error: offset | rel. error: light step | "
             "rel. error: NumAcc3 |", "|---|---:|---:|---:|---:|"]
    prefix = f"scalar/{precision}/"
    for name, b in rows.items():
        if not name.startswith(prefix):
            continue
        variant = name[len(prefix):]
        ns = b["real_ns"] / b["updates"]
        lines.append(f"| {variant} | {ns:.2f} | {fmt_err(b.get('err_offset'))} | "
                     f"{fmt_err(b.get('err_step'))} | {fmt_err(b.get('err_numacc3'))} |")
    return "\n".join(lines)


def batch_table(rows):
    lines = ["| precision | kernel | ms per 1920x1080 frame | ns / pixel | GB/s | fraction of the same-bytes copy |",
             "|---|---|---:|---:|---:|---:|"]
    fractions = {}
    for precision in ("float", "double"):
        for kernel, copy in (("moving_stats_update", "copy (same bytes)"),
                             ("moving_stats_update compensated", "copy compensated (same bytes)"),
                             ("copy (same bytes)", "copy (same bytes)"),
                             ("copy compensated (same bytes)", "copy compensated (same bytes)")):
            b = rows.get(f"batch/{precision}/{kernel}")
            c = rows.get(f"batch/{precision}/{copy}")
            if b is None or c is None:
                continue
            frac = c["real_ns"] / b["real_ns"]
            fractions[(precision, kernel)] = frac
            gbs = b.get("bytes_per_second", 0) / 1e9
            lines.append(f"| {precision} | {kernel} | {b['real_ns'] / 1e6:.3f} | {b['real_ns'] / b['updates']:.3f} | "
                         f"{gbs:.1f} | {100 * frac:.0f}% |")
    return "\n".join(lines), fractions


def targets_table(rows, fractions):
    lines = ["| target | measured | met |", "|---|---|---|"]
    for precision in ("float", "double"):
        f = fractions.get((precision, "moving_stats_update"))
        if f is not None:
            lines.append(f"| batch EMCM update ({precision}) >= 70% of the copy bound | {100 * f:.0f}% | "
                         f"{'yes' if f >= 0.7 else '**no**'} |")
    for precision in ("float", "double"):
        for ours, boost in list(BOOST_EQUIVALENT.items()) + list(BOOST_SAME_OUTPUTS.items()):
            a = rows.get(f"scalar/{precision}/{ours}")
            b = rows.get(f"scalar/{precision}/{boost}")
            if a is None or b is None:
                continue
            ta, tb = a["real_ns"] / a["updates"], b["real_ns"] / b["updates"]
            lines.append(f"| {ours} ({precision}) faster than {boost} | {ta:.2f} ns vs {tb:.2f} ns | "
                         f"{'yes' if ta < tb else '**no**'} |")
    return "\n".join(lines)


def raw_table(rows):
    lines = ["| precision | statistic | ours | error | raw moments | error | Boost lazy_variance (raw) | error |",
             "|---|---|---|---:|---|---:|---|---:|"]
    for precision in ("float", "double"):
        for kind in ("offset", "numacc3"):
            for stat, ours, raw in (("exponential variance", "emcm", "raw moments (exponential E[x^2]-E[x]^2)"),
                                    ("cumulative variance", "running_covariance",
                                     "raw moments (cumulative E[x^2]-E[x]^2)")):
                a = rows.get(f"scalar/{precision}/{ours}")
                r = rows.get(f"scalar/{precision}/{raw}")
                lz = rows.get(f"scalar/{precision}/Boost lazy_variance (raw moments)")
                if a is None or r is None:
                    continue
                boost_cells = (f"Boost lazy_variance | {fmt_err(lz.get('err_' + kind))}"
                               if lz is not None and stat == "cumulative variance" else "- | -")
                lines.append(f"| {precision} | {stat}, {kind} | {ours} | {fmt_err(a.get('err_' + kind))} | "
                             f"{raw} | {fmt_err(r.get('err_' + kind))} | {boost_cells} |")
    return "\n".join(lines)


def context_line(report, command):
    c = report.get("context", {})
    caches = ", ".join(f"L{x['level']} {x['size'] // 1024} KiB" for x in c.get("caches", []) if x.get("type") != "Instruction")
    return (f"Measured by `{command}` on {c.get('num_cpus', '?')} CPUs at {c.get('mhz_per_cpu', '?')} MHz "
            f"({caches}), load average {', '.join(f'{x:.2f}' for x in c.get('load_avg', []))} at the start, "
            f"Google Benchmark library built as {c.get('library_build_type', '?')}, {c.get('date', '')}.")


def replace_block(text, name, body, path):
    begin, end = f"<!-- BEGIN GENERATED: {name} -->", f"<!-- END GENERATED: {name} -->"
    i, j = text.find(begin), text.find(end)
    if i < 0 or j < i:
        sys.exit(f"bench_tables.py: {path} has no '{begin}' ... '{end}' block")
    return text[: i + len(begin)] + "\n" + body + "\n" + text[j:]


def write_atomically(path, text):
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), prefix=".bench_tables.")
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bench", default=os.path.join(ROOT, "build", "bin", "emcv-bench"))
    ap.add_argument("--min-time", default="0.1")
    ap.add_argument("--repetitions", type=int, default=3)
    args = ap.parse_args()
    if args.repetitions < 1:
        sys.exit("bench_tables.py: --repetitions must be at least 1")

    report, command = run_bench(args.bench, args.min_time, args.repetitions)
    rows = medians(report)
    if not rows:
        sys.exit("bench_tables.py: the benchmark reported no results")
    batch, fractions = batch_table(rows)
    blocks_time = {
        "context": context_line(report, command.replace(ROOT + "/", "")),
        "scalar-float": scalar_table(rows, "float"),
        "scalar-double": scalar_table(rows, "double"),
        "batch": batch,
        "targets": targets_table(rows, fractions),
    }
    with open(DOC_TIME) as f:
        text_time = f.read()
    with open(DOC_NUMERICS) as f:
        text_numerics = f.read()
    for name, body in blocks_time.items():
        text_time = replace_block(text_time, name, body, DOC_TIME)
    text_numerics = replace_block(text_numerics, "raw-moments", raw_table(rows) + "\n\n" + blocks_time["context"],
                                  DOC_NUMERICS)
    write_atomically(DOC_TIME, text_time)
    write_atomically(DOC_NUMERICS, text_numerics)
    print(f"wrote {os.path.relpath(DOC_TIME, ROOT)} and {os.path.relpath(DOC_NUMERICS, ROOT)}")


if __name__ == "__main__":
    main()
