"""Files a run owns and how they are written: its output folder, written whole or not at
all, and its private working folder (folders.py); files written atomically, each whole
or not at all (writing.py). The lowest layer but errors: it knows no scene."""

from orchestrate.files.writing import partial_path, write_csv, written

__all__ = ["partial_path", "write_csv", "written"]
