"""The monolithic solve of the discrete penalised problem (freefem/monolithic.edp).

All three subdomains in one matrix, the contact set iterated to a fixed point. It
solves the same discrete problem as the Robin loop (same forms, same interface
quadrature), which makes it the yardstick of the loop's correctness."""

import os
import tempfile

import numpy as np

from . import freefem
from .contact import bond_traction, contact_stress


def solve_monolithic(scene, settings, files, workdir, model=None):
    """Interface displacements of the monolithic solution, as the Robin loop's blocks:
    ``{"upper_n", "coating_n", "coating_bond", "lower_bond"}``, plus ``solves``.

    ``model`` overrides settings.model; "none" solves the scene without coating (then
    ``files.lower_mesh`` must touch Omega1, and "coating_n" is its top's displacement)."""
    output = os.path.join(workdir, "monolithic_traces.txt")
    freefem.run_script("monolithic.edp", [
        "-model", model or settings.model, "-coating", files.coating_mesh,
        "-upper", files.upper_mesh, "-lower", files.lower_mesh, "-nodes", files.shell_nodes,
        "-contact", files.contact_points, "-bond", files.bond_points,
        "-E1", scene.E1, "-nu1", scene.nu1, "-E2", scene.E2, "-nu2", scene.nu2,
        "-E3", scene.E3, "-nu3", scene.nu3, "-h2", scene.h2, "-kshear", scene.shear_factor,
        "-stamp", scene.stamp, "-theta", settings.theta, "-output", output],
        os.path.join(workdir, "monolithic.log"))
    tokens = open(output).read().split()
    arrays, i = [], 0
    for _ in range(6):
        n = int(tokens[i])
        arrays.append(np.array(tokens[i + 1:i + 1 + n], dtype=float))
        i += 1 + n
    solves, settled = int(tokens[i]), int(tokens[i + 1])
    if not settled:
        raise RuntimeError(f"the monolithic contact set did not settle in {solves} solves")
    u1n, w, f1, f2, u31, u32 = arrays
    return {"upper_n": u1n, "coating_n": w, "coating_bond": np.array([f1, f2]),
            "lower_bond": np.array([u31, u32]), "solves": solves}


def monolithic_interface(scene, settings, coated=True):
    """Monolithic interface displacements and stresses of a scene, in a private folder.

    Returns the traces of ``solve_monolithic`` plus "x1", "sigma_12n" and "sigma_23n"
    (the penalty laws evaluated on the traces). ``coated=False`` solves the same scene
    without its coating: Omega3 grown by h2 touches Omega1 on the same contact points."""
    from .mesh import body_mesh, write_medit
    from .subdomains import write_inputs   # meshes and interface points, as for the DDM

    with tempfile.TemporaryDirectory(prefix="monolithic-") as workdir:
        files, contact, bond = write_inputs(scene, settings, workdir)
        if not coated:
            write_medit(body_mesh(scene, settings, "lower-uncoated"), files.lower_mesh)
        result = solve_monolithic(scene, settings, files, workdir,
                                  model=None if coated else "none")
    result["x1"] = contact.x
    result["sigma_12n"] = contact_stress(contact.gap, result["upper_n"], result["coating_n"],
                                         settings.theta)
    result["sigma_23n"] = bond_traction(result["coating_bond"], result["lower_bond"],
                                        settings.theta)[1]
    return result
