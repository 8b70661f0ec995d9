"""An edit of the material law in the FreeFEM forms shows in every answer, the reported
stresses included (freefem/elasticity.idp takes them from elasticEnergy, freefem/shell.idp
from shellEnergy and shellStretchEnergy; restated formulas would not follow an edit).

The law scaled by c = 1.25 in every body is the same discrete problem as every modulus
(indenter, coating, base) scaled by c, provided the penalty is the same physical one:
the solver's penalty is theta / Scene.modulus (the stiffer body's E), so theta / c with
the moduli as given equals theta with the moduli times c. Under the paper scene's stamp
descent the answers are then the same; the Robin parameter changes only the loop's path.
Runs on the paper's scene (h2 = b/8, E2 = 5E) per coating model, each about a second:
  edited     the forms copied and edited (ORCHESTRATE_FORMS), the law times c, the moduli
             as given, theta / c;
  moduli     the project's forms, every modulus times c, theta;
  original   the project's forms, the moduli as given, theta: its problem is `edited`'s
             divided by c, so it has `edited`'s displacements and 1/c of its stresses.
`edited` must equal `moduli` in displacements, contact and bond stresses and reported
stresses, and its stresses must be c times `original`'s. Stresses restated apart from
the forms failed that: `edited` reported `original`'s stresses (s11 of the 2D coating,
T11 of the shells: these tests fail on the forms before the change).

Two edits. "energy" scales the forms (elasticEnergy; shellEnergy, shellStretchEnergy and
shellStretchGradientEnergy, all three parts of the stretch shell's energy: leaving out the
last, the stretch shell's fields differ from the scaled moduli's by up to 1 %). The 2D
stresses are elasticEnergy's work on unit strains, sigma33 too (it does no work in a
plane-strain energy, but its unit strain reads it), so all of them follow, and
sigma_eq with them. "law" scales the law itself (elasticStress).

Tolerance: both runs stop at eps_u = 1e-9 (relative change of the interface state);
RTOL = 1e-7 of each field's largest value leaves a hundred times that. Measured: 1e-12
(the active-set loop solves each contact set's fixed point directly)."""

import json
import re
import shutil

import numpy as np
import pandas as pd
import pytest

from orchestrate.paths import FORMS_VARIABLE, FREEFEM_DIR
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import paper_scene
from orchestrate.run.solve import solve

FACTOR = 1.25
EPS_U = 1e-9
RTOL = 1e-7
THETA = Settings().theta               # the default penalty, b/E
H2, E2 = 0.125, 5.0
SHELL_ENERGY = ("shellEnergy", "shellStretchEnergy", "shellStretchGradientEnergy")
EDITS = {
    "energy": {"elasticity.idp": ("elasticEnergy",), "shell.idp": SHELL_ENERGY},
    "law": {"elasticity.idp": ("elasticStress",)},       # for the 2D coating
}
MODELS = ("elastic", "shell", "stretch_shell")
STRESSES = {"elastic": ("s11", "s22", "s12"), "shell": ("T11", "T13", "M11"),
            "stretch_shell": ("T11", "T13", "M11", "T33")}
DISPLACEMENTS = {"elastic": ("u1", "u2"), "shell": ("v", "w", "gamma"),
                 "stretch_shell": ("v", "w", "gamma", "epsilon")}


def scaled_macro(text, name, factor):
    """The text with macro `name`'s body multiplied by factor; exactly one definition."""
    definition = re.compile(r"(macro " + name + r"\([^)]*\))(.*?)(// EOM)", re.DOTALL)
    edited, count = definition.subn(
        lambda m: f"{m.group(1)} ({factor})*({m.group(2)}) {m.group(3)}", text)
    assert count == 1, f"{name}: {count} definitions"
    return edited


def edited_forms(folder, edit):
    """A copy of freefem/ in folder with the macros of EDITS[edit] times FACTOR."""
    shutil.copytree(FREEFEM_DIR, folder)
    for file, names in EDITS[edit].items():
        path = folder / file
        text = path.read_text()
        for name in names:
            text = scaled_macro(text, name, FACTOR)
        path.write_text(text)
    return folder


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """run(model, kind) -> run folder; kind: "energy" or "law" (edited), "moduli",
    "original"; each solved once."""
    root = tmp_path_factory.mktemp("constitutive_law")
    forms = {edit: edited_forms(root / f"forms_{edit}", edit) for edit in EDITS}
    done = {}

    def run(model, kind):
        if (model, kind) not in done:
            scale = FACTOR if kind == "moduli" else 1.0
            theta = THETA / FACTOR if kind in forms else THETA
            scene = paper_scene(h2=H2, E2=E2 * scale, E1=scale, E3=scale, model=model)
            folder = root / f"{model}_{kind}"
            with pytest.MonkeyPatch.context() as patch:
                if kind in forms:
                    patch.setenv(FORMS_VARIABLE, str(forms[kind]))
                else:
                    patch.delenv(FORMS_VARIABLE, raising=False)
                summary = solve(scene, Settings(theta=theta, eps_u=EPS_U), str(folder))
            assert summary["converged"], (model, kind)
            done[model, kind] = folder
        return done[model, kind]
    return run


def _coating(folder, model):
    """The coating's nodal fields (2D) or its mid-line's fields (shells)."""
    name = "coating1.csv" if model == "elastic" else "coating1_fields.csv"
    return pd.read_csv(folder / name)


def _close(actual, expected, what):
    """actual == expected to RTOL of expected's largest magnitude (NaN where both are)."""
    actual, expected = np.asarray(actual, float), np.asarray(expected, float)
    scale = np.nanmax(np.abs(expected))
    assert scale > 0, what
    np.testing.assert_allclose(actual, expected, rtol=0, atol=RTOL * scale, equal_nan=True,
                               err_msg=what)


def _same_answers(actual, expected, path="answers"):
    """Every number of an answers tree equal to RTOL; positions, flags and None equal."""
    if isinstance(expected, dict):
        assert actual.keys() == expected.keys(), path
        for key in expected:
            _same_answers(actual[key], expected[key], f"{path}.{key}")
    elif isinstance(expected, float):
        assert actual == pytest.approx(expected, rel=RTOL), path
    else:
        assert actual == expected, path


def _interface_tables(folder):
    return {name: pd.read_csv(folder / f"{name}.csv")
            for name in ("contact", "interface", "traces")}


@pytest.mark.parametrize("model", MODELS)
def test_an_edited_energy_is_the_problem_with_scaled_moduli(runs, model):
    edited, moduli = runs(model, "energy"), runs(model, "moduli")
    tables, expected_tables = _interface_tables(edited), _interface_tables(moduli)
    for name, columns in (("contact", ("sigma_n",)), ("interface", ("sigma_n", "sigma_t")),
                          ("traces", ("a_t", "a_n", "b_t", "b_n"))):
        for column in columns:
            _close(tables[name][column], expected_tables[name][column], f"{name}.{column}")
    coating, expected = _coating(edited, model), _coating(moduli, model)
    for column in DISPLACEMENTS[model] + STRESSES[model]:
        _close(coating[column], expected[column], column)
    answers = json.loads((edited / "summary.json").read_text())["answers"]
    expected_answers = json.loads((moduli / "summary.json").read_text())["answers"]
    _same_answers(answers["contact"], expected_answers["contact"])
    _same_answers(answers["bonds"], expected_answers["bonds"])
    _same_answers(answers["coatings"], expected_answers["coatings"])


@pytest.mark.parametrize("model", MODELS)
def test_the_reported_stresses_follow_the_edited_energy(runs, model):
    """On the same displacements, the stresses of the edited law are FACTOR times the
    project's: what stresses restated apart from the energy did not show."""
    edited, original_run = runs(model, "energy"), runs(model, "original")
    coating, original = _coating(edited, model), _coating(original_run, model)
    for column in DISPLACEMENTS[model]:
        _close(coating[column], original[column], column)
    for column in STRESSES[model]:
        _close(coating[column], FACTOR * original[column], column)
    _close(pd.read_csv(edited / "contact.csv").sigma_n,
           FACTOR * pd.read_csv(original_run / "contact.csv").sigma_n, "contact sigma_n")
    if model == "elastic":     # sigma33 does no plane work, but is read from the energy
        for column in ("s33", "sigma_eq"):
            _close(coating[column], FACTOR * original[column], column)


def test_an_edited_law_shows_in_every_2d_stress(runs):
    edited, moduli = runs("elastic", "law"), runs("elastic", "moduli")
    coating, expected = _coating(edited, "elastic"), _coating(moduli, "elastic")
    for column in ("u1", "u2", "s11", "s22", "s12", "s33", "sigma_eq"):
        _close(coating[column], expected[column], column)
    _close(pd.read_csv(edited / "contact.csv").sigma_n,
           pd.read_csv(moduli / "contact.csv").sigma_n, "contact sigma_n")
    answers = json.loads((edited / "summary.json").read_text())["answers"]
    expected_answers = json.loads((moduli / "summary.json").read_text())["answers"]
    _same_answers(answers, expected_answers)

