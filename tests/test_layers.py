"""The layout: the tool's layers import only those below them, the tool imports no study,
and the studies use the tool's public API only.

The layers and the rule against studies are import-linter contracts (pyproject.toml,
[tool.importlinter]); the public API is the ``orchestrate`` package and its layers'
packages (``orchestrate.run``, ``orchestrate.model``, ...) and top modules
(``orchestrate.cli``, ``orchestrate.paths``, ``orchestrate.errors``), never a module inside
a layer. A copy of the tree with one forbidden import breaks the contract: the check is
not vacuous.
"""

import ast
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import PROJECT_DIR

LINT_IMPORTS = Path(sys.executable).with_name("lint-imports")


def _lint(tree):
    return subprocess.run([str(LINT_IMPORTS), "pyproject.toml"], cwd=tree, env={
        "PYTHONPATH": str(tree), "PATH": "/usr/bin:/bin"}, capture_output=True, text=True,
        timeout=300)


def test_the_import_contracts_are_kept():
    result = _lint(PROJECT_DIR)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "2 kept, 0 broken" in result.stdout


@pytest.mark.parametrize("module, line", [
    ("orchestrate/run/solve.py", "import studies.figures"),           # a study in the tool
    ("orchestrate/model/scene.py", "import orchestrate.run.answers"),  # a layer up
    ("orchestrate/ddm/robin.py", "import orchestrate.workers.worker"),  # a sibling layer
])
def test_a_forbidden_import_breaks_the_contracts(tmp_path, module, line):
    for name in ("orchestrate", "studies"):
        shutil.copytree(PROJECT_DIR / name, tmp_path / name, symlinks=True,
                        ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copy(PROJECT_DIR / "pyproject.toml", tmp_path)
    path = tmp_path / module
    path.write_text(path.read_text() + f"\n{line}\n")
    result = _lint(tmp_path)
    assert result.returncode != 0 and "BROKEN" in result.stdout, result.stdout


def _orchestrate_imports(path):
    """Every module name under orchestrate that a file imports."""
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            yield node.module
        elif isinstance(node, ast.Import):
            yield from (alias.name for alias in node.names)


def test_the_studies_use_the_tools_public_api_only():
    found = {}
    for path in (PROJECT_DIR / "studies").glob("*.py"):
        for module in _orchestrate_imports(path):
            if module.startswith("orchestrate") and module.count(".") > 1:
                found.setdefault(path.name, []).append(module)
    assert found == {}, "studies importing modules inside the tool's layers"
