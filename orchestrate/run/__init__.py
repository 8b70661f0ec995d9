"""One run: everything decided before any work (plan.py), the run itself and its files
(solve.py), the answers a coating engineer looks for (answers.py), the warnings where a
run leaves its model (validity.py), a start from a finished run (warm_start.py), the
coarse level's own workers (coarse_level.py), ParaView collections (paraview.py), the
monolithic solve of the same discrete problem (monolithic.py) and the Python API
(api.py)."""
