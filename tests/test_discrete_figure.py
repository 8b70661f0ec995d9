"""The discrete-coating figure (make discrete): both coating models over the patches of
orchestrate/scenes/discrete.toml, drawn from their CSV files.

Physics the figure shows and a test can check: the stiff patch under the cylinder
carries the load to its bonded end, where both models concentrate the contact pressure
(the edge of a stiff patch pressed by a softer indenter; singular in the 2D model); the
bare base between patches stays out of contact (the cylinder's sag over the gap, 0.014 b,
is below the patches' thickness, 0.125 b); and away from the ends both models agree
(measured: the bond's normal stress under the middle of the central patch differs by
0.65 % between the models; the end's contact pressure is 3.5 (shell) and 2.7 (2D)
times the centre's)."""

import numpy as np
import pandas as pd
import pytest

from orchestrate.discrete_figure import figure, singular_ends
from orchestrate.scene import Settings, to_dict
from orchestrate.scene_file import SCENES_DIR, apply_overrides, load_scene
from orchestrate.solve import solve


@pytest.fixture(scope="module")
def drawn(tmp_path_factory):
    base = tmp_path_factory.mktemp("discrete")
    scene, _ = load_scene(SCENES_DIR / "discrete.toml")
    folders = []
    for model in ("shell", "elastic"):
        solve(apply_overrides(scene, {"model": model}), Settings(), base / model)
        folders.append(str(base / model))
    figure(folders, base / "figure")
    return scene, base / "figure", pd.read_csv(base / "figure" / "discrete_data.csv")


def test_the_figure_and_its_data_are_written(drawn):
    scene, out, data = drawn
    assert (out / "discrete.png").exists() and (out / "discrete.pdf").exists()
    assert set(data.model) == {"shell", "elastic"}
    assert set(data.quantity) == {"contact sigma_n", "bond sigma_n", "bond sigma_t"}


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
