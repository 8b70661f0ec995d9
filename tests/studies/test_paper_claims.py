"""The paper's claims about its figures 3-5 (METHOD.md), checked on our runs.

Every figure scene is solved (24 runs, both coating models, the default paper meshes)
by what `make fig3 fig4 fig5` runs, which draws the three figures too, and each claim
becomes an assertion on the computed data: an ordering, a trend, the place of a maximum
(studies/claims.py measures them). Where our data contradict a claim, the test
asserts what the data show and says why; results/claims.md (studies/claims.py) gives the
numbers."""

import itertools
import json
import shutil
import subprocess
import sys
import time

import pandas as pd
import pytest

from studies.claims import Runs, distance, left_edge, local_maxima, maximum
from studies.figure_sweep import (FIGURE_FILES, STAGING, FigureDrawing, figure_runs,
                                      ready_figures)
from studies.figure_scenes import FIGURE_HEIGHTS, FIGURE_SCENES
from studies.paths import FIGURE_SWEEP
from orchestrate.workers.provenance import forms_digest
from orchestrate.sweeps import load_sweep, named_points
from tests.conftest import PROJECT_DIR

pytestmark = pytest.mark.slow       # not in the everyday subset (make test-fast)

HEIGHTS = FIGURE_HEIGHTS
BOND_SHEAR_CODES = ("bond_shear_model", "coarse_bond")   # of the bond's shear, not the claims'


@pytest.fixture(scope="module")
def figures(tmp_path_factory):
    """The folder `python -m studies.figure_sweep --out` filled: the figure sweep's runs
    (figures/) and the three figures."""
    out = tmp_path_factory.mktemp("figures")
    done = subprocess.run([sys.executable, "-m", "studies.figure_sweep", "--out", str(out)],
                          cwd=PROJECT_DIR, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return out


@pytest.fixture(scope="module")
def runs(figures):
    return Runs([str(figures / "figures")])


def test_the_figures_command_draws_the_three_figures_from_its_sweep(figures):
    """Every figure whole (PNG, PDF, data), drawn beside the sweep; nothing partial."""
    for name in ("fig3", "fig4", "fig5"):
        assert (figures / f"{name}.png").stat().st_size > 10_000
        assert (figures / f"{name}.pdf").read_bytes().rstrip().endswith(b"%%EOF")
        assert (figures / f"{name}_data.csv").is_file()
    assert not list(figures.glob("*partial*"))
    assert (figures / "figures" / "runs.csv").is_file()
    curves = {name: pd.read_csv(figures / f"{name}_data.csv") for name in ("fig3", "fig4")}
    assert curves["fig3"].groupby(["h2", "E2", "model"]).ngroups == 8
    assert curves["fig4"].groupby(["h2", "E2", "model"]).ngroups == 20
    assert pd.read_csv(figures / "fig5_data.csv").groupby(["h2", "E2"]).ngroups == 12


# The peak contact stress (E) of every figure scene, computed once by the figure sweep at
# the commit that split the tool into layers. On the paper's mesh each contact set is
# solved directly (exact to rounding), so a run gives its scene's peak whatever neighbour
# it started from: these hold to 1e-9. A change of the forms, the mesh or the penalty
# moves them, and must say so here.
PINNED_PEAKS = {
    ('elastic', 1.0, 5.0): -0.0006640651475707704,
    ('elastic', 1.0, 1.0): -0.0005153756463449589,
    ('elastic', 1.0, 0.2): -0.0003009810031214424,
    ('elastic', 0.5, 5.0): -0.0005981363010512989,
    ('elastic', 0.5, 1.0): -0.0005198776982315847,
    ('elastic', 0.5, 0.2): -0.0003768382455058899,
    ('elastic', 0.25, 5.0): -0.0005519517660319219,
    ('elastic', 0.25, 1.0): -0.0005225383380149978,
    ('elastic', 0.25, 0.2): -0.0004374113841523184,
    ('elastic', 0.125, 5.0): -0.0005392035499187096,
    ('elastic', 0.125, 1.0): -0.0005238859208096455,
    ('elastic', 0.125, 0.2): -0.00047647803731593725,
    ('elastic', 0.0625, 5.0): -0.0005337589225372183,
    ('elastic', 0.0625, 1.0): -0.0005243849102484939,
    ('shell', 1.0, 5.0): -0.00068176880100879,
    ('shell', 1.0, 1.0): -0.0006030111026811861,
    ('shell', 0.5, 5.0): -0.0006029143184941561,
    ('shell', 0.5, 1.0): -0.0005597891506885714,
    ('shell', 0.25, 5.0): -0.0005533278067799006,
    ('shell', 0.25, 1.0): -0.0005384078707159515,
    ('shell', 0.125, 5.0): -0.0005386703708735677,
    ('shell', 0.125, 1.0): -0.0005304427740259327,
    ('shell', 0.0625, 5.0): -0.0005329473309904696,
    ('shell', 0.0625, 1.0): -0.0005274944433701588,
}


def test_every_figure_scene_gives_its_pinned_peak(figures):
    table = pd.read_csv(figures / "figures" / "runs.csv")
    found = {(row.model, row.h2, row.E2): row.peak_contact_stress for row in table.itertuples()}
    assert set(found) == set(PINNED_PEAKS)
    for scene, peak in PINNED_PEAKS.items():
        assert found[scene] == pytest.approx(peak, rel=1e-9), scene


def test_the_figure_scenes_warn_only_where_the_shell_is_measured_off(figures):
    """No figure scene leaves the model (orchestrate/run/validity.py) but the shell runs whose
    estimated model error exceeds the 1 % tolerance: there the warning is right (the
    bond shear's warnings aside: the next test's and coarse_bond, tests/run/test_validity.py). Each
    shell run is measured against the 2D model's run of the same scene (peak contact
    stress and peak bond stress, the estimate's two quantities): the warning is given
    exactly where the measured error exceeds the tolerance, and its value is within a
    factor 2 of the measured one (where that exceeds 0.2 %)."""
    table = pd.read_csv(figures / "figures" / "runs.csv").set_index("id")
    elastic = table[table["model"] == "elastic"].set_index(["h2", "E2"])
    for name, row in table.iterrows():
        summary = json.loads((figures / "figures" / "runs" / name / "summary.json").read_text())
        codes = [w["code"] for w in summary["warnings"] if w["code"] not in BOND_SHEAR_CODES]
        if row["model"] == "elastic":
            assert codes == [], name
            continue
        reference = elastic.loc[(row["h2"], row["E2"])]
        measured = max(abs(row[key] / reference[key] - 1.0)
                       for key in ("peak_contact_stress", "peak_interface_stress"))
        tolerance = summary["settings"]["model_tolerance"]
        assert codes == (["model_error"] if measured > tolerance else []), (name, measured)
        if codes:
            [estimate] = [w["value"] for w in summary["warnings"] if w["code"] == "model_error"]
            assert 0.5 <= estimate / measured <= 2.0, (name, estimate, measured)


def test_the_figure_shell_runs_say_their_bond_shear_where_it_is_off(figures):
    """The bond shear, which the default answers leave unjudged: every shell run whose
    largest bond shear differs from the 2D model's run of the same scene by more than
    the tolerance warns (bond_shear_model), with an estimate within a factor 2 of that
    difference. (The estimate is within 2x of the measured error in most cases, not
    all, studies/adequacy.py: on the thickest stiff coating, h2 = b, E2 = 5 E, it warns
    at 1.6 % where the difference is 0.6 %; results/claims.md lists every run.)"""
    table = pd.read_csv(figures / "figures" / "runs.csv").set_index("id")
    elastic = table[table["model"] == "elastic"].set_index(["h2", "E2"])
    warned = 0
    for name, row in table[table["model"] == "shell"].iterrows():
        summary = json.loads((figures / "figures" / "runs" / name / "summary.json").read_text())
        found = [w for w in summary["warnings"] if w["code"] == "bond_shear_model"]
        key = "bond-coating1.shear"
        measured = abs(row[key] / elastic.loc[(row["h2"], row["E2"])][key] - 1.0)
        if measured > summary["settings"]["model_tolerance"]:
            assert found, (name, measured)
            assert 0.5 <= found[0]["value"] / measured <= 2.0, (name, found[0]["value"],
                                                                measured)
            warned += 1
    assert warned >= 8          # the shells' bond shear is off on nearly every figure scene


def test_every_bond_answer_has_a_value_away_from_the_patch_end_on_thick_coatings(figures):
    """On the h2 = b scenes an end zone of 2 h2 would cover the whole patch (2 b long):
    capped at a quarter of the patch, it leaves the bond's compression (on the symmetry
    axis, no end) and shear as design values; peel has none only where the bond is in
    compression everywhere."""
    table = pd.read_csv(figures / "figures" / "runs.csv")
    thick = table[table["h2"] == 1.0]
    assert len(thick) == 5
    for name in thick["id"]:
        folder = figures / "figures" / "runs" / name
        bond = json.loads((folder / "summary.json").read_text())["answers"]["bonds"][
            "bond-coating1"]
        for quantity in ("compression", "shear"):
            assert bond[quantity] and not bond[quantity]["end_zone"], (name, quantity)
            assert bond[quantity]["x1"] <= 1.5                     # 2 b - 2 b / 4
        assert bond["compression"]["x1"] <= 0.0625                 # under the indenter
        interface = pd.read_csv(folder / "interface.csv")
        in_tension = (interface["sigma_n"][interface["x1"] < 1.5] > 0).any()
        assert (bond["peel"] is not None) == bool(in_tension), name


def test_a_run_that_did_not_converge_keeps_out_only_the_figures_that_draw_it(figures,
                                                                             tmp_path):
    """The figure sweep again on its finished runs, one of which (shell, b/2, 5E: fig. 4
    alone draws it) stopped as stagnated: figs. 3 and 5 are drawn, fig. 4 is not, and
    the command says that a run did not converge."""
    shutil.copytree(figures / "figures", tmp_path / "figures")     # its runs and manifest
    summary = next((tmp_path / "figures" / "runs").glob("*model=shell_h2=0.5_E2=5")) / "summary.json"
    report = json.loads(summary.read_text())
    summary.write_text(json.dumps({**report, "status": "stagnated", "converged": False}))
    done = subprocess.run([sys.executable, "-m", "studies.figure_sweep", "--out",
                           str(tmp_path)], cwd=PROJECT_DIR, capture_output=True, text=True)
    assert done.returncode == 1 and "1 stagnated" in done.stdout
    assert sorted(path.name for path in tmp_path.glob("fig*.png")) == ["fig3.png", "fig5.png"]


def test_an_interrupted_rebuild_leaves_the_earlier_figures_whole(figures, tmp_path):
    """The figures are drawn aside and put in place together: a rebuild killed while it
    draws leaves the earlier set as it was (and no staging folder); one that finishes
    replaces every figure."""
    shutil.copytree(figures, tmp_path, dirs_exist_ok=True)
    names = [f"{figure}{suffix}" for figure in ("fig3", "fig4", "fig5")
             for suffix in FIGURE_FILES]
    before = {name: (tmp_path / name).read_bytes() for name in names}
    stamps = {name: (tmp_path / name).stat().st_mtime_ns for name in names}
    drawing = FigureDrawing(FIGURE_SWEEP, tmp_path / "figures", tmp_path)
    drawing.run_done()                        # every run is current: all three drawing
    time.sleep(0.5)
    drawing.close()                           # killed mid-rebuild
    assert {name: (tmp_path / name).read_bytes() for name in names} == before
    assert not (tmp_path / STAGING).exists()
    with FigureDrawing(FIGURE_SWEEP, tmp_path / "figures", tmp_path) as drawing:
        drawing.run_done()
        assert len(drawing.finish()) == 3
    assert all((tmp_path / name).stat().st_mtime_ns != stamps[name] for name in names)
    assert not (tmp_path / STAGING).exists()


def test_a_figure_is_drawn_once_the_runs_it_draws_have_converged(tmp_path):
    """fig. 5's runs, which the sweep file lists first, make it ready while the others
    run; a run that did not converge, or that is not the sweep's point from its inputs
    now (another sweep's, or solved with other forms), keeps its figures out."""
    runs = figure_runs(FIGURE_SWEEP, tmp_path)
    assert (len(runs["fig3"]), len(runs["fig4"]), len(runs["fig5"])) == (8, 20, 12)
    points = [name for name, _ in named_points(load_sweep(FIGURE_SWEEP)[1])]
    assert [folder.name for folder in runs["fig5"]] == points[:12]
    assert {folder.name for figure in runs for folder in runs[figure]} == set(points)
    (tmp_path / "sweep.json").write_text(json.dumps(
        {"sweep_id": "this", "points": {name: {"inputs": "its"} for name in points}}))

    def finish(folder, status, sweep="this", forms=forms_digest()):
        folder.mkdir(parents=True, exist_ok=True)
        (folder / "summary.json").write_text(json.dumps({
            "status": status, "sweep_point": {"sweep_id": sweep, "inputs": "its"},
            "provenance": {"forms_digest": forms}}))
    finish(runs["fig5"][-1], "converged", sweep="another")
    for folder in runs["fig5"][:-1]:
        finish(folder, "converged")
    assert ready_figures(runs, {}) == []
    finish(runs["fig5"][-1], "converged", forms="other forms")
    assert ready_figures(runs, {}) == []
    finish(runs["fig5"][-1], "converged")
    assert ready_figures(runs, {}) == ["fig5"]
    assert ready_figures(runs, {"fig5": "drawing"}) == []
    for folder in runs["fig4"]:
        finish(folder, "converged")
    finish(runs["fig3"][-1], "stagnated")
    assert ready_figures(runs, {"fig5": "drawing"}) == []
    finish(runs["fig3"][-1], "converged")
    assert ready_figures(runs, {"fig5": "drawing"}) == ["fig3", "fig4"]


def test_make_draws_the_figures_from_the_one_list_of_scenes():
    """`make fig3` runs `python -m studies.figure_sweep`: the figure sweep (the only list of
    the figure scenes, which studies/figures.py reads too) into results/figures/, then
    the drawing; that list has the 24 scenes of figs. 3-5."""
    make = subprocess.run(["make", "-n", "-B", "fig3"], cwd=PROJECT_DIR, capture_output=True,
                          text=True).stdout
    assert "-m studies.figure_sweep" in make
    assert FIGURE_SWEEP == PROJECT_DIR / "studies" / "sweeps" / "figures.toml"
    assert len(FIGURE_SCENES) == 24
    assert {(m, E2) for m, _, E2 in FIGURE_SCENES} == {
        ("shell", 5.0), ("shell", 1.0), ("elastic", 5.0), ("elastic", 1.0), ("elastic", 0.2)}


def contact(runs, model, h2, E2):
    return runs.curve("contact.csv", model, h2, E2)


def interface(runs, model, h2, E2):
    return runs.curve("interface.csv", model, h2, E2)


def _decreasing(values):
    return all(b < a for a, b in zip(values, values[1:]))


# ---- Fig. 3: sigma_12n on S12 ----------------------------------------------------------

@pytest.mark.parametrize("h2", [1.0, 0.125])
def test_fig3_models_differ_more_for_E2_equal_E(runs, h2):
    assert (distance(contact(runs, "shell", h2, 1.0), contact(runs, "elastic", h2, 1.0))
            > distance(contact(runs, "shell", h2, 5.0), contact(runs, "elastic", h2, 5.0)))


@pytest.mark.parametrize("E2", [5.0, 1.0])
def test_fig3_models_come_closer_as_h2_decreases(runs, E2):
    assert (distance(contact(runs, "shell", 0.125, E2), contact(runs, "elastic", 0.125, E2))
            < distance(contact(runs, "shell", 1.0, E2), contact(runs, "elastic", 1.0, E2)))


@pytest.mark.parametrize("model, E2", [("shell", 5.0), ("shell", 1.0), ("elastic", 5.0)])
def test_fig3_smaller_h2_lowers_the_contact_stress(runs, model, E2):
    assert (-runs.summary(model, 0.125, E2)["peak_contact_stress"]
            < -runs.summary(model, 1.0, E2)["peak_contact_stress"])


def test_fig3_contradiction_2d_coating_of_the_bodies_modulus(runs):
    """Not for the 2D model with E2 = E: there the coating is the same material as
    Omega3, the lower body is one homogeneous body of height h + h2, and a thinner coating
    makes it shorter and stiffer, so the peak pressure rises slightly (measured +1.6 %
    from h2 = b to b/8). The shell model, which does not see the coating as part of
    the body, shows the paper's trend."""
    thick = -runs.summary("elastic", 1.0, 1.0)["peak_contact_stress"]
    thin = -runs.summary("elastic", 0.125, 1.0)["peak_contact_stress"]
    assert 1.0 < thin / thick < 1.05


@pytest.mark.parametrize("model, E2", list(itertools.product(("shell", "elastic"), (5.0, 1.0))))
def test_fig3_smaller_h2_widens_the_contact(runs, model, E2):
    assert (runs.summary(model, 0.125, E2)["contact_half_width"]
            > runs.summary(model, 1.0, E2)["contact_half_width"])


@pytest.mark.parametrize("model", ["shell", "elastic"])
def test_fig3_the_thinner_the_coating_the_less_E2_matters(runs, model):
    assert (distance(contact(runs, model, 0.125, 5.0), contact(runs, model, 0.125, 1.0))
            < distance(contact(runs, model, 1.0, 5.0), contact(runs, model, 1.0, 1.0)))


# ---- Fig. 4: sigma_23n on S23 ----------------------------------------------------------

@pytest.mark.parametrize("E2", [5.0, 1.0])
def test_fig4_models_agree_better_as_h2_decreases(runs, E2):
    assert _decreasing([distance(interface(runs, "shell", h2, E2),
                                 interface(runs, "elastic", h2, E2)) for h2 in HEIGHTS])


@pytest.mark.parametrize("h2", HEIGHTS)
def test_fig4_models_agree_better_for_the_stiffer_coating(runs, h2):
    assert (distance(interface(runs, "shell", h2, 5.0), interface(runs, "elastic", h2, 5.0))
            < distance(interface(runs, "shell", h2, 1.0), interface(runs, "elastic", h2, 1.0)))


@pytest.mark.parametrize("model", ["shell", "elastic"])
def test_fig4_curves_for_different_E2_converge_as_h2_decreases(runs, model):
    assert _decreasing([distance(interface(runs, model, h2, 5.0), interface(runs, model, h2, 1.0))
                        for h2 in HEIGHTS])


@pytest.mark.parametrize("model, E2", list(itertools.product(("shell", "elastic"), (5.0, 1.0))))
def test_fig4_sigma23_approaches_sigma12_as_h2_decreases(runs, model, E2):
    assert _decreasing([distance(interface(runs, model, h2, E2), contact(runs, model, h2, E2))
                        for h2 in HEIGHTS])


# ---- Fig. 5: sigma_eq in the 2D coating ------------------------------------------------

def _maximum(runs, h2, E2):
    return maximum(runs.coating(h2, E2), runs.height, h2)


def _edge_maxima(runs, h2, E2):
    """Local maxima of sigma_eq along the left edge: {relative height: value}."""
    heights, values = left_edge(runs.coating(h2, E2), runs.height)
    return {round(heights[i] / h2, 3): values[i] for i in local_maxima(values)}


def test_fig5_soft_coating_thick_maximum_in_the_middle_of_the_left_edge(runs):
    _, x1, height = _maximum(runs, 1.0, 0.2)
    assert x1 == 0.0 and 0.3 <= height <= 0.7


def test_fig5_soft_coating_maximum_grows_and_moves_to_S23_as_h2_drops(runs):
    maxima = [_maximum(runs, h2, 0.2) for h2 in HEIGHTS[:4]]
    assert _decreasing([-value for value, _, _ in maxima])
    heights = [height for _, _, height in maxima]
    assert all(b <= a for a, b in zip(heights, heights[1:])) and heights[-1] == 0.0


def test_fig5_E2_equal_E_maximum_on_the_left_edge_nearer_S23_than_for_a_soft_coating(runs):
    _, x1, height = _maximum(runs, 1.0, 1.0)
    _, _, soft_height = _maximum(runs, 1.0, 0.2)
    assert x1 == 0.0 and height < soft_height


def test_fig5_E2_equal_E_maximum_falls_as_h2_drops(runs):
    assert _decreasing([_maximum(runs, h2, 1.0)[0] for h2 in HEIGHTS[:4]])


@pytest.mark.parametrize("h2", [1.0, 0.5, 0.25])
def test_fig5_stiff_coating_two_maxima_on_the_left_edge(runs, h2):
    assert set(_edge_maxima(runs, h2, 5.0)) == {0.0, 1.0}     # at S23 and at S12


def test_fig5_contradiction_stiff_thin_coating_has_one_maximum(runs):
    """Not at h2 = b/8: the left edge then has a single maximum, at S12 (the same at
    mesh level 2, so not a matter of the one-layer mesh)."""
    assert set(_edge_maxima(runs, 0.125, 5.0)) == {1.0}


def test_fig5_stiff_coating_maximum_moves_from_S23_to_S12_as_h2_drops(runs):
    """The paper: a smaller h2 raises the maximum near S12 and lowers the one near S23.
    From h2 = b to b/4 (the thinnest with both) it does; in between it does not: both
    grow from b to b/2, then fall: results/claims.md gives the numbers."""
    thick, middle, thin = (_edge_maxima(runs, h2, 5.0) for h2 in (1.0, 0.5, 0.25))
    assert thin[1.0] > thick[1.0] and thin[0.0] < thick[0.0]
    assert middle[1.0] > thick[1.0] and middle[0.0] > thick[0.0]


@pytest.mark.parametrize("h2", [1.0, 0.5, 0.25])
def test_fig5_maxima_grow_with_E2(runs, h2):
    assert _decreasing([-_maximum(runs, h2, E2)[0] for E2 in (0.2, 1.0, 5.0)])


def test_fig5_contradiction_thin_soft_coating_above_E2_equal_E(runs):
    """Not at h2 = b/8 between E/5 and E: the thin coating passes the contact pressure
    on nearly unchanged whatever its modulus (fig. 4), and the soft layer's maximum,
    at S23, ends above the one of E2 = E (2.55e-4 against 2.34e-4)."""
    soft, same, stiff = (_maximum(runs, 0.125, E2)[0] for E2 in (0.2, 1.0, 5.0))
    assert same < soft < stiff
