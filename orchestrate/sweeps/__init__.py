"""Parameter sweeps: the sweep file and its points, the manifest that says which run
folder is which point, the engines (local processes, Dask), the table (sweep.py), and the
run folders' names (run_names.py)."""
