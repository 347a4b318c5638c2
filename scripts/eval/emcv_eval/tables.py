# SPDX-License-Identifier: MIT
"""Numbers and markdown tables as the evaluation's tables print them."""
import math
import statistics


def to_float(v):
    """A CSV cell as a float; NaN for an empty or unreadable one."""
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def fmt(x, digits=2):
    """`x` to `digits` decimals; "n/a" for None, NaN or infinity."""
    return "n/a" if x is None or (isinstance(x, float) and not math.isfinite(x)) else f"{x:.{digits}f}"


def sign(x, digits=2):
    """`x` with its sign to `digits` decimals; "n/a" for None, NaN or infinity."""
    return "n/a" if x is None or not math.isfinite(x) else f"{x:+.{digits}f}"


def cell(value, digits=2, sign=False):
    """`value` to `digits` decimals (with its sign under `sign`); "-" for None (an empty span)."""
    if value is None:
        return "-"
    return f"{value:+.{digits}f}" if sign else f"{value:.{digits}f}"


def mean_finite(xs):
    """The mean of the finite values of `xs`; NaN without one."""
    xs = [x for x in xs if math.isfinite(x)]
    return math.fsum(xs) / len(xs) if xs else math.nan


def median(xs):
    """The median of the values of `xs` that are not NaN; NaN without one."""
    xs = [x for x in xs if not math.isnan(x)]
    return statistics.median(xs) if xs else math.nan


def row(cells):
    """One markdown table row: "| a | b |"."""
    return "| " + " | ".join(str(c) for c in cells) + " |"


def rule(columns, align=None):
    """The markdown line under a header of `columns` cells: "---" per column, "---:" where `align` has "r"."""
    align = align or "l" * columns
    if len(align) != columns:
        raise ValueError(f"align {align!r} has {len(align)} columns, the table {columns}")
    return "|" + "".join("---:|" if a == "r" else "---|" for a in align)


def table(header, rows, align=None):
    """A markdown table: the header row, its rule (`align`: one "l" or "r" per column) and one row per item of
    `rows` (each a sequence of cells); the lines joined with newlines."""
    return "\n".join([row(header), rule(len(header), align)] + [row(r) for r in rows])
