"""A sweep's table in the scene's units (orchestrate/sweeps/table.py, plots/plot_sweep.py):
a swept key given with its own unit is a number in the file's units in its column, a
key of every patch (coating.thickness) as much as a single one (load.force), and the
forces' unit is the run's: N on a body of revolution, not N/mm. Found by a sweep of the
2 mm ball over "coating.thickness" = ["2 um", "0.005 mm"]: its column held the text,
the plot drew it as two categories on an axis labelled mm, and the legend said
load.force=5 N/mm. The summaries are written here, as a run writes them; nothing is
solved."""

import json

import pytest

from orchestrate.model.scene import to_dict
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene
from orchestrate.plots.plot_sweep import _label, axis_label
from orchestrate.sweeps.table import gather

POINTS = [{"coating.thickness": "2 um", "load.force": "5 N"},
          {"coating.thickness": "0.005 mm", "load.force": "0.02 kN"}]


@pytest.fixture
def table(tmp_path):
    """The ball's sweep table from summaries holding its scenes and units."""
    ball, _ = load_scene(SCENES_DIR / "ball_mm.toml")
    runs = []
    for number, values in enumerate(POINTS):
        scene = apply_overrides(ball, values)
        folder = tmp_path / "runs" / f"point{number}"
        folder.mkdir(parents=True)
        (folder / "summary.json").write_text(json.dumps({
            "scene": to_dict(scene), "status": "converged", "contact_force": 1.0,
            "units": {"length": "mm", "stress": "MPa", "force": "N"}}))
        runs.append((folder.name, values))
    return gather(tmp_path, runs)


def test_a_swept_key_with_its_own_unit_is_a_number_in_the_files_units(table):
    assert table["coating.thickness"].tolist() == pytest.approx([0.002, 0.005])
    assert table["coating[1].thickness"].tolist() == pytest.approx([0.002, 0.005])
    assert table["load.force"].tolist() == pytest.approx([5.0, 20.0])


def test_a_body_of_revolutions_forces_are_labelled_whole(table):
    assert axis_label(table, "load.force") == "load.force (N)"
    assert axis_label(table, "contact_force") == "contact_force (N)"
    assert axis_label(table, "coating.thickness") == "coating.thickness (mm)"
    assert _label(table, ["load.force"], (20.0,)) == "load.force=20 N"
