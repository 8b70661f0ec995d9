"""Where the project's files are."""

from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
PROJECT_DIR = PACKAGE_DIR.parent
FREEFEM_DIR = PROJECT_DIR / "freefem"
RESULTS_DIR = PROJECT_DIR / "results"
