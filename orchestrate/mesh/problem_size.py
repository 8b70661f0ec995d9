"""The size of a problem, estimated before any mesh is made, against the machine.

A body meshed by gmsh has its face's element size s0 near its interfaces, growing by g
per unit distance up to s_max: about L / (c g) (1/s0 - 1/s_max) triangles along a fine
face of length L and A / (c s_max^2) over the rest of its area A, with c = TRIANGLE_AREA
(the area of a triangle of size s is about c s^2; the paper's bodies: 1380 triangles).
On a face sized to the contact, s0 is the face's own graded size at each stretch
(counted at the finest all along, the gallery's estimates were 1.5-3.8 times its
meshes' unknowns).
A P2 vector field has about 4 unknowns per triangle. Memory: MEMORY_PER_DOF per unknown
(measured: 430 MB for an 86 000-dof body at mesh level 4, with MUMPS's factors) and
MEMORY_PER_WORKER per FreeFEM process. A run is refused before any work when its
estimate exceeds Settings.memory_limit (default: 3/4 of the memory free now).

A direct solve of each contact set holds, in the driver, dense matrices of the interface
state: about MEMORY_PER_INTERFACE_PAIR bytes per pair of interface unknowns (measured:
1.0 GB at the peak for the near-rigid cylinder's 3848 at mesh level 3), which
interface_system_memory counts against the same limit.
"""

import math

import numpy as np

from orchestrate.mesh.body_plans import GROWTH, BodyPlan
from orchestrate.mesh.discretization import CoatingPlan
from orchestrate.errors import ParameterError

TRIANGLE_AREA = 0.45
MEMORY_PER_DOF = 6e3        # bytes
MEMORY_PER_WORKER = 100e6   # bytes
GIB = 2.0 ** 30
MEMORY_PER_INTERFACE_PAIR = 64.0   # bytes: two dense copies of (2 n)^2 doubles


def body_triangles(plan):
    """Estimated triangles of a gmsh body: along its face, each stretch at the face's own
    element size there (a face sized to the contact is graded: BodyPlan.grading)."""
    level = plan.mesh_level
    s_max, growth = plan.max_size / level, GROWTH / level
    fine = 0.0                           # sum of length * (1/s0 - 1/s_max) along the face
    for piece in plan.face:
        lengths, middles = _stretches(piece)
        share = 1.0
        if piece.label == "Free":        # fine only near the interfaces
            share = min(1.0, 2 * plan.near / max(float(np.sum(lengths)), 1e-300))
        sizes = face_size_at(plan, middles)
        fine += share * float(np.sum(lengths * np.maximum(1 / sizes - 1 / s_max, 0.0)))
    if plan.shape == "roller":
        area = math.pi * (plan.radius ** 2 - plan.bore ** 2) * (0.5 if plan.half or plan.mirror else 1)
    else:
        face_height = plan.lowest if plan.shape == "indenter" else plan.face[0].points[0][1]
        area = (plan.right - plan.left) * abs(plan.far - face_height)
    triangles = fine / (TRIANGLE_AREA * growth) + area / (TRIANGLE_AREA * s_max ** 2)
    return triangles * (2 if plan.mirror else 1)


def face_size_at(plan, points):
    """The mesh size gmsh is given on the face at ``points`` (meshes.py's size field)."""
    sizes = np.full(len(points), float(plan.face_size))
    if plan.grading is not None:
        x_c, y_c, reach, growth, far = plan.grading
        distance = np.hypot(points[:, 0] - x_c, points[:, 1] - y_c)
        sizes = np.minimum(sizes + growth * np.maximum(distance - reach, 0.0), far)
    return sizes


# A free piece's curve sampled in this many stretches for its sizes
FREE_SAMPLES = 64


def _stretches(piece):
    """(lengths, midpoints) of a face piece's stretches: an interface piece's edges; a
    free line, profile (as its chord) or arc about the origin cut in FREE_SAMPLES."""
    points = piece.points
    if piece.curve == "edges":
        return (np.linalg.norm(np.diff(points, axis=0), axis=1),
                0.5 * (points[1:] + points[:-1]))
    a, b = points[0], points[-1]
    if piece.curve == "arc":
        radius = math.hypot(*a)
        start, end = (math.atan2(p[0], p[1]) for p in (a, b))
        angles = start + ((end - start) % (2 * math.pi)) * (np.arange(FREE_SAMPLES) + 0.5) / FREE_SAMPLES
        middles = radius * np.column_stack([np.sin(angles), np.cos(angles)])
        length = radius * ((end - start) % (2 * math.pi))
    else:
        t = (np.arange(FREE_SAMPLES) + 0.5) / FREE_SAMPLES
        middles = a + t[:, None] * (b - a)
        length = float(np.linalg.norm(b - a))
    return np.full(FREE_SAMPLES, length / FREE_SAMPLES), middles


def estimated_dofs(problem):
    """{subdomain: estimated unknowns}."""
    dofs = {}
    for name, subdomain in problem.subdomains.items():
        plan = subdomain.plan
        if subdomain.kind == "rigid":
            dofs[name] = 1
        elif isinstance(plan, BodyPlan):
            dofs[name] = 4 * body_triangles(plan)
        elif isinstance(plan, CoatingPlan):
            dofs[name] = 2 * (2 * len(plan.nodes) - 1) * (2 * plan.layers + 1)
        else:                            # P4 fields v, w, gamma (and P2 epsilon)
            dofs[name] = 3 * (4 * (len(plan.nodes) - 1) + 1) + (
                2 * (len(plan.nodes) - 1) + 1 if plan.thickness_stretch else 0)
    return dofs


def available_memory():
    """Bytes of memory free now (MemAvailable), or None where it cannot be read."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return float(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def memory_limit(settings):
    """(bytes, the limit in words) a run may take: Settings.memory_limit, else 3/4 of
    the memory free now; (None, None) where that cannot be told."""
    if settings.memory_limit is not None:
        return settings.memory_limit * GIB, f"memory_limit = {settings.memory_limit:g} GiB"
    free = available_memory()
    if free is None:
        return None, None
    return 0.75 * free, f"3/4 of the {free / GIB:.1f} GiB free (memory_limit)"


def interface_unknowns(problem):
    """The interface unknowns of every side of every interface."""
    return sum(2 * i.size * i.components for i in problem.interfaces)


def interface_system_memory(problem):
    """Bytes a direct solve of each contact set holds in the driver (the module's
    docstring)."""
    return MEMORY_PER_INTERFACE_PAIR * interface_unknowns(problem) ** 2


def check_size(problem):
    """Refuse a problem whose estimated memory exceeds the limit, before any work."""
    dofs = estimated_dofs(problem)
    memory = sum(MEMORY_PER_DOF * n + MEMORY_PER_WORKER for n in dofs.values())
    limit_bytes, what = memory_limit(problem.settings)
    if limit_bytes is None:
        return dofs
    if memory > limit_bytes:
        largest = max(dofs, key=dofs.get)
        raise ParameterError(
            f"mesh_level = {problem.settings.mesh_level}, element_size = "
            f"{problem.settings.element_size:g}: the problem is estimated at "
            f"{sum(dofs.values()):.3g} unknowns ({largest}: {dofs[largest]:.3g}) and "
            f"{memory / GIB:.1f} GiB of memory, above {what}: coarsen the mesh "
            "(mesh_level, element_size), thicken a 2D coating, or raise memory_limit",
            "mesh_level")
    return dofs


def check_direct_size(problem):
    """Refuse a direct solve (asked: inner_solve = "direct") whose dense interface
    system exceeds the limit, before any work."""
    memory = interface_system_memory(problem)
    limit_bytes, what = memory_limit(problem.settings)
    if limit_bytes is not None and memory > limit_bytes:
        raise ParameterError(
            f"inner_solve = \"direct\": its dense interface system of "
            f"{interface_unknowns(problem)} interface unknowns is estimated at "
            f"{memory / GIB:.1f} GiB, above {what}: iterate (inner_solve = \"iterate\" or "
            "\"auto\"), coarsen the mesh or raise memory_limit", "inner_solve")
