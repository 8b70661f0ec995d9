"""The scene as validated data: the bodies, coatings and load (scene.py), the solver
settings, scene files and their overrides (scene_file.py), units and values with units
(units.py), the faces' geometry (geometry.py), and the a priori estimates of a scene:
the contact's half-width and each coating model's error (estimate.py). Pure Python, no
mesh, no process."""
