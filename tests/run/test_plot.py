"""The plot of one run (orchestrate/plots/plot.py) for an engineer: zoomed on the contact,
patch ends and their singular values kept out of the y scale, the run's units on the
axes, the scene in the title, the summary's warnings under the axes.

Three runs, solved once (about 6 s): the steel cylinder on a hard coating in mm and MPa
(orchestrate/scenes/cylinder_mm.toml, its contact 7 % of the face), the paper's scene in
b and E, and the discrete coating (orchestrate/scenes/discrete.toml, shell model), whose
bonded patch ends lie under the contact. Tests read the drawn figure's axes, not its
pixels; the variants (warnings, no contact, an older summary) are copies of a run's
files with summary.json edited."""

import json
import shutil

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest

from orchestrate.run.answers import near_patch_ends
from orchestrate.plots.plot import plot_run, singular_ends, stresses_figure, zone_margin
from orchestrate.model.scene import Settings, scene_from_dict
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene, paper_scene
from orchestrate.run.solve import solve

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    base = tmp_path_factory.mktemp("plot")
    mm, _ = load_scene(SCENES_DIR / "cylinder_mm.toml")
    discrete, _ = load_scene(SCENES_DIR / "discrete.toml")
    scenes = {"mm": mm, "paper": paper_scene(),
              "discrete": apply_overrides(discrete, {"model": "shell"})}
    for name, scene in scenes.items():
        solve(scene, Settings(body_fields=False), base / name)
    return base


def _drawn(folder):
    """(summary, scene, the figure's axes) of the run in ``folder``."""
    summary = json.loads((folder / "summary.json").read_text())
    figure = stresses_figure(folder)
    plt.close(figure)                      # its artists stay readable
    return summary, scene_from_dict(summary["scene"]), figure.axes[0]


def _edited(runs, name, tmp_path, **changes):
    """A copy of run ``name`` whose summary.json has ``changes`` (None: key removed)."""
    folder = tmp_path / name
    shutil.copytree(runs / name, folder)
    summary = json.loads((folder / "summary.json").read_text())
    for key, value in changes.items():
        if value is None:
            summary.pop(key, None)
        else:
            summary[key] = value
    (folder / "summary.json").write_text(json.dumps(summary))
    return folder


@pytest.mark.parametrize("name", ["mm", "paper", "discrete"])
def test_the_x_range_is_the_contact_zone_and_its_margin(runs, name):
    summary, scene, axes = _drawn(runs / name)
    low, high = axes.get_xlim()
    zones = summary["contact_zones"]
    assert zones and low == 0.0                      # half models: from the axis
    end = zones[-1][1]
    margin = zone_margin(zones[-1], scene)
    # the margin's rule: the contact's half-width (a half model's zone is half of it) or
    # three coating thicknesses, whichever is larger
    thickness = max(c.thickness for c in scene.coatings)
    start = zones[-1][0]
    assert margin == pytest.approx(max(end if start == 0 else (end - start) / 2,
                                       3 * thickness))
    assert high == pytest.approx(min(end + margin, scene.base.top))
    assert high < 0.5 * scene.base.top               # zoomed: the contact, not the face


def test_the_mm_runs_view_is_its_contact_not_the_face(runs):
    summary, scene, axes = _drawn(runs / "mm")
    assert summary["contact_zones"][0][1] / scene.base.top < 0.1     # contact: 7 %
    assert axes.get_xlim()[1] == pytest.approx(summary["contact_zones"][0][1] + 0.9)  # 3 h


@pytest.mark.parametrize("name", ["mm", "paper", "discrete"])
def test_the_bond_stresses_beyond_the_view_are_small(runs, name):
    """What the margin leaves out, away from patch ends, is within an eighth of the
    bond's peak stress (normal and shear each)."""
    summary, scene, axes = _drawn(runs / name)
    low, high = axes.get_xlim()
    bond = pd.read_csv(runs / name / "interface.csv")
    away = ~near_patch_ends(scene, bond.x1.to_numpy())
    beyond = away & ((bond.x1 < low) | (bond.x1 > high)).to_numpy()
    for column in ("sigma_n", "sigma_t"):
        values = bond[column].abs().to_numpy()
        assert values[beyond].max(initial=0.0) < values[away].max() / 8


def test_values_at_bonded_ends_are_drawn_but_out_of_the_y_scale(runs):
    """The discrete coating: its contact pressure peaks at the first patch's bonded end
    (x1 = 0.5 b); away from the ends every value shown lies within the y limits."""
    summary, scene, axes = _drawn(runs / "discrete")
    low, high = axes.get_xlim()
    bottom, top = axes.get_ylim()
    shown = {"contact": pd.read_csv(runs / "discrete" / "contact.csv"),
             "bond": pd.read_csv(runs / "discrete" / "interface.csv")}
    at_ends, away = [], []
    for table in shown.values():
        in_view = table[(table.x1 >= low) & (table.x1 <= high)]
        near = near_patch_ends(scene, in_view.x1.to_numpy())
        for column in ("sigma_n", "sigma_t"):
            if column in in_view:
                at_ends.append(in_view[column].to_numpy()[near])
                away.append(in_view[column].to_numpy()[~near])
    at_ends, away = np.concatenate(at_ends), np.concatenate(away)
    assert np.all((away >= bottom) & (away <= top))
    assert at_ends.min() < 2 * bottom               # the end's pressure, cut off
    # and drawn: the curves hold the ends' values, clipped by the axes
    curves = np.concatenate([line.get_ydata() for line in axes.get_lines()
                             if len(line.get_ydata()) > 2])
    assert curves.min() == min(shown["contact"].sigma_n.min(), shown["bond"].sigma_n.min(),
                               shown["bond"].sigma_t.min()) < bottom


def test_singular_ends_are_marked_and_patches_shaded(runs):
    summary, scene, axes = _drawn(runs / "discrete")
    low, high = axes.get_xlim()
    in_view = [x1 for x1 in singular_ends(scene) if low <= x1 <= high]
    assert in_view == [0.5, 0.75, 1.25]             # 1.5 and 2.0 lie beyond the view
    vertical = [line.get_xdata()[0] for line in axes.get_lines()
                if len(set(line.get_xdata())) == 1 and line.get_linestyle() == ":"]
    assert sorted(vertical) == in_view
    assert any("bonded ends at 1.5, 2 b" in text.get_text() for text in axes.texts)
    labels = [text.get_text() for text in axes.get_legend().get_texts()]
    assert "coating patch" in labels and "patch end zone: drawn, out of the y scale" in labels


def test_the_paper_scene_has_no_singular_end_in_view(runs):
    """A half model's patch end on the axis is no singular end; the paper's other end
    (x1 = 2 b) lies beyond the view, named at its side."""
    _, scene, axes = _drawn(runs / "paper")
    assert singular_ends(scene) == [2.0]
    assert axes.get_xlim()[1] < 2.0
    assert any("bonded end at 2 b →" == text.get_text() for text in axes.texts)


def test_axes_and_title_in_the_runs_units(runs):
    _, _, axes = _drawn(runs / "mm")
    assert "(mm)" in axes.get_xlabel() and axes.get_ylabel().startswith("stress (MPa")
    title = axes.get_title()
    for part in ("cylinder R = 50 mm", "h = 0.3 mm", "E = 420 GPa", "2D model",
                 "force 1000 N/mm", "E = 210 GPa"):      # moduli below a thousand
        assert part in title
    _, _, axes = _drawn(runs / "paper")
    assert "(b)" in axes.get_xlabel() and axes.get_ylabel().startswith("stress (E")
    for part in ("parabolic indenter R = 500 b", "h = 0.125 b", "shell model", "descent"):
        assert part in axes.get_title()


def test_the_peak_pressure_and_the_bonds_largest_shear_are_marked(runs):
    summary, _, axes = _drawn(runs / "mm")
    lines = {line.get_label(): line for line in axes.get_lines()}
    marks = {quantity: next(line for label, line in lines.items() if label.startswith(start))
             for quantity, start in (("pressure", "peak pressure"),
                                     ("shear", "largest bond shear"))}
    peak = summary["answers"]["contact"]["peak_pressure"]
    shear = summary["answers"]["bonds"]["bond-coating1"]["shear"]
    assert (marks["pressure"].get_xdata()[0], marks["pressure"].get_ydata()[0]) == (
        peak["x1"], -peak["value"])
    assert marks["shear"].get_xdata()[0] == shear["x1"]
    assert abs(marks["shear"].get_ydata()[0]) == pytest.approx(shear["value"])
    assert f"{peak['value']:.4g} MPa" in marks["pressure"].get_label()


def test_warnings_are_listed_in_red_under_the_axes(runs, tmp_path):
    warnings = [{"code": "large_strain", "message": "..."},
                {"code": "coarse_contact", "message": "..."},
                {"code": "coarse_contact", "message": "another patch"}]
    _, _, axes = _drawn(_edited(runs, "mm", tmp_path, warnings=warnings))
    [text] = [t for t in axes.texts if t.get_text().startswith("warnings:")]
    assert text.get_text() == "warnings: large_strain, coarse_contact (x2)"
    assert text.get_color() == "red" and text.get_fontsize() < 8
    _, _, axes = _drawn(_edited(runs, "paper", tmp_path, warnings=[]))   # none: nothing
    assert not [t for t in axes.texts if t.get_text().startswith("warnings:")]


def test_a_run_without_contact_shows_the_whole_face(runs, tmp_path):
    _, scene, axes = _drawn(_edited(runs, "mm", tmp_path, contact_zones=[]))
    assert axes.get_xlim() == (0.0, scene.base.top)


def test_an_older_summary_is_plotted_in_b_and_E(runs, tmp_path):
    """A summary written before units, warnings and answers: b and E, no marks."""
    folder = _edited(runs, "paper", tmp_path, units=None, warnings=None, answers=None)
    path = plot_run(folder)
    assert path == str(folder / "stresses.png") and (folder / "stresses.png").stat().st_size
    _, _, axes = _drawn(folder)
    assert "(b)" in axes.get_xlabel() and "(E" in axes.get_ylabel()
