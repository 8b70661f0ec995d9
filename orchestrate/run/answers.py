"""The answers a coating engineer looks for, from a finished run's stresses.

    contact     the peak contact pressure (positive), where it is
    bonds       per bond: the largest tensile normal stress (peel), the largest
                compressive one and the largest shear, each with its position
    coatings    per patch: the largest von Mises stress and its position, and the
                largest tensile stress along its top face (2D model);
                the fibre stresses at the top and bottom faces and the mean shear from
                the shell's forces (shell models; a shell of revolution's radial and
                hoop fibre stresses)
    substrate   the base's largest von Mises stress, where and how deep below its face
                (under a Hertzian contact it lies below the surface), and the largest
                tensile stress along its face (under sliding friction, behind the
                contact: 2 mu p0 on a half-plane); where the bodies' fields are not
                computed, none

Where a bonded coating ends, the elastic solution is singular (a bi-material wedge): the
stresses there grow as the mesh refines and have no converged value. Every maximum is
therefore taken twice: away from the patches' ends (the values to design with) and
within their end zones ("at_patch_ends", marked mesh-dependent: they say where the
stress concentrates, not how much); each says which it is ("end_zone": false or true).
An end zone reaches END_ZONE thicknesses from the end, but at most END_ZONE_SHARE of
the patch's length: a coating as thick as its patch is long (the paper's h2 = b on a
patch of 2 b) keeps values away from its ends, and an end's zone never reaches the
other end's, nor the symmetry axis of a half model, which is no end. The contact's
peak pressure is split the same way: a peak at a patch end (the indenter pressing on
the step of a patch's edge) is singular too.

Computed in the solver's b and E from the run's data in memory, expressed in the scene's
units with the summary (orchestrate/model/units.py); compression is negative, tension
positive.
"""

import numpy as np

END_ZONE = 2.0   # thicknesses from a patch's end: measured, the 2D model's peak there
                 # moved 11-42 % between meshes (studies/model_errors.py)
END_ZONE_SHARE = 0.25   # of the patch's length at most (the module's text)


def end_zone_width(coating, thicknesses=END_ZONE, capped=True):
    """How far from a patch's end its end zone reaches (``capped``: at most
    END_ZONE_SHARE of its length)."""
    width = thicknesses * coating.thickness
    return min(width, END_ZONE_SHARE * (coating.end - coating.start)) if capped else width


def near_patch_ends(scene, x1, thicknesses=END_ZONE, capped=True):
    """Which points x1 lie in some patch's end zone (end_zone_width)."""
    near = np.zeros(len(x1), dtype=bool)
    for coating in scene.coatings:
        width = end_zone_width(coating, thicknesses, capped)
        for end in scene.patch_ends(coating):
            near |= np.abs(np.asarray(x1) - end) <= width
    return near


TENSION, COMPRESSION, MAGNITUDE = "tension", "compression", "magnitude"


def _extreme(values, x1, x2, kind, end_zone):
    """{value, x1, x2, end_zone} of the largest tension (> 0), compression (< 0) or
    magnitude; None where there is none."""
    if len(values) == 0:
        return None
    i = int(np.argmin(values) if kind == COMPRESSION else np.argmax(values))
    if (kind == TENSION and values[i] <= 0) or (kind == COMPRESSION and values[i] >= 0):
        return None
    return {"value": float(values[i]), "x1": float(x1[i]), "x2": float(x2[i]),
            "end_zone": end_zone}


def _maxima(scene, quantities, x1, x2):
    """For each (name, values, kind): the extreme away from the patches' ends and,
    apart, the one within their end zones (mesh-dependent)."""
    return _maxima_where(near_patch_ends(scene, np.asarray(x1)), quantities, x1, x2)


def _maxima_where(near_end, quantities, x1, x2):
    """_maxima with the points in the end zones given (``near_end``)."""
    x1, x2 = np.asarray(x1), np.asarray(x2)
    away = {name: _extreme(np.asarray(values)[~near_end], x1[~near_end], x2[~near_end], kind,
                           False)
            for name, values, kind in quantities}
    if near_end.any():
        away["at_patch_ends"] = {
            "mesh_dependent": True,
            **{name: _extreme(np.asarray(values)[near_end], x1[near_end], x2[near_end], kind,
                              True)
               for name, values, kind in quantities}}
    return away


def contact_answers(scene, x1, x2, sigma_n):
    """The peak contact pressure (positive) and its position, away from the patches'
    ends and, apart, within their end zones."""
    return _maxima(scene, [("peak_pressure", -np.asarray(sigma_n), TENSION)], x1, x2)


def bond_answers(scene, x1, x2, sigma_n, sigma_t):
    """Peel (the largest tensile sigma_n: the bond opens where it is positive), the
    largest compression and the largest |shear| on one bond (the traction on the base)."""
    return _maxima(scene, [("peel", sigma_n, TENSION), ("compression", sigma_n, COMPRESSION),
                           ("shear", np.abs(sigma_t), MAGNITUDE)], x1, x2)


def coating_answers(scene, nodes, coating=None):
    """The largest von Mises stress of a 2D patch and its position, from its nodes'
    x1, x2, sigma_eq (columns by name), and with ``coating`` (its Coating) the largest
    tensile stress along its top face (face_tension)."""
    found = _maxima(scene, [("von_mises", np.asarray(nodes["sigma_eq"]), MAGNITUDE)],
                    nodes["x1"], nodes["x2"])
    if coating is not None:
        height = _height_over_face(scene.base, nodes["x1"], nodes["x2"])
        _merge(found, _face_tension(scene, nodes, np.abs(height - coating.thickness)
                                    <= 1e-9 * coating.thickness, near_patch_ends))
    return found


def _height_over_face(base, x1, x2):
    """A point's height over the base's face (its depth below it, negative)."""
    x1, x2 = np.asarray(x1, dtype=float), np.asarray(x2, dtype=float)
    return x2 - base.height if base.shape == "block" else np.hypot(x1, x2) - base.radius


def _face_tension(scene, nodes, on_face, near_ends):
    """{"face_tension": ...} (and its end zones' apart) of the nodes ``on_face``: the
    tangential stress t' sigma t along a face parallel to the base's, t = (n2, -n1)."""
    x1, x2 = np.asarray(nodes["x1"])[on_face], np.asarray(nodes["x2"])[on_face]
    if scene.base.shape == "block":
        t1, t2 = np.ones_like(x1), np.zeros_like(x1)
    else:
        radius = np.hypot(x1, x2)
        t1, t2 = x2 / radius, -x1 / radius
    s11, s22, s12 = (np.asarray(nodes[name])[on_face] for name in ("s11", "s22", "s12"))
    along = s11 * t1 ** 2 + 2 * s12 * t1 * t2 + s22 * t2 ** 2
    return _maxima_where(near_ends(scene, x1), [("face_tension", along, TENSION)], x1, x2)


def _merge(found, more):
    """``more``'s maxima into ``found``, end zones with end zones."""
    ends = more.pop("at_patch_ends", None)
    found.update(more)
    if ends:
        found.setdefault("at_patch_ends", {"mesh_dependent": True})
        ends.pop("mesh_dependent")
        found["at_patch_ends"].update(ends)


def substrate_answers(scene, nodes):
    """The base's largest von Mises stress, its position and its depth below the base's
    face, from its nodes' x1, x2, sigma_eq (columns by name; {} without them). A node
    near a patch's end (within its end zone of it, across and below the face) is in the
    end zones: the bond's corner is singular in the base too."""
    if "sigma_eq" not in nodes or len(nodes["sigma_eq"]) == 0:
        return {}
    x1, x2 = np.asarray(nodes["x1"]), np.asarray(nodes["x2"])
    base = scene.base
    depth = (base.height - x2 if base.shape == "block"
             else base.radius - np.hypot(x1, x2))
    reach = max((end_zone_width(c) for c in scene.coatings), default=0.0)
    near = near_patch_ends(scene, x1) & (depth <= reach)
    found = _maxima_where(near, [("von_mises", np.asarray(nodes["sigma_eq"]), MAGNITUDE)],
                          x1, x2)
    for extreme in [found.get("von_mises"), found.get("at_patch_ends", {}).get("von_mises")]:
        if extreme:
            k = int(np.flatnonzero((x1 == extreme["x1"]) & (x2 == extreme["x2"]))[0])
            extreme["depth"] = float(depth[k])
    if all(name in nodes for name in ("s11", "s22", "s12")):
        scale = base.height if base.shape == "block" else base.radius
        _merge(found, _face_tension(scene, nodes, np.abs(depth) <= 1e-9 * scale,
                                    near_patch_ends))
    return found


def fibre_stresses(fields, thickness):
    """sigma11 at the shell's top and bottom faces and the mean transverse shear from its
    forces: the strain is eps11 + xi3 chi11 through the thickness (freefem/shell.idp,
    xi3 along the face's outward normal), so sigma11 = T11/h + 12 M11 xi3 / h^3, at
    xi3 = +-h/2: T11/h +- 6 M11/h^2; the shear's mean is T13/h (columns by name)."""
    membrane = np.asarray(fields["T11"]) / thickness
    bending = 6.0 * np.asarray(fields["M11"]) / thickness ** 2
    return membrane + bending, membrane - bending, np.asarray(fields["T13"]) / thickness


def revolution_fibre_stresses(fields, thickness):
    """A shell of revolution's fibre stresses from its forces per unit length of a circle
    (freefem/shell_revolution.idp: the radial and hoop strains are eps + z kappa through
    the thickness, z along the face's outward normal e_z): the radial stress at the top
    (z = +h/2) and bottom faces, N_r/h +- 6 M_r/h^2, the hoop stress there,
    N_theta/h +- 6 M_theta/h^2, and the mean transverse shear Q/h (columns by name)."""
    def faces(force, moment):
        membrane = np.asarray(fields[force]) / thickness
        bending = 6.0 * np.asarray(fields[moment]) / thickness ** 2
        return membrane + bending, membrane - bending
    return (*faces("N_r", "M_r"), *faces("N_theta", "M_theta"),
            np.asarray(fields["Q"]) / thickness)


def _faces(name, top, bottom):
    """The largest tension and compression on the top and bottom faces, named after
    ``name`` (a prefix)."""
    return [(f"{name}top_tension", top, TENSION), (f"{name}top_compression", top, COMPRESSION),
            (f"{name}bottom_tension", bottom, TENSION),
            (f"{name}bottom_compression", bottom, COMPRESSION)]


def shell_answers(scene, coating, fields):
    """The extreme fibre stresses (tension and compression, top and bottom faces) and the
    largest mean shear of a shell patch, from its fields (columns x1, x2, T11, T13, M11);
    of a shell of revolution (an axisymmetric scene) the radial and the hoop fibre
    stresses ("radial_top_tension", "hoop_top_tension", ...) and the mean shear, from
    N_r, N_theta, Q, M_r, M_theta."""
    if scene.axisymmetric:
        radial_top, radial_bottom, hoop_top, hoop_bottom, shear = revolution_fibre_stresses(
            fields, coating.thickness)
        faces = (_faces("radial_", radial_top, radial_bottom)
                 + _faces("hoop_", hoop_top, hoop_bottom))
    else:
        top, bottom, shear = fibre_stresses(fields, coating.thickness)
        faces = _faces("", top, bottom)
    return _maxima(scene, faces + [("mean_shear", np.abs(shear), MAGNITUDE)],
                   fields["x1"], fields["x2"])


def describe(answers, units, axisymmetric=False):
    """The answers as lines for a person, with the units of the summary's "units"; a
    position along the face is x1, or r on a body of revolution."""
    stress, length = units["stress"], units["length"]
    along = "r" if axisymmetric else "x1"

    def where(extreme):
        depth = (f", {extreme['depth']:.4g} {length} deep" if "depth" in extreme else "")
        return (f"{extreme['value']:.4g} {stress} at {along} = {extreme['x1']:.4g} "
                f"{length}{depth}")
    lines = []
    for group, found in (("", {"contact": answers["contact"]}), ("bonds", answers["bonds"]),
                         ("coatings", answers["coatings"]),
                         ("", {"substrate": answers.get("substrate") or {}})):
        for name, values in found.items():
            away = [f"{quantity.replace('_', ' ')} {where(extreme)}"
                    for quantity, extreme in values.items()
                    if quantity != "at_patch_ends" and extreme]
            ends = [f"{quantity.replace('_', ' ')} {where(extreme)}"
                    for quantity, extreme in values.get("at_patch_ends", {}).items()
                    if quantity != "mesh_dependent" and extreme]
            if not away and not ends:
                continue
            if group == "bonds" and "peel" in values and not values["peel"] and not \
                    values.get("at_patch_ends", {}).get("peel"):
                away.insert(0, "no peel (in compression everywhere)")
            lines.append(f"{name}: " + ", ".join(away or ["none away from the patch ends"])
                         + (f"; in patch end zones (singular, mesh-dependent): "
                            f"{', '.join(ends)}" if ends else ""))
    return lines
