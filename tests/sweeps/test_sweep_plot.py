"""Sweeps for people: run folders named by their values (orchestrate/sweeps/run_names.py), the
table in the sweep file's order, hash-named folders of older sweeps adopted, a plot of a
sweep's table (orchestrate/plots/plot_sweep.py), and `plot` on a run that is not there.

One small sweep of the shape of `make stability` (both models over h2, one point at
another E2, one run of the paper's loop that stops at its iteration limit) is run once,
about 7 s on 2 cores; every other test reads it or needs no FreeFEM."""

import json
import os
import re
import subprocess
import sys

import matplotlib.image
import pandas as pd
import pytest

from orchestrate.errors import ParameterError
from orchestrate.model.units import force_name
from orchestrate.plots.plot import plot_run
from orchestrate.plots import plot_sweep as plot_sweep_module
from orchestrate.plots.plot_sweep import axis_label, plot_sweep, read_runs, select, split_columns
from orchestrate.sweeps.run_names import MAX_LENGTH, run_names
from orchestrate.sweeps import load_sweep, named_points, run_sweep
from tests.conftest import PROJECT_DIR

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

SWEEP = """
name = "shape"
[fixed]
eps_u = 1e-4
[grid]
model = ["shell", "elastic"]
h2 = [0.5, 0.25]
[[runs]]
model = "shell"
h2 = 0.5
E2 = 5.0
[[runs]]
model = "shell"
method = "paper"
max_iterations = 30
"""
NAMES = ["eps_u=0.0001_model=shell_h2=0.5", "eps_u=0.0001_model=shell_h2=0.25",
         "eps_u=0.0001_model=elastic_h2=0.5", "eps_u=0.0001_model=elastic_h2=0.25",
         "eps_u=0.0001_model=shell_h2=0.5_E2=5",
         "eps_u=0.0001_model=shell_method=paper_max_iterations=30"]


@pytest.fixture(scope="module")
def sweep(tmp_path_factory):
    folder = tmp_path_factory.mktemp("shape")
    (folder / "shape.toml").write_text(SWEEP)
    table = run_sweep(folder / "shape.toml", folder / "out", jobs=2,
                      stream=open(os.devnull, "w"))
    return folder / "shape.toml", folder / "out", table


def _orchestrate(*arguments):
    return subprocess.run([sys.executable, "-m", "orchestrate", *map(str, arguments)],
                          cwd=PROJECT_DIR, capture_output=True, text=True, timeout=120)


# ---- run folder names -----------------------------------------------------------------

def test_run_folders_are_named_by_their_values_in_the_files_order(tmp_path):
    path = tmp_path / "names.toml"
    path.write_text(SWEEP + '[[runs]]\nscene = "scenes/two patches.toml"\n'
                    '"coating[2].E" = 2.5\n"load.force" = 1e-3\n'
                    'rho = 0.30000000000000004\n')
    _, points = load_sweep(path)
    names = [name for name, _ in named_points(points)]
    assert names[:6] == NAMES
    # brackets dropped, unsafe characters replaced; numbers as :g writes them (six digits)
    assert names[6] == ("eps_u=0.0001_scene=scenes_two_patches.toml_coating2.E=2.5_"
                        "load.force=0.001_rho=0.3")


def test_points_whose_names_would_collide_take_a_hash_suffix():
    alone = {"scene": "a/b.toml"}
    before = run_names([alone, {"h2": 0.5}])
    after = run_names([alone, {"h2": 0.5}, {"scene": "a_b.toml"}, {"E2": 5}, {"E2": 5.0},
                       {"model": "Shell"}, {"model": "shell"}])
    assert before == ["scene=a_b.toml", "h2=0.5"]
    assert after[1] == "h2=0.5"                      # no collision: its name alone
    assert all("@" in name for name in after[:1] + after[2:])
    assert after[0].startswith("scene=a_b.toml@") and after[3].startswith("E2=5@")
    # no two points share a folder, even on a file system blind to letter case, and a
    # point never takes the folder another point had before the sweep grew
    assert len({name.casefold() for name in after}) == len(after)
    assert before[0] not in after


def test_a_long_name_is_cut_and_takes_a_suffix():
    long = [{"scene": "x" * 200, "h2": h2} for h2 in (0.5, 0.25)]
    names = run_names(long)
    assert all(len(name) == MAX_LENGTH and "@" in name for name in names)
    assert names[0] != names[1] and names[0][:100] == names[1][:100]


# ---- the table and the run folders of a sweep -----------------------------------------

def test_rows_follow_the_sweep_files_order(sweep):
    path, out, table = sweep
    assert table.id.tolist() == NAMES != sorted(NAMES)
    assert pd.read_csv(out / "runs.csv").id.tolist() == NAMES
    assert sorted(os.listdir(out / "runs")) == sorted(NAMES)
    assert table.status.tolist() == ["converged"] * 5 + ["max_iterations"]


# ---- plot-sweep -----------------------------------------------------------------------

def test_plot_sweep_draws_an_output_against_a_parameter_per_model(sweep):
    _, out, _ = sweep
    result = _orchestrate("plot-sweep", out, "--y", "peak_contact_stress", "--x", "h2",
                          "--by", "model")
    assert result.returncode == 0, result.stderr
    png = out / "peak_contact_stress-h2-model.png"
    assert result.stdout.strip() == str(png)
    height, width, _ = matplotlib.image.imread(png).shape
    assert width > 600 and height > 400
    # the paper's loop's run has no peak; the run at E2 = 5 is a line of its own
    assert ("1 run(s) without peak_contact_stress left out (status: max_iterations)"
            in result.stderr)
    assert "lines split also by E2" in result.stderr


def test_lines_split_only_by_what_tells_runs_apart(sweep):
    _, out, _ = sweep
    table = read_runs(out).dropna(subset=["peak_contact_stress"])
    assert split_columns(table, "h2", "model") == ["E2"]     # not also coating[1].E
    assert split_columns(select(table, ["E2=1"]), "h2", "model") == []
    assert len(select(table, ["model=shell", "h2=0.5"])) == 2


@pytest.mark.parametrize("arguments, named", [
    (["--y", "peak_stress", "--x", "h2"], "--y peak_stress"),
    (["--y", "iterations", "--x", "h2", "--by", "colour"], "--by colour"),
    (["--y", "iterations", "--x", "h2", "--where", "E2=3"], "--where E2=3"),
])
def test_plot_sweep_names_a_column_it_cannot_use_in_one_line(sweep, arguments, named):
    _, out, _ = sweep
    result = _orchestrate("plot-sweep", out, *arguments)
    assert result.returncode == 2
    assert len(result.stderr.strip().splitlines()) == 1 and "Traceback" not in result.stderr
    assert result.stderr.startswith(f"error: {named}")
    if "where" not in named:
        assert "columns: id, eps_u, model, h2" in result.stderr
    else:
        assert "E2 takes 1, 5" in result.stderr


@pytest.fixture
def drawn_labels(monkeypatch):
    """The (x, y) axis labels of every figure plot_sweep draws, in order."""
    labels = []
    draw = plot_sweep_module.draw

    def recording(*arguments, **options):
        figure = draw(*arguments, **options)
        labels.append((figure.axes[0].get_xlabel(), figure.axes[0].get_ylabel()))
        return figure
    monkeypatch.setattr(plot_sweep_module, "draw", recording)
    return labels


def _in_units(table, tmp_path, length="mm", stress="MPa"):
    """runs.csv of ``table`` with its runs' units renamed (the numbers are as they are:
    the labels are under test); return its folder."""
    table = table.copy()
    table["units.length"], table["units.stress"] = length, stress
    table["units.force"] = force_name(stress, length)    # a plane-strain run's
    table.to_csv(tmp_path / "runs.csv", index=False)
    return tmp_path


def test_plot_sweep_labels_its_axes_in_b_and_E_for_a_dimensionless_sweep(sweep,
                                                                        drawn_labels):
    _, out, _ = sweep
    plot_sweep(out, "peak_contact_stress", "h2", by="model", out=out / "labels.png")
    assert drawn_labels == [("h2 (b)", "peak_contact_stress (E)")]


@pytest.mark.parametrize("x, y, labels", [
    ("h2", "peak_contact_stress", ("h2 (mm)", "peak_contact_stress (MPa)")),
    ("coating[1].thickness", "bond-coating1.shear",
     ("coating[1].thickness (mm)", "bond-coating1.shear (MPa)")),
    ("E2", "bond-coating1.shear_x1", ("E2 (MPa)", "bond-coating1.shear_x1 (mm)")),
    ("h2", "total_force", ("h2 (mm)", "total_force (N/mm)")),
    ("h2", "iterations", ("h2 (mm)", "iterations")),            # a count: no unit
    ("model", "coating1.von_mises", ("model", "coating1.von_mises (MPa)")),
])
def test_plot_sweep_labels_its_axes_in_the_runs_units(sweep, tmp_path, drawn_labels, x, y,
                                                      labels):
    _, out, table = sweep
    folder = _in_units(table, tmp_path)
    plot_sweep(folder, y, x, where=["E2=1"] if x != "E2" else [], out=tmp_path / "p.png")
    assert drawn_labels == [labels]


def test_a_table_without_units_is_in_b_and_E(sweep):
    table = read_runs(sweep[1]).drop(columns=["units.length", "units.stress"],
                                     errors="ignore")
    assert axis_label(table, "coating[1].E") == "coating[1].E (E)"
    assert axis_label(table, "descent") == "descent (b)"
    assert axis_label(table, "theta") == "theta (b/E)"      # a setting: b and E always


def test_runs_in_different_units_are_refused_on_a_shared_axis(sweep, tmp_path):
    _, _, table = sweep
    mixed = table.copy()
    mixed["units.length"] = ["mm"] * 3 + ["b"] * (len(table) - 3)
    mixed.to_csv(tmp_path / "runs.csv", index=False)
    with pytest.raises(ParameterError, match=r"different units \(units.length: mm, b\): pick "
                       r"one with --where units.length=mm"):
        plot_sweep(tmp_path, "peak_contact_stress", "h2", out=tmp_path / "p.png")
    # picked: the label has its unit
    path, _ = plot_sweep(tmp_path, "peak_contact_stress", "h2", where=["units.length=mm"],
                         out=tmp_path / "p.png")
    assert os.path.exists(path)


# ---- plot of one run ------------------------------------------------------------------

def _run_folder(tmp_path, summary):
    folder = tmp_path / "run"
    folder.mkdir()
    if summary is not None:
        (folder / "summary.json").write_text(json.dumps(summary))
    return folder


@pytest.mark.parametrize("summary, says", [
    ("missing", "no such folder"),
    (None, "holds no finished run (no summary.json)"),
    ({"status": "stagnated", "converged": False, "reason": "no progress"},
     "did not converge (stagnated: no progress)"),
    ({"status": "error", "converged": False, "reason": "worker killed\nmore"},
     "the run failed: worker killed;"),
])
def test_plot_of_a_run_that_is_not_there_says_so(tmp_path, summary, says):
    folder = tmp_path / "run" if summary == "missing" else _run_folder(tmp_path, summary)
    with pytest.raises(ParameterError, match="^" + re.escape(str(folder))) as error:
        plot_run(folder)
    assert says in str(error.value) and "\n" not in str(error.value)


def test_plot_on_a_missing_run_is_one_line_and_a_refusal(tmp_path):
    result = _orchestrate("plot", tmp_path / "nothing")
    assert result.returncode == 2
    assert result.stderr == f"error: {tmp_path / 'nothing'}: no such folder\n"
