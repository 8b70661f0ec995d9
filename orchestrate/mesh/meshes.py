"""Meshes of the bodies (gmsh) and of the 2D coatings (structured), written for FreeFEM
with meshio.

A body's face is the sequence of pieces of its BodyPlan (orchestrate/mesh/discretization.py):
an interface piece is meshed with exactly its vertices, one edge per interface element,
so that both sides of an interface have their nodes at the same points; free pieces
are meshed by gmsh. Triangles are graded away from the face, as in the paper (about
1372 and 1349 triangles per body at mesh level 1): the size is the face's element size
near the interfaces and the free face as far again as they reach, and grows by GROWTH
per unit distance from there, up to a maximum; on a face sized to the contact
(BodyPlan.grading) the face's own element size is the graded one of its FaceSpacing,
taken as a function of the distance from the contact's centre. A mirror-symmetric body is meshed on
x1 >= 0 and mirrored, so that its mesh is mirror-symmetric too.
"""

from collections import OrderedDict
from contextlib import contextmanager
import copy
import dataclasses
import hashlib
import math
from pathlib import Path
import signal
import threading

from orchestrate.errors import SystemFailure
from orchestrate.files.writing import number_rows

try:
    import gmsh
except OSError as error:                 # its shared library could not be loaded
    raise SystemFailure(f"loading gmsh's library failed: {error} (out of memory, e.g. under "
                        "ulimit -v? or a broken install)") from None
import meshio
import numpy as np

from orchestrate.mesh.body_plans import GROWTH
from orchestrate.faults import checkpoint
from orchestrate.mesh.labels import LABELS


# ---- the 2D coating ---------------------------------------------------------------------

def coating_mesh(plan):
    """Structured triangle mesh of a 2D coating patch: columns at the patch's element
    ends, ``layers`` layers of cells up to its thickness, two triangles per cell (the
    diagonal mirrored left of x1 = 0); its bottom (Bond) and top carry exactly the
    interface nodes."""
    columns = len(plan.nodes) - 1
    offsets = plan.thickness * np.arange(plan.layers + 1) / plan.layers
    offsets[-1] = plan.thickness
    points = np.vstack([plan.face.point(plan.nodes, offset) for offset in offsets])
    node = lambda i, j: j * (columns + 1) + i  # noqa: E731
    triangles = []
    for j in range(plan.layers):
        for i in range(columns):
            a, b, c, d = node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)
            if plan.nodes[i] + plan.nodes[i + 1] < 0:
                triangles += [(a, b, d), (b, c, d)]
            else:
                triangles += [(a, b, c), (a, c, d)]
    edges = {
        "Bond": [(node(i, 0), node(i + 1, 0)) for i in range(columns)],
        "end": [(node(columns, j), node(columns, j + 1)) for j in range(plan.layers)],
        "top": [(node(i + 1, plan.layers), node(i, plan.layers)) for i in range(columns)],
        "start": [(node(0, j + 1), node(0, j)) for j in range(plan.layers)],
    }
    label = {"Bond": "Bond", "end": "Free", "top": plan.top_label, "start": plan.start_label}
    lines = np.array([edge for name in edges for edge in edges[name]])
    line_refs = np.concatenate([np.full(len(edges[name]), LABELS[label[name]]) for name in edges])
    triangles = _counterclockwise(points, np.array(triangles))
    return meshio.Mesh(points, [("line", lines), ("triangle", triangles)],
                       cell_data={"medit:ref": [line_refs, np.full(len(triangles), 1)]})


# ---- bodies -----------------------------------------------------------------------------

# A sweep meshes the same bodies scene after scene (the base of every figure scene, the
# indenter of every scene with the same h2): gmsh's meshes, and the medit text each was
# written as, are kept by plan for the process's life, the last few.
_KEPT = 8
_body_meshes = OrderedDict()        # plan digest -> [mesh, its medit text or None]


def body_mesh(plan):
    """Triangle mesh of a body from its plan (an indenter, a block or a roller)."""
    return copy.deepcopy(_kept_body(plan)[0])


def write_body_mesh(plan, path):
    """Write the mesh of ``plan`` in medit format (write_medit) to ``path``; return the
    mesh."""
    kept = _kept_body(plan)
    if kept[1] is None:
        write_medit(kept[0], path)
        kept[1] = Path(path).read_bytes()
    else:
        Path(path).write_bytes(kept[1])
    return copy.deepcopy(kept[0])


def _kept_body(plan):
    key = _digest(plan)
    if key not in _body_meshes:
        mesh = _mirrored(_gmsh_body(plan)) if plan.mirror else _gmsh_body(plan)
        _body_meshes[key] = [mesh, None]
        while len(_body_meshes) > _KEPT:
            _body_meshes.popitem(last=False)
    _body_meshes.move_to_end(key)
    return _body_meshes[key]


def _digest(value, digest=None):
    """A digest of every number, string and array of a plan (dataclasses, tuples, arrays,
    numbers), with their types: two plans with equal digests mesh alike."""
    top = digest is None
    digest = hashlib.sha256() if top else digest
    digest.update(type(value).__name__.encode())
    if dataclasses.is_dataclass(value):
        for field in dataclasses.fields(value):
            digest.update(field.name.encode())
            _digest(getattr(value, field.name), digest)
    elif isinstance(value, (tuple, list)):
        digest.update(str(len(value)).encode())
        for item in value:
            _digest(item, digest)
    elif isinstance(value, np.ndarray):
        digest.update(str(value.shape).encode() + str(value.dtype).encode())
        digest.update(np.ascontiguousarray(value).tobytes())
    elif value is None or isinstance(value, (bool, int, float, str)):
        digest.update(repr(value).encode())
    else:
        raise TypeError(f"cannot digest a {type(value).__name__} of a mesh plan")
    return digest.hexdigest() if top else digest


class _Outline:
    """Points and curves of one gmsh model, points shared where they coincide."""

    def __init__(self, scale):
        self.geo = gmsh.model.geo
        self.points = []          # (x, y, tag)
        self.tolerance = 1e-12 * scale
        self.labels = {}          # label -> curve tags, in order of first use
        self.face_curves = []     # curves the size field measures the distance to
        self.sequence = []        # every curve, in the order made
        self.centre = None

    def point(self, xy):
        x, y = float(xy[0]), float(xy[1])
        for px, py, tag in self.points:
            if abs(px - x) <= self.tolerance and abs(py - y) <= self.tolerance:
                return tag
        tag = self.geo.addPoint(x, y, 0)
        self.points.append((x, y, tag))
        return tag

    def curve(self, tag, label, face=False):
        self.sequence.append(tag)
        self.labels.setdefault(label, []).append(tag)
        if face:
            self.face_curves.append(tag)
        return tag

    def line(self, a, b, label, face=False):
        return [self.curve(self.geo.addLine(self.point(a), self.point(b)), label, face)]

    def arc(self, a, b, label, face=False):
        """Arcs about the origin from a to b (clockwise when going from a to b at
        increasing arc length on the face), in pieces of at most 90 degrees."""
        if self.centre is None:
            self.centre = self.geo.addPoint(0, 0, 0)
        radius = math.hypot(*a)
        start, end = math.atan2(a[0], a[1]), math.atan2(b[0], b[1])
        if end <= start:
            end += 2 * math.pi
        pieces = max(1, math.ceil((end - start) / (math.pi / 2) - 1e-9))
        angles = np.linspace(start, end, pieces + 1)
        corners = [a] + [radius * np.array([math.sin(t), math.cos(t)]) for t in angles[1:-1]] + [b]
        return [self.curve(self.geo.addCircleArc(self.point(p), self.centre, self.point(q)),
                           label, face) for p, q in zip(corners, corners[1:])]


def _face_curves(outline, plan):
    """The face's curves from its start to its end; returns the interface curves whose
    nodes must be exactly their vertices (transfinite lines) and the node count."""
    transfinite = []
    interface_points = [p.points for p in plan.face if p.label != "Free"]
    for k, piece in enumerate(plan.face):
        if piece.label != "Free":
            if piece.uniform:
                tag = outline.line(piece.points[0], piece.points[-1], piece.label, face=True)[0]
                transfinite.append((tag, len(piece.points)))
            else:
                for a, b in zip(piece.points, piece.points[1:]):
                    tag = outline.line(a, b, piece.label, face=True)[0]
                    transfinite.append((tag, 2))
            continue
        for near, a, b in _split_free(piece, plan, interface_points):
            if piece.curve == "arc":
                outline.arc(a, b, "Free", face=near)
            elif piece.curve == "profile":
                xs = np.linspace(a[0], b[0], max(2, math.ceil(abs(b[0] - a[0]) / (4 * plan.face_size)) + 1))
                heights = plan.lowest + plan.indenter.sag(xs - plan.indenter.centre)
                heights[0], heights[-1] = a[1], b[1]
                profile = np.column_stack([xs, heights])
                for p, q in zip(profile, profile[1:]):
                    outline.line(p, q, "Free", face=near)
            else:
                outline.line(a, b, "Free", face=near)
    return transfinite


def _split_free(piece, plan, interface_points):
    """A free piece as (near the interfaces?, start, end) parts: the part within
    ``plan.near`` of an interface vertex is refined like the face."""
    a, b = piece.points[0], piece.points[-1]
    if not interface_points:
        return [(False, a, b)]
    vertices = np.vstack(interface_points)
    touches_a = np.min(np.linalg.norm(vertices - a, axis=1)) < 1e-9 * (1 + plan.near)
    touches_b = np.min(np.linalg.norm(vertices - b, axis=1)) < 1e-9 * (1 + plan.near)
    length = _curve_length(piece, a, b)
    if length <= plan.near * (1 + 1e-9) and (touches_a or touches_b):
        return [(True, a, b)]
    parts, start, stop = [], 0.0, length
    if touches_a:
        start = plan.near
    if touches_b:
        stop = length - plan.near
    if start >= stop:
        return [(True, a, b)]
    cut_a, cut_b = _along(piece, a, b, start), _along(piece, a, b, stop)
    if touches_a:
        parts.append((True, a, cut_a))
    parts.append((False, cut_a if touches_a else a, cut_b if touches_b else b))
    if touches_b:
        parts.append((True, cut_b, b))
    return parts


def _curve_length(piece, a, b):
    if piece.curve == "arc":
        start, end = math.atan2(a[0], a[1]), math.atan2(b[0], b[1])
        if end <= start:
            end += 2 * math.pi
        return math.hypot(*a) * (end - start)
    return float(np.linalg.norm(b - a)) if piece.curve == "line" else abs(b[0] - a[0])


def _along(piece, a, b, distance):
    """The point ``distance`` along a free piece from a."""
    if piece.curve == "arc":
        radius = math.hypot(*a)
        angle = math.atan2(a[0], a[1]) + distance / radius
        return radius * np.array([math.sin(angle), math.cos(angle)])
    fraction = distance / _curve_length(piece, a, b)
    return a + fraction * (b - a)


def _gmsh_body(plan):
    scale = max(abs(plan.left), abs(plan.right), abs(plan.far), plan.radius, 1.0)
    with _gmsh_session():
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(plan.shape)
        outline = _Outline(scale)
        transfinite = _face_curves(outline, plan)
        loops = _close_outline(outline, plan)
        geo = gmsh.model.geo
        surface = geo.addPlaneSurface([geo.addCurveLoop(loop) for loop in loops])
        geo.synchronize()
        for tag, nodes in transfinite:
            gmsh.model.mesh.setTransfiniteCurve(tag, nodes)
        level = plan.mesh_level
        fields = gmsh.model.mesh.field
        distance = fields.add("Distance")
        fields.setNumbers(distance, "CurvesList", outline.face_curves)
        fields.setNumber(distance, "Sampling", 100 * level)
        size = fields.add("MathEval")
        on_face = f"{plan.face_size}"
        if plan.grading is not None:       # the face's own length there (FaceSpacing;
                                           # problem_size.face_size_at counts with it)
            x_c, y_c, reach, growth, far = plan.grading
            # a negative centre in parentheses: gmsh's parser refuses "x - -1.5" (and
            # aborts the process)
            on_face = (f"Min({plan.face_size} + {growth}*Max(Sqrt((x - ({x_c!r}))^2 + "
                       f"(y - ({y_c!r}))^2) - {reach!r}, 0), {far!r})")
        fields.setString(size, "F", f"Min({on_face} + {GROWTH / level}*F{distance}, "
                                    f"{plan.max_size / level})")
        fields.setAsBackgroundMesh(size)
        for option in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints",
                       "MeshSizeFromCurvature"):
            gmsh.option.setNumber(f"Mesh.{option}", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)  # Frontal-Delaunay: well-shaped triangles
        for name, curves in outline.labels.items():
            gmsh.model.addPhysicalGroup(1, curves, LABELS[name], name=name)
        gmsh.model.addPhysicalGroup(2, [surface], 1, name=plan.shape)
        gmsh.model.mesh.generate(2)
        mesh = _to_meshio()
    _snap_to_face(mesh.points, plan)
    return mesh


def _close_outline(outline, plan):
    """The curves after the face, closing the outline; returns the curve loops."""
    face_curves = list(outline.sequence)
    first = plan.face[0].points[0]
    last = plan.face[-1].points[-1]
    side = "Symmetry" if plan.half or plan.mirror else "Free"
    if plan.shape in ("indenter", "block"):
        far_label = "Stamp" if plan.shape == "indenter" else "Clamped"
        right = outline.line(last, (plan.right, plan.far), "Free")
        far = outline.line((plan.right, plan.far), (plan.left, plan.far), far_label)
        left = outline.line((plan.left, plan.far), first, side)
        # group order as the paper's meshes were built: face, far side, symmetry, free
        _reorder(outline.labels, far_label, side)
        return [face_curves + right + far + left]
    bore = plan.bore
    if plan.half or plan.mirror:
        down = outline.line(last, (0.0, -bore), "Symmetry")
        shaft = outline.arc(np.array([0.0, bore]), np.array([0.0, -bore]), "Clamped")
        up = outline.line((0.0, bore), first, "Symmetry")
        return [face_curves + down + [-tag for tag in reversed(shaft)] + up]
    shaft = outline.arc(np.array([0.0, -bore]), np.array([0.0, bore]), "Clamped")
    shaft += outline.arc(np.array([0.0, bore]), np.array([0.0, -bore]), "Clamped")
    return [face_curves, shaft]


def _reorder(labels, far_label, side):
    order = [name for name in labels if name not in (far_label, side, "Free")]
    order += [far_label, side] + (["Free"] if "Free" in labels else [])
    items = {name: labels[name] for name in order if name in labels}
    labels.clear()
    labels.update(items)


def _snap_to_face(points, plan):
    """Put the face's nodes exactly where the interfaces have them (gmsh is off by
    ~1e-12 inside transfinite lines), and a flat face's nodes exactly on its line."""
    vertices = np.vstack([p.points for p in plan.face if p.label != "Free"])
    spacing = plan.face_size
    heights = {float(y) for p in plan.face for y in p.points[:, 1]}
    if len(heights) == 1 and all(p.curve in ("edges", "line") for p in plan.face):
        y_face = heights.pop()
        on_face = np.flatnonzero(np.abs(points[:, 1] - y_face) < 1e-9 * spacing)
        _snap(points[:, :1], on_face, vertices[:, :1], 1e-6 * spacing)
        points[on_face, 1] = y_face
        return
    _snap(points, np.arange(len(points)), vertices, 1e-6 * spacing)


def _snap(points, which, targets, within):
    """Move each of the points ``which`` (rows of ``points``, in place) onto its nearest
    target where that is closer than ``within``. The targets within ``within`` in x1 of
    a point are a run of them sorted by x1: a face's vertices lie far apart against
    ``within``, so a run holds one or two (a face's step) and a k-d tree, whose module
    took 0.16 s to load in every process, buys nothing."""
    order = np.argsort(targets[:, 0], kind="stable")
    sorted_x = targets[order, 0]
    moved = points[which]
    first = np.searchsorted(sorted_x, moved[:, 0] - within, side="left")
    end = np.searchsorted(sorted_x, moved[:, 0] + within, side="right")
    best, nearest = np.full(len(which), np.inf), np.zeros(len(which), dtype=int)
    for k in range(int(np.max(end - first, initial=0))):
        candidate = first + k
        inside = candidate < end
        rows = order[np.minimum(candidate, len(order) - 1)]
        distance = np.where(inside, np.linalg.norm(moved - targets[rows], axis=1), np.inf)
        closer = distance < best
        best[closer], nearest[closer] = distance[closer], rows[closer]
    close = best < within
    points[which[close]] = targets[nearest[close]]


def _mirrored(mesh):
    """A mesh of x1 >= 0 with its mirror image; the symmetry edges become interior."""
    points = mesh.points
    on_axis = points[:, 0] == 0.0
    mirror_index = np.arange(len(points))
    off_axis = np.flatnonzero(~on_axis)
    mirror_index[off_axis] = len(points) + np.arange(len(off_axis))
    mirrored_points = points[off_axis] * np.array([-1.0, 1.0])
    all_points = np.vstack([points, mirrored_points])
    triangles = mesh.cells_dict["triangle"]
    lines = mesh.cells_dict["line"]
    line_refs = mesh.cell_data_dict["medit:ref"]["line"]
    keep = line_refs != LABELS["Symmetry"]
    lines, line_refs = lines[keep], line_refs[keep]
    all_triangles = np.vstack([triangles, mirror_index[triangles][:, [0, 2, 1]]])
    all_lines = np.vstack([lines, mirror_index[lines][:, [1, 0]]])
    all_refs = np.concatenate([line_refs, line_refs])
    triangle_refs = mesh.cell_data_dict["medit:ref"]["triangle"]
    return meshio.Mesh(all_points, [("line", all_lines), ("triangle", all_triangles)],
                       cell_data={"medit:ref": [all_refs, np.concatenate([triangle_refs] * 2)]})


@contextmanager
def _gmsh_session():
    """gmsh initialised for one model. gmsh installs its own C-level signal handlers
    while it works; the signals that stop a run are held back meanwhile (blocked: they wait,
    pending) and the driver's handlers put back before they are let through, so that a
    signal during meshing stops the run, with its clean-up, once the body is meshed.
    Only the main thread has signal handlers (a Dask worker meshes in another thread)."""
    main_thread = threading.current_thread() is threading.main_thread()
    held = {signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT}
    handlers = ({sig: signal.getsignal(sig) for sig in held | {signal.SIGPIPE}}
                if main_thread else {})
    if main_thread:
        signal.pthread_sigmask(signal.SIG_BLOCK, held)
    gmsh.initialize(interruptible=False)
    try:
        checkpoint("meshing")
        yield
    finally:
        gmsh.finalize()
        for sig, handler in handlers.items():
            if handler is not None:
                signal.signal(sig, handler)
        if main_thread:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, held)


def _to_meshio():
    """The current gmsh model's mesh, with physical-group numbers as medit references."""
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    index = np.full(int(node_tags.max()) + 1, -1, dtype=np.int64)
    index[node_tags.astype(np.int64)] = np.arange(len(node_tags))
    points = coords.reshape(-1, 3)[:, :2]
    cells, refs = [], []
    for dim, kind, nodes_per_cell in ((1, "line", 2), (2, "triangle", 3)):
        blocks, block_refs = [], []
        for _, tag in gmsh.model.getPhysicalGroups(dim):
            for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, tag):
                _, _, element_nodes = gmsh.model.mesh.getElements(dim, entity)
                connectivity = index[element_nodes[0].astype(np.int64)].reshape(-1, nodes_per_cell)
                blocks.append(connectivity)
                block_refs.append(np.full(len(connectivity), tag, dtype=np.int64))
        connectivity = np.vstack(blocks)
        if kind == "triangle":
            connectivity = _counterclockwise(points, connectivity)
        cells.append((kind, connectivity))
        refs.append(np.concatenate(block_refs))
    # only the triangles' nodes (gmsh also meshes the centre point of circle arcs)
    used = np.zeros(len(points), dtype=bool)
    used[cells[1][1].ravel()] = True
    renumber = np.cumsum(used) - 1
    cells = [(kind, renumber[connectivity]) for kind, connectivity in cells]
    return meshio.Mesh(points[used], cells, cell_data={"medit:ref": refs})


def _counterclockwise(points, triangles):
    """FreeFEM wants positively oriented triangles; gmsh follows the curve loop."""
    a, b, c = (points[triangles[:, i]] for i in range(3))
    area2 = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    flipped = triangles.copy()
    flipped[area2 < 0] = flipped[area2 < 0][:, [0, 2, 1]]
    return flipped


MEDIT_CELLS = {"line": b"Edges", "triangle": b"Triangles"}


def write_medit(mesh, path):
    """Write a mesh in medit ``.mesh`` format, which FreeFEM's ``readmesh`` reads: its
    vertices (label 1: FreeFEM labels a boundary by its edges), then its edges and
    triangles, numbered from 1, each with its "medit:ref", as meshio writes the format
    (whose writer, a Python format per line, spent 20 ms on a body of a thousand
    vertices, a tenth of a cold run's set-up at the median)."""
    points = np.asarray(mesh.points, dtype=float)
    parts = [b"MeshVersionFormatted 2\nDimension 2\n\nVertices\n%d\n" % len(points),
             number_rows([points[:, 0], points[:, 1], np.ones(len(points), dtype=int)],
                         b" ", b"\n")]
    for block, refs in zip(mesh.cells, mesh.cell_data["medit:ref"]):
        if block.type not in MEDIT_CELLS:
            raise ValueError(f"a medit mesh for FreeFEM holds no {block.type} cells")
        parts += [b"\n%s\n%d\n" % (MEDIT_CELLS[block.type], len(block.data)),
                  number_rows([*(np.asarray(block.data) + 1).T, np.asarray(refs)],
                              b" ", b"\n")]
    parts.append(b"\nEnd\n")
    with open(path, "wb") as out:
        out.write(b"".join(parts))
