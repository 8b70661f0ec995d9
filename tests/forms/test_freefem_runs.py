"""The test harness itself: a FreeFEM script runs and a broken one reports its error."""

import pytest


def test_a_broken_script_fails_with_its_log(run_freefem, tmp_path):
    script = tmp_path / "broken.edp"
    script.write_text("real x = ;\n")
    with pytest.raises(RuntimeError, match="failed"):
        run_freefem(str(script))
