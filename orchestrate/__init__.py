"""Python driver of the Robin domain decomposition: scenes, meshes, FreeFEM workers,
the Robin loop, results. ``python -m orchestrate --help`` lists the commands."""

import os

# The driver's linear algebra is small (the interface); a multi-threaded BLAS would
# spin on the cores the FreeFEM workers need (measured: 12.7 -> 9.1 ms per iteration).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
