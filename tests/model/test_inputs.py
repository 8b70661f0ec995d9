"""Bad input is refused before any work, with a message naming the parameter."""

import os
import subprocess
import sys

import pytest

from orchestrate.model.scene import ParameterError, Settings
from orchestrate.model.scene_file import paper_scene
from tests.conftest import PROJECT_DIR


@pytest.mark.parametrize("values, key", [
    ({"E1": -1.0}, "indenter.E"), ({"E2": 0.0}, "coating[1].E"), ({"E3": -2.0}, "base.E"),
    ({"nu1": 0.5}, "indenter.nu"), ({"nu2": 0.7}, "coating[1].nu"), ({"nu3": -1.0}, "base.nu"),
    ({"h2": 0.0}, "coating[1].thickness"), ({"h2": -0.1}, "coating[1].thickness"),
    ({"h2": 8.0}, "coating[1].thickness"), ({"h2": 9.0}, "coating[1].thickness"),
    ({"height": 0.0}, "indenter.height"), ({"length": -4.0}, "indenter.width"),
    ({"coating_length": 5.0}, "coating[1].end"), ({"stamp": -1e-3}, "load.displacement"),
    ({"E1": float("nan")}, "indenter.E"), ({"model": "plate"}, "coating[1].model"),
    ({"E1": 1e300, "E2": 1e300, "E3": 1e300}, "indenter.E"),   # converged to zero force
])
def test_the_papers_parameters_are_refused_naming_the_key_and_the_flag(values, key):
    name = next(iter(values))
    with pytest.raises(ParameterError) as error:
        paper_scene(**values)
    message = str(error.value)
    assert message.startswith(f"{key} = ")
    assert f"(set by {name})" in message


def test_chi_is_refused_naming_itself():
    with pytest.raises(ParameterError, match=r"^chi = 0.0 must be a positive number"):
        paper_scene(chi=0.0)


@pytest.mark.parametrize("values, parameter", [
    ({"rho": 0.0}, "rho"), ({"rho": 1.5}, "rho"), ({"rho": -0.5}, "rho"),
    ({"theta": 0.0}, "theta"), ({"theta": -1e-3}, "theta"),
    ({"mesh_level": 0}, "mesh_level"), ({"mesh_level": 1.5}, "mesh_level"),
    ({"mesh_level": True}, "mesh_level"), ({"eps_u": 0.0}, "eps_u"), ({"eps_u": 1e-2}, "eps_u"),
    ({"max_iterations": 0}, "max_iterations"),
    ({"method": "fast"}, "method"), ({"robin": -1.0}, "robin"),
    ({"robin": 2.0, "theta": 1.0}, "robin"), ({"workers": "threads"}, "workers"),
    ({"element_size": 0.0}, "element_size"),
    ({"model_tolerance": 0.0}, "model_tolerance"), ({"model_tolerance": 1.5}, "model_tolerance"),
    ({"model_tolerance": float("nan")}, "model_tolerance"),
    ({"body_fields": "no"}, "body_fields"), ({"body_fields": 0}, "body_fields"),
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
    ("--E2", "-1", "coating[1].E = "), ("--nu1", "0.5", "indenter.nu = "),
    ("--h2", "8", "coating[1].thickness = "), ("--rho", "1.2", "rho = "),
    ("--theta", "0", "theta = "), ("--mesh-level", "0", "mesh_level = "),
    ("--set", "indenter.radius=-5", "indenter.radius = "),
    ("--set", "base.colour=1", "base.colour"),
    ("--set", "coating[1].model='automatic'", "coating[1].model = "),
    ("--model-tolerance", "-0.01", "model_tolerance = "),
    ("--force", "1e-3", "method = 'paper' cannot carry load.force"),
])
def test_command_line_refuses_before_any_work(flag, value, parameter, tmp_path):
    out = tmp_path / "run"
    extra = ["--method", "paper"] if flag == "--force" else []
    result = _cli("solve", "--out", str(out), flag, value, *extra)
    assert result.returncode == 2
    assert parameter in result.stderr
    assert not out.exists()


def test_a_true_or_false_setting_is_a_flag_and_its_negation():
    from orchestrate.cli import build_parser, scene_from_arguments
    for flags, expected in (([], True), (["--no-body-fields"], False),
                            (["--body-fields"], True)):
        args = build_parser().parse_args(["solve", "--out", "x", *flags])
        assert scene_from_arguments(args)[1].body_fields is expected


def test_mesh_level_must_be_an_integer(tmp_path):
    result = _cli("solve", "--out", str(tmp_path / "run"), "--mesh-level", "1.5")
    assert result.returncode == 2
    assert "--mesh-level" in result.stderr


def test_missing_freefem_is_reported_before_any_work(tmp_path):
    env = dict(os.environ, FREEFEM="no-such-freefem-binary")
    out = tmp_path / "run"
    result = _cli("solve", "--out", str(out), env=env)
    assert result.returncode == 2
    assert "FreeFEM not found" in result.stderr
    assert not out.exists()


def test_the_default_penalty_follows_the_interface_elements():
    """theta = 4e-3 E times the interface element's length (studies/penalty.py shows
    its error below the mesh's at levels 1-3); the paper's loop keeps the paper's 1e-3;
    a theta given is kept."""
    assert Settings().theta == pytest.approx(2.5e-4, rel=1e-12)
    assert Settings(mesh_level=2).theta == pytest.approx(1.25e-4, rel=1e-12)
    assert Settings(element_size=0.125).theta == pytest.approx(5e-4, rel=1e-12)
    assert Settings(method="paper").theta == 1e-3
    assert Settings(theta=1e-2).theta == 1e-2


def test_the_default_robin_parameter_is_the_coarse_elements_stiffness_with_two_levels():
    """gamma = 8 E/b for a loop on its own, times the square root of the mesh level; with a
    coarse correction (mesh level 2 and finer) 4 E over the element length, the
    stiffness of the modes the coarse mesh cannot see; a gamma given is kept, and the
    paper's loop keeps 1/theta."""
    assert Settings().robin_parameter == 8.0
    assert Settings(mesh_level=2, inner_solve="iterate").robin_parameter == pytest.approx(
        8.0 * 2 ** 0.5, rel=1e-12)
    assert Settings(mesh_level=2).robin_parameter == pytest.approx(64.0, rel=1e-12)
    assert Settings(mesh_level=3, element_size=0.125).robin_parameter == pytest.approx(32.0)
    assert Settings(mesh_level=2, robin=5.0).robin_parameter == 5.0
    assert Settings(method="paper").robin_parameter == pytest.approx(1e3)
