"""Where the studies write, and the one list of the figures' scenes."""

from pathlib import Path

STUDIES_DIR = Path(__file__).resolve().parent
RESULTS_DIR = STUDIES_DIR.parent / "results"
# Every scene of the paper's figures 3-5, listed once (studies/figure_scenes.py)
FIGURE_SWEEP = STUDIES_DIR / "sweeps" / "figures.toml"
