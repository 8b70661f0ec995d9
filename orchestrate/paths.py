"""Where the project's files are."""

from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
PROJECT_DIR = PACKAGE_DIR.parent
FREEFEM_DIR = PROJECT_DIR / "freefem"
RESULTS_DIR = PROJECT_DIR / "results"
# Every scene of the paper's figures 3-5, listed once (orchestrate/figures.py)
FIGURE_SWEEP = PACKAGE_DIR / "sweeps" / "figures.toml"
