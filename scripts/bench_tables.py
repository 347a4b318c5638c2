#!/usr/bin/python3
"""Regenerates the tables of docs/accuracy-vs-time.md (and the raw-moment table of docs/numerics.md and the
batch figures quoted in docs/integration.md) from one run of emcv-bench.

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
DOC_INTEGRATION = os.path.join(ROOT, "docs", "integration.md")

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


def fmt_cell(b, kind):
    """An error cell. Where the measured error is not above the reference's own bound, the difference cannot
    be told from the reference's error: the cell then gives the certified upper bound, error + bound, as
    "<= x" instead of a value."""
    e, bound = b.get("err_" + kind), b.get("refbound_" + kind)
    if e is not None and bound is not None and bound > 0 and e == e and e <= bound:
        return f"<= {e + bound:.1e}"
    return fmt_err(e)


def scalar_table(rows, precision):
    lines = ["| variant | ns / update | rel. error: offset | rel. error: light step | "
             "rel. error: NumAcc3 |", "|---|---:|---:|---:|---:|"]
    prefix = f"scalar/{precision}/"
    for name, b in rows.items():
        if not name.startswith(prefix):
            continue
        variant = name[len(prefix):]
        ns = b["real_ns"] / b["updates"]
        lines.append(f"| {variant} | {ns:.2f} | {fmt_cell(b, 'offset')} | "
                     f"{fmt_cell(b, 'step')} | {fmt_cell(b, 'numacc3')} |")
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
                boost_cells = (f"Boost lazy_variance | {fmt_cell(lz, kind)}"
                               if lz is not None and stat == "cumulative variance" else "- | -")
                lines.append(f"| {precision} | {stat}, {kind} | {ours} | {fmt_cell(a, kind)} | "
                             f"{raw} | {fmt_cell(r, kind)} | {boost_cells} |")
    return "\n".join(lines)


def largest_cache(report):
    """(size in bytes, level) of the largest data or unified cache the benchmark reports, or None."""
    caches = [(x.get("size", 0), x.get("level", "?")) for x in report.get("context", {}).get("caches", [])
              if x.get("type") != "Instruction"]
    return max(caches) if caches else None


def copy_bound_sentence(report, rows):
    """Says whether the batch's copy bound is an in-cache copy: its working set against the largest cache."""
    sets = [b["working_set_bytes"] for n, b in rows.items() if n.startswith("batch/") and "working_set_bytes" in b]
    largest = largest_cache(report)
    if not sets or not largest:
        return "The batch's working set against the cache sizes is unknown (no cache or working-set report)."
    lo, hi = min(sets) / 2**20, max(sets) / 2**20
    cache, level = largest
    mib = cache / 2**20
    if max(sets) <= cache:
        return (f"The batch's working set (the distinct arrays of one frame, {lo:.0f} to {hi:.0f} MiB) fits the "
                f"largest reported cache (L{level}, {mib:.0f} MiB): its \"copy bound\" is an in-cache copy, faster than "
                f"a copy from DRAM would be.")
    if min(sets) > cache:
        return (f"The batch's working set ({lo:.0f} to {hi:.0f} MiB) exceeds the largest reported cache "
                f"({mib:.0f} MiB): its \"copy bound\" is a copy through DRAM.")
    return (f"The batch's working set ({lo:.0f} to {hi:.0f} MiB) straddles the largest reported cache ({mib:.0f} MiB): "
            f"the copy bound is an in-cache copy for the smaller kernels and a DRAM copy for the larger.")


def context_line(report, command, rows):
    c = report.get("context", {})
    caches = ", ".join(f"L{x['level']} {x['size'] // 1024} KiB" for x in c.get("caches", []) if x.get("type") != "Instruction")
    return (f"Measured by `{command}` on {c.get('num_cpus', '?')} CPUs at {c.get('mhz_per_cpu', '?')} MHz "
            f"({caches}), load average {', '.join(f'{x:.2f}' for x in c.get('load_avg', []))} at the start, "
            f"Google Benchmark library built as {c.get('library_build_type', '?')}, {c.get('date', '')}. "
            + copy_bound_sentence(report, rows))


def per_update(rows, name):
    b = rows.get(name)
    return None if b is None else b["real_ns"] / b["updates"]


def reference_bound_sentence(rows):
    parts, unresolved = [], 0
    for precision in ("float", "double"):
        worst = {}
        for name, b in rows.items():
            if not name.startswith(f"scalar/{precision}/"):
                continue
            for kind in ("offset", "step", "numacc3"):
                v = b.get("refbound_" + kind)
                if v is not None:
                    worst[kind] = max(worst.get(kind, 0.0), v)
                    e = b.get("err_" + kind)
                    unresolved += 1 if e is not None and v > 0 and e <= v else 0
        if worst:
            parts.append(f"{precision}: " + ", ".join(f"{k} {worst[k]:.1e}" for k in ("offset", "step", "numacc3")
                                                      if k in worst))
    if not parts:
        return "(the benchmark reported no reference bounds)"
    return (f"That reference carries its own a-priori error bound (docs/numerics.md section 2). Relative to the "
            f"exact value, the largest over the variants is {'; '.join(parts)} (Boost's rolling window uses a "
            f"two-pass sum without a bound). {unresolved} error cells are not above their reference's bound; "
            f"such a cell gives the certified upper bound, measured difference + reference bound, as \"<= x\".")


def compensated_cost(rows, fractions):
    lines = ["| precision | compensated_emcm / emcm (one stream) | compensated batch / plain batch | "
             "plain batch, fraction of its copy | compensated batch, fraction of its own copy |",
             "|---|---:|---:|---:|---:|"]
    for p in ("float", "double"):
        a, b = per_update(rows, f"scalar/{p}/compensated_emcm"), per_update(rows, f"scalar/{p}/emcm")
        c, d = rows.get(f"batch/{p}/moving_stats_update compensated"), rows.get(f"batch/{p}/moving_stats_update")
        if None in (a, b, c, d):
            continue
        lines.append(f"| {p} | {a / b:.1f}x | {c['real_ns'] / d['real_ns']:.1f}x | "
                     f"{100 * fractions.get((p, 'moving_stats_update'), 0):.0f}% | "
                     f"{100 * fractions.get((p, 'moving_stats_update compensated'), 0):.0f}% |")
    return "\n".join(lines)


def one_stream(rows):
    lines = ["| precision | step, clamps as selects (ns) | step, clamps behind branches (ns) | selects / branches | "
             "emcm push (ns) |", "|---|---:|---:|---:|---:|"]
    for p in ("float", "double"):
        sel = per_update(rows, f"scalar/{p}/emcm step, range clamps as selects")
        br = per_update(rows, f"scalar/{p}/emcm step, range clamps behind branches")
        push = per_update(rows, f"scalar/{p}/emcm")
        if None in (sel, br, push):
            continue
        lines.append(f"| {p} | {sel:.2f} | {br:.2f} | {sel / br:.2f}x | {push:.2f} |")
    return "\n".join(lines)


def integration_batch(fractions, report, rows):
    f = {k: 100 * v for k, v in fractions.items()}
    in_cache = "an in-cache copy" if "fits the largest" in copy_bound_sentence(report, rows) else "a copy"
    return (f"In the last benchmark run the plain update ran at {f.get(('float', 'moving_stats_update'), 0):.0f}% "
            f"(float) and {f.get(('double', 'moving_stats_update'), 0):.0f}% (double) of the speed of {in_cache} of "
            f"the same bytes, the compensated one at "
            f"{f.get(('float', 'moving_stats_update compensated'), 0):.0f}% and "
            f"{f.get(('double', 'moving_stats_update compensated'), 0):.0f}% of its own (larger) copy "
            f"([accuracy-vs-time.md](accuracy-vs-time.md), regenerated by `/usr/bin/python3 scripts/bench_tables.py`).")


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
        "context": context_line(report, command.replace(ROOT + "/", ""), rows),
        "reference-bound": reference_bound_sentence(rows),
        "compensated-cost": compensated_cost(rows, fractions),
        "one-stream": one_stream(rows),
        "scalar-float": scalar_table(rows, "float"),
        "scalar-double": scalar_table(rows, "double"),
        "batch": batch,
        "targets": targets_table(rows, fractions),
    }
    with open(DOC_TIME) as f:
        text_time = f.read()
    with open(DOC_NUMERICS) as f:
        text_numerics = f.read()
    with open(DOC_INTEGRATION) as f:
        text_integration = f.read()
    text_integration = replace_block(text_integration, "batch-summary", integration_batch(fractions, report, rows),
                                     DOC_INTEGRATION)
    for name, body in blocks_time.items():
        text_time = replace_block(text_time, name, body, DOC_TIME)
    text_numerics = replace_block(text_numerics, "raw-moments", raw_table(rows) + "\n\n" + blocks_time["context"],
                                  DOC_NUMERICS)
    write_atomically(DOC_TIME, text_time)
    write_atomically(DOC_NUMERICS, text_numerics)
    write_atomically(DOC_INTEGRATION, text_integration)
    print(f"wrote {os.path.relpath(DOC_TIME, ROOT)}, {os.path.relpath(DOC_NUMERICS, ROOT)} and "
          f"{os.path.relpath(DOC_INTEGRATION, ROOT)}")


if __name__ == "__main__":
    main()
