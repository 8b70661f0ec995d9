"""Plots of finished runs and sweeps, from their files alone: a run's stresses along the
surface (plot.py), a sweep's column against another (plot_sweep.py), two runs of one
scene compared panel by panel (discrete_figure.py). matplotlib is imported here only."""
