"""Where the tool's files are: the package, the checkout it runs from (if it runs from
one), and the FreeFEM scripts and forms (freefem/, or the folder $ORCHESTRATE_FORMS
names)."""

import os
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
PROJECT_DIR = PACKAGE_DIR.parent
FREEFEM_DIR = (PACKAGE_DIR / "forms").resolve()   # freefem/ in a checkout (forms is a link
                                                  # to it), the installed copy elsewhere
SCENES_DIR = PACKAGE_DIR / "scenes"
FORMS_VARIABLE = "ORCHESTRATE_FORMS"


def forms_dir():
    """The folder of the FreeFEM scripts and forms a run reads: $ORCHESTRATE_FORMS (a copy
    of freefem/ with edited forms, say), else freefem/."""
    return Path(os.environ.get(FORMS_VARIABLE) or FREEFEM_DIR)
