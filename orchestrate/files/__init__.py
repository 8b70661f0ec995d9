"""Files a run owns and how they are written: its output folder, written whole or not at
all, and its private working folder (folders.py); atomic writes and the run's output
files (outputs.py). The lowest layer but errors: it knows no scene."""
