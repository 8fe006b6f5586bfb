"""The summary a batch prints at its end: aligned text, Markdown or CSV."""

from __future__ import annotations

import csv
import io

from foon2asp.report.registry import register
from foon2asp.tree.results import BatchReport

_COLUMNS = (
    "method results statuses trees valid units_min units_median units_mean units_max time_total_s time_median_ms"
).split()


def _cell(value) -> str:
    if value is None:
        return "-"
    if isinstance(value, dict):
        return " ".join(f"{k}={v}" for k, v in value.items())
    return str(value)


def render_summary(rows: list[dict], fmt: str = "text", report: BatchReport | None = None) -> str:
    """The summary as aligned text, a Markdown table or CSV."""
    if fmt == "csv":
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(_COLUMNS)
        for row in rows:
            writer.writerow([_cell(row[c]) for c in _COLUMNS])
        return buf.getvalue()
    table = [[_cell(row[c]) for c in _COLUMNS] for row in rows]
    head = ""
    if report is not None:
        head = (
            f"{report.done} new result(s), {report.skipped} already done, "
            f"{report.elapsed_s:.2f} s with {report.workers} worker(s)"
            + (f"; results in {report.output}" if report.output else "")
            + (f"\ngrounding: {report.grounding}" if report.grounding else "")
            + (f" (auto: {report.grounding_reason})" if report.grounding_reason else "")
            + "\n"
        )
    if fmt == "markdown":
        lines = ["| " + " | ".join(_COLUMNS) + " |", "|" + "---|" * len(_COLUMNS)]
        lines += ["| " + " | ".join(r) + " |" for r in table]
        return (head + "\n" if head else "") + "\n".join(lines) + "\n"
    widths = [max(len(c), *(len(r[i]) for r in table)) if table else len(c) for i, c in enumerate(_COLUMNS)]
    lines = ["  ".join(c.ljust(w) for c, w in zip(_COLUMNS, widths)).rstrip()]
    lines += ["  ".join(v.ljust(w) for v, w in zip(r, widths)).rstrip() for r in table]
    return head + "\n".join(lines) + "\n"


for _fmt, _ext, _what in (
    ("text", "txt", "aligned table"),
    ("markdown", "md", "Markdown table"),
    ("csv", "csv", "CSV"),
):
    register("summary", _fmt, _ext, f"per-method counts and sizes as {_what}")(
        lambda rows, report=None, _f=_fmt: render_summary(rows, _f, report)
    )
