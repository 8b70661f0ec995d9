"""Every example scene the repository ships (orchestrate/scenes/, its gallery too)
converges with its own settings, and under a force carries it: a scene no test ran had
stopped converging unseen (the fretting example, whose answer tests/run/test_friction.py
checks against the monolithic solve; the gallery's pads, solved and checked in
tests/ddm/test_contact_set_updates.py)."""

import pytest

from orchestrate import solve
from orchestrate.model.scene_file import SCENES_DIR, load_scene

pytestmark = pytest.mark.slow       # about a second a scene

SCENES = sorted(path for path in [*SCENES_DIR.glob("*.toml"), *SCENES_DIR.glob("gallery/*.toml")]
                if path.name not in ("fretting_mm.toml", "patches_and_bare_base.toml"))


@pytest.mark.parametrize("path", SCENES, ids=lambda path: path.stem)
def test_every_example_scene_converges(path):
    scene, settings = load_scene(path)
    summary = solve(scene, settings).summary
    assert summary["converged"], summary["reason"]
    if scene.load.force is not None:        # the whole body's (a half model carries half)
        assert summary["total_force"] == pytest.approx(scene.load.force, rel=1e-6)
