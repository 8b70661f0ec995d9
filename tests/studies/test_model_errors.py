"""The adequacy study's measured rows (studies/model_errors.py): measured once and kept,
but a row measured on another scene under the same label (a scene file edited since) is
measured again, not reused."""

import json

import pandas as pd

from orchestrate.model import to_dict
from orchestrate.model.scene import Base, Coating, Indenter, Load, Scene
from studies import model_errors


def _fake_measure(label, scene):
    return {"label": label, "scene": json.dumps(to_dict(scene)),
            "shell_error_peak": scene.coatings[0].thickness, "stretch_shell_error_peak": 0.0,
            "elastic_error_peak": 0.0, "seconds": 0.0}


def _scene(thickness):
    return Scene(indenter=Indenter(radius=20.0), base=Base(), load=Load(force=0.05),
                 coatings=(Coating(thickness=thickness),))


def test_a_row_of_an_edited_scene_is_measured_again(tmp_path, monkeypatch):
    monkeypatch.setattr(model_errors, "measure", _fake_measure)
    table = tmp_path / "rows.csv"
    model_errors.measure_all([("kept", _scene(0.1)), ("edited", _scene(0.2))], table, jobs=1,
                             progress=lambda text: None)
    said = []
    rows = model_errors.measure_all([("kept", _scene(0.1)), ("edited", _scene(0.3))], table,
                                    jobs=1, progress=said.append)
    assert dict(zip(rows.label, rows.shell_error_peak)) == {"kept": 0.1, "edited": 0.3}
    assert len(pd.read_csv(table)) == 2 and "edited" in said[0] and "kept" not in said[0]
