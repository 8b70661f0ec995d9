"""The studies' reports: each study that measures something writes, beside its CSV, a
short markdown file into results/ (results/hertz.md beside results/hertz.csv, say): its
tables, formatted from the data it measured, with what every column means and its unit,
and the sentences of finding computed from that data. docs/ explains and links them; it
types none of their numbers.

    report = Report("A cylinder on a block against Hertz", "python -m studies.hertz")
    report.text("Errors against plane-strain Hertz, mesh level 1.")
    report.table(rows, [Column("size", "W (b)", "{:g}", "both bodies' width and height"),
                        Column("peak_error", "peak", percent, "peak pressure / Hertz's - 1")])
    report.finding(f"the error falls like (a/W)^{slope:.2f}")
    report.write(RESULTS_DIR / "hertz.md")
"""

from dataclasses import dataclass
import math
import os
from pathlib import Path
import shlex
import sys
from typing import Callable, Union

import numpy as np
import pandas as pd

from orchestrate.files import written


# ---- numbers as the reports write them ----------------------------------------------------

def _missing(value):
    return value is None or (isinstance(value, float) and math.isnan(value))


def percent(value, digits=2, signed=False):
    """A fraction as a percentage: 0.0123 -> '1.23 %' ('+1.23 %' if signed); '' if
    missing."""
    if _missing(value):
        return ""
    return f"{100 * value:{'+' if signed else ''}.{digits}f} %"


def signed_percent(value, digits=2):
    return percent(value, digits, signed=True)


def percent_g(value, digits=2):
    """A fraction as a percentage to ``digits`` significant digits: 3.1e-5 -> '0.0031 %'."""
    return "" if _missing(value) else f"{100 * value:.{digits}g} %"


def significant(value, digits=3):
    """A number to ``digits`` significant digits ('' if missing)."""
    return "" if _missing(value) else f"{value:.{digits}g}"


def seconds(value):
    return "" if _missing(value) else f"{value:.2f} s"


def span(values, show=significant):
    """'low-high' of some numbers ('low' when they are equal); '' if none."""
    values = [v for v in values if not _missing(v)]
    if not values:
        return ""
    low, high = show(min(values)), show(max(values))
    return low if low == high else f"{low}-{high}"


def listing(items):
    """'a, b and c'."""
    items = [str(item) for item in items]
    return ", ".join(items[:-1]) + " and " + items[-1] if len(items) > 1 else "".join(items)


def fraction_of_b(value):
    """A length in b as the paper writes it: 'b', 'b/8', '2 b', '0.35 b'."""
    if value == 1:
        return "b"
    if value < 1 and abs(1 / value - round(1 / value)) < 1e-9:
        return f"b/{round(1 / value)}"
    return f"{value:g} b"


def fraction_of_E(value):
    """A modulus in E: 'E', 'E/5', '5E', '0.3 E'."""
    if value == 1:
        return "E"
    if value < 1 and abs(1 / value - round(1 / value)) < 1e-9:
        return f"E/{round(1 / value)}"
    if value == round(value):
        return f"{value:g}E"
    return f"{value:g} E"


def progress_to_stderr(text):
    """A study's progress line: on stderr, for stdout carries its table."""
    print(text, file=sys.stderr)


def print_table(table):
    """A study's table on stdout, each row on one wide line."""
    with pd.option_context("display.width", 250, "display.max_columns", 40):
        print(table.to_string(index=False))


def save_table(table, path):
    """A study's table as CSV at ``path`` (its folder made), whole or not at all."""
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    written(path, lambda partial: table.to_csv(partial, index=False))


def report_beside(table_path):
    """The path of the report written beside a study's CSV (x.csv -> x.md)."""
    return os.path.splitext(table_path)[0] + ".md"


def command_line(module, argv=None):
    """The command a study was run with, for its report: 'python -m MODULE ARGS'."""
    arguments = sys.argv[1:] if argv is None else list(argv)
    return " ".join(["python -m", module] + [shlex.quote(str(a)) for a in arguments])


# ---- tables -------------------------------------------------------------------------------

@dataclass(frozen=True)
class Column:
    """A column of a report's table: ``key`` a field of each row (or a function of the
    row), its ``header`` (with its unit), ``show`` a format string or a function of the
    value, and what it means (listed under the table)."""
    key: Union[str, Callable]
    header: str
    show: Union[str, Callable] = "{}"
    meaning: str = ""

    def cell(self, row):
        value = self.key(row) if callable(self.key) else row.get(self.key)
        if callable(self.show):
            return str(self.show(value))
        return "" if _missing(value) else self.show.format(value)


def _rows(rows):
    """A DataFrame's rows as Series, or the dicts as they are (both have .get)."""
    if hasattr(rows, "iterrows"):
        return [row for _, row in rows.iterrows()]
    return list(rows)


def markdown_table(rows, columns):
    """A markdown table of ``rows`` (a DataFrame, or dicts) in ``columns``, then a list of
    what each column means (those that say)."""
    lines = ["| " + " | ".join(c.header for c in columns) + " |",
             "|" + "---|" * len(columns)]
    for row in _rows(rows):
        lines.append("| " + " | ".join(c.cell(row).replace("|", "\\|") for c in columns)
                     + " |")
    meanings = [f"- {c.header}: {c.meaning}" for c in columns if c.meaning]
    return "\n".join(lines) + ("\n\n" + "\n".join(meanings) if meanings else "")


# ---- the report ---------------------------------------------------------------------------

class Report:
    """A study's report, built part by part and written at once (whole or not at all)."""

    def __init__(self, title, command, data=()):
        self.title, self.command, self.data = title, command, list(data)
        self.parts = []

    def section(self, heading):
        self.parts.append(f"## {heading}")

    def text(self, text):
        self.parts.append(text)

    def finding(self, text):
        """A sentence that follows from the data (computed by the study)."""
        self.parts.append(f"**Finding.** {text}")

    def table(self, rows, columns):
        self.parts.append(markdown_table(rows, columns))

    def markdown(self):
        source = (f" from {listing(f'`{name}`' for name in self.data)}" if self.data else "")
        head = (f"# {self.title}\n\nWritten by `{self.command}`{source}; generated, not "
                "edited: run it again for the current values.")
        return "\n\n".join([head] + self.parts) + "\n"

    def write(self, path):
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        written(path, lambda partial: Path(partial).write_text(self.markdown()))
        return path


def power_fit(x, y):
    """(C, k) of |y| = C x^k, least squares on the logarithms (needs two points)."""
    x, y = np.asarray(x, float), np.abs(np.asarray(y, float))
    k, log_c = np.polyfit(np.log(x), np.log(y), 1)
    return float(np.exp(log_c)), float(k)


def proportional_fit(x, y):
    """C of y = C x, least squares through the origin."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    return float(np.dot(x, y) / np.dot(x, x))
