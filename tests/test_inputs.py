"""Bad input is refused before any work, with a message naming the parameter."""

import subprocess
import sys

import pytest

from orchestrate.scene import ParameterError, Scene, Settings
from tests.conftest import PROJECT_DIR


@pytest.mark.parametrize("values, parameter", [
    ({"E1": -1.0}, "E1"), ({"E2": 0.0}, "E2"), ({"E3": -2.0}, "E3"),
    ({"nu1": 0.5}, "nu1"), ({"nu2": 0.7}, "nu2"), ({"nu3": -1.0}, "nu3"),
    ({"h2": 0.0}, "h2"), ({"h2": -0.1}, "h2"), ({"h2": 8.0}, "h2"), ({"h2": 9.0}, "h2"),
    ({"height": 0.0}, "height"), ({"length": -4.0}, "length"),
    ({"coating_length": 5.0}, "coating_length"), ({"chi": 0.0}, "chi"),
    ({"stamp": -1e-3}, "stamp"), ({"E1": float("nan")}, "E1"),
])
def test_scene_refuses(values, parameter):
    with pytest.raises(ParameterError, match=rf"^{parameter} = "):
        Scene(**values)


@pytest.mark.parametrize("values, parameter", [
    ({"rho": 0.0}, "rho"), ({"rho": 1.5}, "rho"), ({"rho": -0.5}, "rho"),
    ({"theta": 0.0}, "theta"), ({"theta": -1e-3}, "theta"),
    ({"mesh_level": 0}, "mesh_level"), ({"mesh_level": 1.5}, "mesh_level"),
    ({"mesh_level": True}, "mesh_level"), ({"eps_u": 0.0}, "eps_u"),
    ({"max_iterations": 0}, "max_iterations"), ({"model": "plate"}, "model"),
    ({"method": "fast"}, "method"), ({"robin": -1.0}, "robin"),
    ({"robin": 2.0, "theta": 1.0}, "robin"), ({"workers": "threads"}, "workers"),
    ({"shell_elements": 0}, "shell_elements"),
])
def test_settings_refuse(values, parameter):
    with pytest.raises(ParameterError, match=rf"^{parameter} = "):
        Settings(**values)


def test_rho_of_one_is_allowed():
    assert Settings(rho=1.0).rho == 1.0


def _cli(*arguments, env=None):
    return subprocess.run([sys.executable, "-m", "orchestrate", *arguments],
                          cwd=PROJECT_DIR, capture_output=True, text=True, env=env, timeout=60)


@pytest.mark.parametrize("flag, value, parameter", [
    ("--E2", "-1", "E2"), ("--nu1", "0.5", "nu1"), ("--h2", "8", "h2"),
    ("--rho", "1.2", "rho"), ("--theta", "0", "theta"), ("--mesh-level", "0", "mesh_level"),
])
def test_command_line_refuses_before_any_work(flag, value, parameter, tmp_path):
    out = tmp_path / "run"
    result = _cli("solve", "--out", str(out), flag, value)
    assert result.returncode == 2
    assert f"{parameter} = " in result.stderr
    assert not out.exists()


def test_mesh_level_must_be_an_integer(tmp_path):
    result = _cli("solve", "--out", str(tmp_path / "run"), "--mesh-level", "1.5")
    assert result.returncode == 2
    assert "--mesh-level" in result.stderr


def test_missing_freefem_is_reported_before_any_work(tmp_path):
    import os
    env = dict(os.environ, FREEFEM="no-such-freefem-binary")
    out = tmp_path / "run"
    result = _cli("solve", "--out", str(out), env=env)
    assert result.returncode == 2
    assert "FreeFEM not found" in result.stderr
    assert not out.exists()
