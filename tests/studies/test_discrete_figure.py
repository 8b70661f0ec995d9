"""The discrete-coating figure (make discrete): both coating models over the patches of
orchestrate/scenes/discrete.toml, drawn from their CSV files.

Physics the figure shows and a test can check: the stiff patch under the cylinder
carries the load to its bonded end, where both models concentrate the contact pressure
(the edge of a stiff patch pressed by a softer indenter; singular in the 2D model); the
bare base between patches stays out of contact (the cylinder's sag over the gap, 0.014 b,
is below the patches' thickness, 0.125 b); and away from the ends both models agree
(measured: the bond's normal stress under the middle of the central patch differs by
0.65 % between the models; the end's contact pressure is 3.5 (shell) and 2.7 (2D)
times the centre's).

The command writes where --out says (the PNG, its PDF and data beside it), discrete.png
in the current folder by default, never the repository's results/ unless asked; its axes
are in the runs' units, and runs of different units or scenes are refused."""

import json
import os
import shutil

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest

from orchestrate.plots.discrete_figure import draw, figure, load, main, singular_ends
from studies.paths import RESULTS_DIR
from orchestrate.model.scene import Settings, to_dict
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene
from orchestrate.run.solve import solve

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    base = tmp_path_factory.mktemp("discrete")
    scene, _ = load_scene(SCENES_DIR / "discrete.toml")
    folders = []
    for model in ("shell", "elastic"):
        solve(apply_overrides(scene, {"model": model}), Settings(body_fields=False),
              base / model)
        folders.append(str(base / model))
    figure(folders, base / "figure" / "discrete.png")
    return scene, base / "figure", pd.read_csv(base / "figure" / "discrete_data.csv")


@pytest.fixture
def folders(drawn):
    return [str(drawn[1].parent / model) for model in ("shell", "elastic")]


def test_the_figure_and_its_data_are_written(drawn):
    scene, out, data = drawn
    assert sorted(os.listdir(out)) == ["discrete.pdf", "discrete.png", "discrete_data.csv"]
    assert set(data.model) == {"shell", "elastic"}
    assert set(data.quantity) == {"contact sigma_n", "bond sigma_n", "bond sigma_t"}


def _results_state():
    """What the repository's results/ holds of the figure: (name, mtime) of each."""
    return {name: os.stat(RESULTS_DIR / name).st_mtime_ns
            for name in ("discrete.png", "discrete.pdf", "discrete_data.csv")
            if (RESULTS_DIR / name).exists()}


def test_the_command_writes_where_out_says_and_nowhere_else(folders, tmp_path, monkeypatch,
                                                          capsys):
    before = _results_state()
    here = tmp_path / "here"
    here.mkdir()
    monkeypatch.chdir(here)
    main([*folders, "--out", str(tmp_path / "mine" / "models.png")])
    assert capsys.readouterr().out.strip() == str(tmp_path / "mine" / "models.png")
    assert sorted(os.listdir(tmp_path / "mine")) == ["models.pdf", "models.png",
                                                     "models_data.csv"]
    assert os.listdir(here) == []
    main(folders)                                   # the default: the current folder
    assert sorted(os.listdir(here)) == ["discrete.pdf", "discrete.png", "discrete_data.csv"]
    assert _results_state() == before               # the repository's untouched


def test_out_must_name_a_png_file(folders, tmp_path):
    with pytest.raises(SystemExit, match="give the PNG file's path"):
        main([*folders, "--out", str(tmp_path)])
    assert os.listdir(tmp_path) == []


def _copy(folder, tmp_path, name, edit):
    """A copy of a run folder whose summary.json ``edit`` changed."""
    copy = tmp_path / name
    shutil.copytree(folder, copy)
    summary = json.loads((copy / "summary.json").read_text())
    edit(summary)
    (copy / "summary.json").write_text(json.dumps(summary))
    return str(copy)


def _in_mm(summary):
    summary["units"].update(length="mm", stress="MPa", force="MPa mm (per unit width)")


def _labels(folders):
    plot, _ = draw([load(folder) for folder in folders])
    plt.close(plot)
    return [axis.get_ylabel() for axis in plot.axes], plot.axes[-1].get_xlabel(), \
        plot.get_suptitle()


def test_the_axes_are_in_the_runs_units(folders, tmp_path):
    ylabels, xlabel, title = _labels(folders)
    assert all(label.endswith("(E)") for label in ylabels) and xlabel.startswith("$x_1$ (b)")
    assert "R = 20 b" in title and "E b per unit width" in title
    in_mm = [_copy(folder, tmp_path, model, _in_mm)
             for folder, model in zip(folders, ("shell", "elastic"))]
    ylabels, xlabel, title = _labels(in_mm)
    assert all(label.endswith("(MPa)") for label in ylabels)
    assert xlabel.startswith("$x_1$ (mm)")
    assert "R = 20 mm" in title and "MPa mm per unit width" in title


@pytest.mark.parametrize("edit, says", [
    (_in_mm, "is in mm/MPa, {first} in b/E: the figure compares runs in the same units"),
    (lambda summary: summary["scene"]["indenter"].update(radius=30.0),
     "and {first} are runs of different scenes"),
])
def test_runs_of_other_units_or_scenes_are_refused(folders, tmp_path, edit, says):
    other = _copy(folders[1], tmp_path, "other", edit)
    with pytest.raises(SystemExit) as refusal:
        main([folders[0], other, "--out", str(tmp_path / "refused.png")])
    assert str(refusal.value).startswith(other)
    assert says.format(first=folders[0]) in str(refusal.value)
    assert not (tmp_path / "refused.png").exists()


def test_the_singular_ends_are_the_bonded_ends_off_the_axis(drawn):
    scene = drawn[0]
    assert singular_ends(to_dict(scene)) == [0.5, 0.75, 1.25, 1.5, 2.0]


@pytest.mark.parametrize("model", ["shell", "elastic"])
def test_the_contact_pressure_peaks_at_the_first_patchs_end(drawn, model):
    data = drawn[2]
    first = data[(data.model == model) & (data.interface == "contact-coating1")]
    assert first.value.idxmax() == first.x1.idxmax()           # at x1 = 0.5
    assert first.value.max() > 2 * first.value.iloc[0]          # well above the centre's


def test_the_bare_base_between_patches_is_out_of_contact(drawn):
    data = drawn[2]
    bare = data[data.interface.str.startswith("contact-base")]
    assert np.all(bare.value == 0)


def test_both_models_agree_away_from_the_ends(drawn):
    data = drawn[2]
    centre = data[(data.interface == "bond-coating1") & (data.quantity == "bond sigma_n")
                  & (data.x1 < 0.25)]
    shell = centre[centre.model == "shell"].value.to_numpy()
    elastic = centre[centre.model == "elastic"].value.to_numpy()
    assert np.max(np.abs(shell - elastic)) < 0.01 * np.max(np.abs(elastic))
