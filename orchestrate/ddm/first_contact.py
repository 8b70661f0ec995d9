"""The loop's a priori start: the state a cold start begins from, and the first contact
set and friction states predicted from the scene before any solve (robin.py's
first_contact_set takes the contact set where the first state interpenetrates nowhere).

The contact set is the points within the a priori half-width (Strategy.first_contact),
or, where those lie on several contact faces under a force, the two bodies' contact as
half-planes across the faces' actual gap (model/half_space_contact.py); the friction
states under partial slip are Cattaneo's.
"""

import math

import numpy as np

from orchestrate.ddm.state import StateLayout
from orchestrate.model.half_space_contact import contact_pressure, face_strips


def held_indenter_state(problem, layout):
    """The zero state, but for a rigid indenter under a descent: its traces are known
    (its one unknown q = -Delta: the trace c2 q, subdomain_rigid.idp), so the first
    contact set is where its face at that descent passes the base's (the zero state
    interpenetrates nowhere, and an empty set leaves nothing to exchange)."""
    x = layout.zeros()
    scene = problem.scene
    if scene.indenter.rigid and scene.load.displacement is not None:
        for i in layout.contact_indices:
            c2 = problem.interfaces[i].sides[0].coefficients[0][:, 1]
            x[layout.slices["u", i, 0]] = -scene.load.displacement * c2
    return x


def predicted_contact(problem, layout, half_width):
    """The contact points' distances from the contact's centre over ``half_width`` (b),
    in the layout's order, the points within it (at most 1) the a priori contact set;
    None without an estimate. Where those points span several contact faces under a
    force, the set is the half-planes' contact across the faces' gap instead
    (profile_contact): 0 in it, infinite elsewhere."""
    if not half_width:
        return None
    distance = _distance(problem, layout, half_width)
    across = profile_contact(problem, layout, distance)
    return distance if across is None else np.where(across, 0.0, np.inf)


def profile_contact(problem, layout, distance):
    """Where the a priori contact (``distance`` at most 1) spans several contact faces
    under a force in plane strain, such as a cylinder across thin pads and the bare base
    between them: the contact points the two bodies' half-planes touch across the faces'
    actual gap (model/half_space_contact.py), else None. A half-width from one face's
    layered contact left the gallery's pads' first set 66 points where the answer's has
    73, across the middle pad, the bare steel between it and the next (where the
    cylinder touches only the middle of the gap) and that pad: the loop walked through
    six sets, 64 iterations at mesh level 1."""
    scene = problem.scene
    if not _spans_faces(problem, layout, distance):
        return None
    lower, upper = zip(*(face_strips(problem.interfaces[i].position[:, 0])
                         for i in layout.contact_indices))
    indenter, base = scene.indenter, scene.base
    compliance = ((0.0 if indenter.rigid else (1.0 - indenter.nu ** 2) / indenter.E)
                  + (1.0 - base.nu ** 2) / base.E)
    solved = contact_pressure(np.concatenate(lower), np.concatenate(upper), layout.gap,
                              compliance, scene.load.force, mirrored=scene.symmetric)
    return None if solved is None else solved[0] > 0.0


def _spans_faces(problem, layout, distance):
    """Whether, under a force in plane strain, the points within the a priori contact
    (``distance`` at most 1) lie on several contact faces."""
    scene = problem.scene
    if scene.load.force is None or scene.axisymmetric:
        return False
    return sum(bool(np.any(distance[rows] <= 1.0)) for _, rows in layout.contact_slices()) > 1


def contact_spans_faces(problem, half_width):
    """Whether ``problem``'s first contact set is the half-planes' contact across its
    faces' gap (profile_contact) rather than the points within ``half_width`` (b)."""
    if not half_width:
        return False
    layout = StateLayout(problem.interfaces)
    return _spans_faces(problem, layout, _distance(problem, layout, half_width))


def _distance(problem, layout, half_width):
    """The contact points' distances from the contact's centre over ``half_width``."""
    x1 = np.concatenate([problem.interfaces[i].position[:, 0] for i in layout.contact_indices])
    return np.abs(x1 - problem.scene.contact_centre) / half_width


def predicted_friction_states(problem, layout, half_width):
    """Partial slip's friction states as Cattaneo's: slipping (phi the sign of Q) where
    |x1 - centre| lies between c = a sqrt(1 - |Q| / (mu P)) and the a priori half-width
    a, sticking elsewhere; all sticking without an estimate, under a given shift or a
    given descent (P is then the answer's). In
    the layout's order of the friction points. (Measured from a cold start, Q = mu P / 2:
    a bare block 68 iterations and 8 contact sets down to 60 and 2, a stretch shell
    under 3 E 92 and 13 down to 78 and 5, a 2D coating 70 and 6 down to 69 and 4; the
    opposite sign took 75-91.)"""
    scene, q = problem.scene, problem.scene.load.tangential_force
    faces = [problem.interfaces[i] for i in layout.friction_indices]
    if not half_width or q is None or not faces or scene.load.force is None:
        return np.zeros(sum(face.size for face in faces))
    least = min(float(np.min(face.friction)) for face in faces)
    stick = half_width * math.sqrt(max(0.0, 1.0 - abs(q) / (least * scene.load.force)))
    distance = np.abs(np.concatenate([face.position[:, 0] for face in faces])
                      - scene.contact_centre)
    return np.where((distance > stick) & (distance <= half_width), np.sign(q), 0.0)
