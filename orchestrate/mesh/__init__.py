"""The scene as subdomains and interfaces (discretization.py: the discrete problem every
run and the monolithic solve share), what the mesher needs of each body (body_plans.py),
the bodies' and 2D coatings' meshes (meshes.py, gmsh and structured), the boundary labels
of freefem/labels.idp (labels.py), and a problem's size, estimated before any mesh
(problem_size.py)."""

from orchestrate.mesh.discretization import discretize, simpson

__all__ = ["discretize", "simpson"]
