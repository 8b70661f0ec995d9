"""What the mesher needs of a body meshed by gmsh (orchestrate/mesh/meshes.py): its face as
pieces, interface pieces with exactly the interface's vertices, free pieces between
them, and the rest of its outline. Built from the interfaces of
orchestrate/mesh/discretization.py.
"""

from dataclasses import dataclass
import math
from typing import Optional

import numpy as np

GROWTH = 0.115     # mesh size grows by GROWTH per unit distance from the face (level 1),
MAX_SIZE = 0.5     # up to MAX_SIZE (or a sixteenth of a larger body): the paper's ~1370
                   # triangles per body


@dataclass(frozen=True)
class FacePiece:
    """A piece of a body's face for the mesher: an interface piece is exactly its
    vertices, one mesh edge between neighbours (``uniform``: equal edges on a line, one
    transfinite gmsh line); a free piece is a curve between its end points: a line, an
    arc about the origin, or the indenter's profile."""
    label: str                 # "Contact", "Bond" or "Free"
    points: np.ndarray         # (k, 2)
    curve: str                 # "edges", "line", "arc" or "profile"
    uniform: bool = False


@dataclass(frozen=True)
class BodyPlan:
    """A body meshed by gmsh (orchestrate/mesh/meshes.py): its outline from its face pieces.

    shape "indenter": face at the bottom, stamp on top at x2 = far; "block": face on top,
    clamped at x2 = far = 0; "roller": face on the circle of radius ``radius``, clamped on
    the bore. ``left``/``right``: x1 of the ends of an indenter or block; the face runs
    from left to right (a roller's from its top clockwise). A half model (``half``) has
    symmetry at x1 = 0 and only x1 >= 0; ``mirror``: mesh that half and mirror it."""
    shape: str
    face: tuple
    left: float
    right: float
    far: float
    half: bool
    mirror: bool
    face_size: float           # element length on the face, where the mesh is finest
    near: float                # the face stays that fine up to this far from its interfaces
    max_size: float
    mesh_level: int
    radius: float = 0.0        # roller
    bore: float = 0.0          # roller
    indenter: Optional[object] = None   # the Indenter, for a profile curve
    lowest: float = 0.0        # the indenter's lowest point
    # a face sized to the contact (discretization.py's FaceSpacing): (x1, x2 of the
    # contact's centre, the reach of its finest elements, their growth beyond, the
    # longest); None: face_size everywhere on the face
    grading: Optional[tuple] = None


def _interface_piece(label, vertices):
    edges = np.diff(vertices, axis=0)
    lengths = np.linalg.norm(edges, axis=1)
    straight = np.all(np.abs(edges[:, 1]) == 0) or np.all(np.abs(edges[:, 0]) == 0)
    uniform = bool(straight and np.allclose(lengths, lengths[0], rtol=1e-12, atol=0))
    return FacePiece(label, vertices, "edges", uniform)


def _near(pieces):
    """How far from its interfaces a face stays fine: as far again as they reach."""
    interface = [p.points for p in pieces if p.label != "Free"]
    if not interface:
        return 0.0
    points = np.vstack(interface)
    return float(np.max(np.ptp(points, axis=0)))


def indenter_plan(scene, settings, indenter_face, contacts, face_size, grading=None):
    indenter = scene.indenter
    half, mirror = scene.symmetric, scene.mirror_symmetric
    left = 0.0 if half or mirror else indenter.centre - indenter.width
    right = indenter.width if half else indenter.centre + indenter.width
    pieces = [_interface_piece("Contact", c.sides[0].place[0::2]) for c in contacts]
    if mirror:
        pieces = _right_half(pieces)
    free_curve = "line" if indenter.flat or indenter.face_mesh == "flat" else "profile"
    height = (lambda x: indenter_face.lowest) if free_curve == "line" else indenter_face.height
    first, last = pieces[0].points[0], pieces[-1].points[-1]
    face = []
    if first[0] > left + 1e-12:
        face.append(FacePiece("Free", np.array([[left, height(left)], first]), free_curve))
    face += pieces
    if last[0] < right - 1e-12:
        face.append(FacePiece("Free", np.array([last, [right, height(right)]]), free_curve))
    top = indenter_face.lowest + indenter.height
    return BodyPlan("indenter", tuple(face), left, right, top, half, mirror, face_size,
                    _near(face), _max_size(indenter.width, indenter.height),
                    settings.mesh_level, indenter=indenter, lowest=indenter_face.lowest,
                    grading=grading)


def _right_half(pieces):
    """The pieces of a mirror-symmetric face on x1 >= 0 (a node sits at x1 = 0)."""
    kept = []
    for piece in pieces:
        x = piece.points[:, 0]
        if x[-1] <= 0:
            continue
        if x[0] < 0:
            piece = _interface_piece(piece.label, piece.points[x >= 0])
        kept.append(piece)
    return kept


def _max_size(*extent):
    return max(MAX_SIZE, max(extent) / 16.0)


def base_plan(scene, settings, face, contacts, bonds, face_size, grading=None):
    base = scene.base
    half, mirror = scene.symmetric, scene.mirror_symmetric
    runs = sorted([(c.s[0], c.s[-1], "Contact", c) for c in contacts
                   if c.sides[1].subdomain == "base"]
                  + [(b.s[0], b.s[-1], "Bond", b) for b in bonds], key=lambda r: r[0])
    if base.shape == "block":
        start = 0.0 if half or mirror else -base.width
        end = base.width
    else:
        start = 0.0 if half or mirror else -math.pi * base.radius
        end = math.pi * base.radius
    pieces = []
    for a, b, label, interface in runs:
        vertices = interface.sides[1].place[0::2]
        pieces.append(_interface_piece(label, vertices))
    if mirror:
        pieces = _right_half(pieces)
    free = "line" if base.shape == "block" else "arc"
    face_pieces, cursor = [], start

    def ends(a, b):
        points = face.point(np.array([a, b]))
        points[np.abs(points[:, 0]) < 1e-12 * abs(end), 0] = 0.0   # on the axis exactly
        return points

    def s_of(point):
        return point[0] if base.shape == "block" else base.radius * math.atan2(point[0], point[1])

    for piece in pieces:
        s0 = s_of(piece.points[0])
        if s0 > cursor + 1e-12:
            face_pieces.append(FacePiece("Free", ends(cursor, s0), free))
        face_pieces.append(piece)
        cursor = s_of(piece.points[-1])
    if end > cursor + 1e-12:
        face_pieces.append(FacePiece("Free", ends(cursor, end), free))
    if base.shape == "block":
        return BodyPlan("block", tuple(face_pieces), start, end, 0.0, half, mirror, face_size,
                        _near(face_pieces), _max_size(base.width, base.height),
                        settings.mesh_level, grading=grading)
    return BodyPlan("roller", tuple(face_pieces), start, end, 0.0, half, mirror, face_size,
                    _near(face_pieces), _max_size(base.radius), settings.mesh_level,
                    radius=base.radius, bore=base.shaft_radius, grading=grading)


