"""Where the studies write; the one list of the figures' scenes, and the gallery's."""

from pathlib import Path

from orchestrate.paths import SCENES_DIR

STUDIES_DIR = Path(__file__).resolve().parent
RESULTS_DIR = STUDIES_DIR.parent / "results"
# Every scene of the paper's figures 3-5, listed once (studies/figure_scenes.py)
FIGURE_SWEEP = STUDIES_DIR / "sweeps" / "figures.toml"
GALLERY_DIR = SCENES_DIR / "gallery"


def gallery_files(names=None):
    """The gallery's scene files (orchestrate/scenes/gallery/), sorted; only those named
    in ``names`` if given."""
    files = sorted(GALLERY_DIR.glob("*.toml"))
    return [path for path in files if path.stem in names] if names else files
