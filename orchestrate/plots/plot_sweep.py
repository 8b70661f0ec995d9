"""Plot of a sweep: one column of its runs.csv against another, one line per value of a
third (``python -m orchestrate plot-sweep SWEEP_DIR --y peak_contact_stress --x h2 --by
model``).

Reads only runs.csv, so a plot never recomputes anything. Rows are picked with ``--where
KEY=VALUE``; runs without a value of y (those that did not converge) are left out, and
said so. Where runs that share x and the line's value still differ in other parameters
(a sweep of several grids: E2, or the loop's settings), the line is split by those too
and its label names them, so that no line joins runs of different scenes. Each axis
names its column's unit (``column_unit``): the column's kind (a length, a stress, ...:
orchestrate/model/units.py) in the runs' units (runs.csv's units.* columns; b and E without
them)."""

import difflib
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

from orchestrate.errors import ParameterError  # noqa: E402
from orchestrate.sweeps.run_names import UNSAFE  # noqa: E402
from orchestrate.model.scene_file import SHORTHANDS  # noqa: E402
from orchestrate.sweeps import OUTCOME_COLUMNS  # noqa: E402
from orchestrate.model.units import (DEGREES, FORCE, KINDS, LENGTH, SCENE_KINDS,  # noqa: E402
                                     SECONDS, STRESS, force_label, force_name)

NOT_PARAMETERS = {"id", *OUTCOME_COLUMNS}  # a run's name and outcome: never split by
LEGEND_INSIDE = 8                          # more lines than this: the legend goes aside
# (line style, marker) of the lines of one colour, told apart by the split parameters
STYLES = [(line, marker) for marker in "osv^Dx" for line in ("-", "--", ":", "-.")]
# the answers' columns (orchestrate/sweeps/sweep.py): stresses, and their positions x1
ANSWER = re.compile(r"^(peak_pressure|(bond-[^.]+|coating\d+)\.\w+)$")
SETTING_UNITS = {"element_size": "b", "theta": "b/E", "robin": "E/b",  # b and E always
                 "worker_timeout": "s", "memory_limit": "GiB"}


def read_runs(sweep_dir):
    """The sweep's runs.csv (SWEEP_DIR, or the CSV file itself) as a table."""
    is_csv = str(sweep_dir).endswith(".csv")
    path = sweep_dir if is_csv else os.path.join(sweep_dir, "runs.csv")
    if not os.path.exists(sweep_dir):
        raise ParameterError(f"{sweep_dir}: no such folder")
    if not os.path.isfile(path):
        raise ParameterError(f"{sweep_dir} holds no runs.csv (is it a sweep's folder? "
                             "`python -m orchestrate sweep FILE` writes it)")
    try:
        table = pd.read_csv(path)
    except (OSError, ValueError, pd.errors.EmptyDataError) as error:
        raise ParameterError(f"{path}: not a readable table ({error})") from None
    if table.empty:
        raise ParameterError(f"{path} has no runs yet")
    return table


def check_column(table, name, option):
    """ParameterError naming ``name`` unless it is a column of runs.csv."""
    if name in table.columns:
        return
    close = difflib.get_close_matches(name, table.columns, n=1)
    hint = f"did you mean {close[0]}? " if close else ""
    raise ParameterError(f"{option} {name}: runs.csv has no such column; {hint}columns: "
                         + ", ".join(table.columns))


def matching(column, text):
    """Which cells of ``column`` equal ``text`` (numbers to 1e-9 relative; "" or "nan":
    an empty cell)."""
    if text.strip().lower() in ("", "nan"):
        return column.isna()
    if pd.api.types.is_bool_dtype(column):
        return column == (text.strip().lower() in ("true", "1"))
    if pd.api.types.is_numeric_dtype(column):
        try:
            value = float(text)
        except ValueError:
            raise ParameterError(f"--where {column.name}={text}: {column.name} holds "
                                 "numbers") from None
        return pd.Series(np.isclose(column, value, rtol=1e-9, atol=0), index=column.index)
    return column.astype(str) == text


def select(table, where):
    """The rows that match every KEY=VALUE of ``where``."""
    for condition in where:
        key, sep, text = condition.partition("=")
        if not sep:
            raise ParameterError(f"--where {condition!r} must read KEY=VALUE")
        check_column(table, key, "--where")
        picked = table[matching(table[key], text)]
        if picked.empty:
            raise ParameterError(f"--where {condition}: no run left with it ({key} takes "
                                 f"{_values_text(table[key])})")
        table = picked
    return table


def _values_text(column):
    values = column.drop_duplicates().tolist()
    shown = ", ".join(f"{v:g}" if isinstance(v, float) else str(v) for v in values[:12])
    return shown + (", ..." if len(values) > 12 else "")


def _statuses(rows):
    return f" (status: {_values_text(rows['status'])})" if "status" in rows else ""


def column_kind(name):
    """The kind of a runs.csv column (LENGTH, STRESS, ... of orchestrate/model/units.py), or
    None: an answer (a stress, its _x1 a length), a scene key (``coating[1].E``), a
    shorthand of the paper's (h2: coating.thickness), any other output by its name."""
    position = re.match(r"^(.*)_x[12]$", name)
    if position and ANSWER.match(position.group(1)):
        return LENGTH
    if ANSWER.match(name):
        return STRESS
    if name in SHORTHANDS and name != "chi":          # chi: an inverse length
        name = SHORTHANDS[name][1][0]
    table, _, field = re.sub(r"\[\d+\]", "", name).partition(".")
    if field:
        return SCENE_KINDS.get(table, {}).get(field)
    return KINDS.get(name)


def _one_unit(table, column, default):
    """The one value of column ``units.KIND`` among the runs; ParameterError if they
    differ (their numbers do not share an axis)."""
    if column not in table:
        return default                    # runs older than units: b and E
    values = table[column].dropna().astype(str).unique().tolist()
    if len(values) > 1:
        raise ParameterError(f"the runs are in different units ({column}: "
                             f"{', '.join(values)}): pick one with --where "
                             f"{column}={values[0]}")
    return values[0] if values else default


def column_unit(table, name):
    """The unit of column ``name`` in the runs of ``table``, as a person writes it; None
    for a plain number or a column of unknown kind."""
    if name in SETTING_UNITS:
        return SETTING_UNITS[name]
    if name == "chi":
        return f"1/{_one_unit(table, 'units.length', 'b')}"
    kind = column_kind(name)
    if kind in (LENGTH, STRESS):
        return _one_unit(table, f"units.{kind}", {LENGTH: "b", STRESS: "E"}[kind])
    if kind == FORCE:
        length = _one_unit(table, "units.length", "b")
        stress = _one_unit(table, "units.stress", "E")
        force = _one_unit(table, "units.force", force_name(stress, length))
        return force_label(force)
    return {SECONDS: "s", DEGREES: "degree"}.get(kind)


def axis_label(table, name):
    """``h2 (mm)``; the name alone where the column has no unit."""
    unit = column_unit(table, name)
    return f"{name} ({unit})" if unit else name


def split_columns(table, x, by):
    """The other parameters that tell apart runs sharing x (and the line's value): the
    first in the table's order of each set of columns that vary together (E2, not also
    coating[1].E)."""
    keys = [x] + ([by] if by else [])
    split = []
    for column in table.columns:
        if column in NOT_PARAMETERS or column in keys:
            continue
        if table.groupby(keys + split, dropna=False, sort=False)[column].nunique(
                dropna=False).max() > 1:
            split.append(column)
    return split


def _label(table, columns, values):
    """A line's label: each column's value, with its unit (``load.force=5 N``)."""
    def one(column, value):
        unit = column_unit(table, column)
        text = f"{value:g}" if isinstance(value, float) else f"{value}"
        return f"{column}={text}" + (f" {unit}" if unit else "")
    return ", ".join(one(column, value) for column, value in zip(columns, values))


def plot_sweep(sweep_dir, y, x, by=None, where=(), out=None, log_x=False, log_y=False):
    """Draw column y of runs.csv against column x, one line per value of ``by`` (and of
    any other parameter that tells runs apart); return (the PNG's path, notes to show)."""
    table = read_runs(sweep_dir)
    for name, option in ((y, "--y"), (x, "--x"), (by, "--by")):
        if name is not None:
            check_column(table, name, option)
    table = select(table, where)
    notes = []
    missing = table[y].isna()
    if missing.all():
        raise ParameterError(f"--y {y}: no selected run has a value{_statuses(table)}")
    if missing.any():
        notes.append(f"{missing.sum()} run(s) without {y} left out"
                     + _statuses(table[missing]))
    table = table[~missing]
    if not pd.api.types.is_numeric_dtype(table[y]):
        raise ParameterError(f"--y {y} holds no numbers (values: {_values_text(table[y])})")
    split = split_columns(table, x, by)
    if split:
        shared = x + (f" and {by}" if by else "")
        notes.append(f"lines split also by {', '.join(split)} (runs with the same {shared} "
                     "differ in them); pick with --where KEY=VALUE")
    folder = os.path.dirname(sweep_dir) if str(sweep_dir).endswith(".csv") else sweep_dir
    title = os.path.basename(os.path.abspath(folder)) + (f" ({', '.join(where)})" if where
                                                         else "")
    figure = draw(table, y, x, ([by] if by else []) + split, title, log_x, log_y,
                  x_label=axis_label(table, x), y_label=axis_label(table, y))
    out = out or os.path.join(folder, _file_name(y, x, by, where))
    try:
        figure.savefig(out, dpi=150, bbox_inches="tight")
    except OSError as error:
        raise ParameterError(f"--out {out}: cannot write it ({error.strerror})") from None
    except ValueError as error:                    # an extension matplotlib cannot write
        raise ParameterError(f"--out {out}: {error}") from None
    finally:
        plt.close(figure)
    return out, notes


def draw(table, y, x, line_keys, title, log_x=False, log_y=False, x_label=None,
         y_label=None):
    """The figure: y against x, a line per values of ``line_keys``, a colour per value
    of the first, a line style per values of the others; the axes labelled ``x_label``,
    ``y_label`` (default: the column names)."""
    figure, axes = plt.subplots(figsize=(6.4, 4.2))
    groups = (table.groupby(line_keys, dropna=False, sort=False) if line_keys
              else [((), table)])
    numeric_x = pd.api.types.is_numeric_dtype(table[x])
    colours, styles = {}, {}
    lines = 0
    for values, rows in groups:
        values = values if isinstance(values, tuple) else (values,)
        colour = colours.setdefault(values[:1], f"C{len(colours) % 10}")
        line, marker = styles.setdefault(values[1:], STYLES[len(styles) % len(STYLES)])
        rows = rows.sort_values(x, kind="stable") if numeric_x else rows
        axes.plot(rows[x] if numeric_x else rows[x].astype(str), rows[y], linestyle=line,
                  marker=marker, markersize=4, color=colour,
                  label=_label(table, line_keys, values) if line_keys else None)
        lines += 1
    if log_x:
        axes.set_xscale("log")
    if log_y:
        axes.set_yscale("log")
    axes.set_xlabel(x_label or x)
    axes.set_ylabel(y_label or y)
    axes.set_title(title)
    if not line_keys:
        figure.tight_layout()
    elif lines <= LEGEND_INSIDE:
        axes.legend(fontsize="small")
        figure.tight_layout()
    else:                          # beside the axes: the saved figure widens to hold it
        axes.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(1.02, 1.0))
    return figure


def _file_name(y, x, by, where):
    """peak_contact_stress-h2-model.png; --where conditions appended."""
    return UNSAFE.sub("", "-".join([y, x] + ([by] if by else []) + list(where))) + ".png"
