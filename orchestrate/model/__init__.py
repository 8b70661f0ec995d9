"""The scene as validated data: the bodies, coatings and load (scene.py), the solver
settings, scene files and their overrides (scene_file.py), units and values with units
(units.py), the faces' geometry (geometry.py), and the a priori estimates of a scene:
the contact's half-width and each coating model's error (estimate.py). Pure Python, no
mesh, no process."""

from orchestrate.model.estimate import contact_half_width, estimated_errors
from orchestrate.model.scene import (DEFAULT_ELEMENT_SIZE, MODELS, Base, Coating, Indenter,
                                     Load, LoadStep, Scene, Settings, scene_from_dict,
                                     to_dict)
from orchestrate.model.scene_file import (apply_overrides, load_scene, paper_scene,
                                          scene_and_settings, shorthand_values)
from orchestrate.model.units import Units

__all__ = ["DEFAULT_ELEMENT_SIZE", "MODELS", "Base", "Coating", "Indenter", "Load", "LoadStep",
           "Scene", "Settings", "Units", "apply_overrides", "contact_half_width", "estimated_errors", "load_scene",
           "paper_scene", "scene_and_settings", "scene_from_dict", "shorthand_values",
           "to_dict"]
