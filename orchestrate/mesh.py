"""Meshes of the bodies and of the 2D coating, written for FreeFEM with meshio.

Omega1 and Omega3 are rectangles meshed by gmsh with triangles graded towards the face
that touches the coating, as in the paper (about 1372 and 1349 triangles at mesh level
1). Along the coated part of that face, [0, l2], the mesh has exactly the interface
nodes: ``interface_elements`` equal edges, each of them one shell element, or one column
of the 2D coating's structured mesh.
"""

from contextlib import contextmanager
from pathlib import Path
import signal
import threading

import math

import gmsh
import meshio
import numpy as np

from .labels import LABELS

# Mesh size near the coated face at level 1 is l2 / 32; it grows by GROWTH per unit
# distance from that face up to MAX_SIZE. These two numbers give the paper's ~1370
# triangles per body.
GROWTH = 0.115
MAX_SIZE = 0.5


# The 2D coating: one layer of cells per b/8 of height, as the paper's 64 ... 512
# triangles for h2 = b/8 ... b, and at least one layer; a cell at most MAX_ASPECT times
# as wide as it is high, so a thin coating refines the interface, and with it the
# bodies' coated faces (the cost the paper alludes to for h2 <= b/16).
COATING_LAYER_HEIGHT = 0.125
MAX_ASPECT = 2.0


def interface_nodes(coating_length, elements):
    """Node abscissae of the shell and of the bodies on S12 and S32."""
    return np.linspace(0.0, coating_length, elements + 1)


def coating_layers(scene, settings):
    """Layers of cells across the 2D coating."""
    return settings.mesh_level * max(1, round(scene.h2 / COATING_LAYER_HEIGHT))


def interface_elements(scene, settings):
    """Elements along S12 and S23: 32 per mesh level, more for a thin 2D coating."""
    elements = settings.shell_elements * settings.mesh_level
    if settings.model == "elastic":
        layer_height = scene.h2 / coating_layers(scene, settings)
        elements = max(elements, math.ceil(scene.coating_length / (MAX_ASPECT * layer_height)))
    return elements


def coating_mesh(scene, settings):
    """Structured triangle mesh of the 2D coating [0, l2] x [h, h + h2], two triangles per
    cell; its top (Contact) and bottom (Bond) carry exactly the interface nodes."""
    columns = interface_elements(scene, settings)
    layers = coating_layers(scene, settings)
    x = interface_nodes(scene.coating_length, columns)
    y = scene.height + scene.h2 * np.arange(layers + 1) / layers
    y[-1] = scene.height + scene.h2          # the contact face exactly where Omega1's is
    points = np.array([(xi, yj) for yj in y for xi in x])
    node = lambda i, j: j * (columns + 1) + i  # noqa: E731
    triangles = []
    for j in range(layers):
        for i in range(columns):
            a, b, c, d = node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)
            triangles += [(a, b, c), (a, c, d)]
    edges = {
        "Bond": [(node(i, 0), node(i + 1, 0)) for i in range(columns)],
        "Free": [(node(columns, j), node(columns, j + 1)) for j in range(layers)],
        "Contact": [(node(i + 1, layers), node(i, layers)) for i in range(columns)],
        "Symmetry": [(node(0, j + 1), node(0, j)) for j in range(layers)],
    }
    lines = np.array([edge for name in edges for edge in edges[name]])
    line_refs = np.concatenate([np.full(len(edges[name]), LABELS[name]) for name in edges])
    return meshio.Mesh(points, [("line", lines), ("triangle", np.array(triangles))],
                       cell_data={"medit:ref": [line_refs, np.full(len(triangles), 1)]})


def body_mesh(scene, settings, body):
    """Triangle mesh of Omega1 (``body="upper"``), Omega3 (``"lower"``) or, for the scene
    without coating, Omega3 grown by h2 and touching Omega1 (``"lower-uncoated"``)."""
    if body not in ("upper", "lower", "lower-uncoated"):
        raise ValueError(f"body must be 'upper', 'lower' or 'lower-uncoated', not {body!r}")
    level = settings.mesh_level
    elements = interface_elements(scene, settings)
    l, h, l2 = scene.length, scene.height, scene.coating_length
    if body == "upper":   # Omega1 = [0, l] x [h + h2, 2h + h2]; coated face at the bottom
        y_face, y_far = h + scene.h2, 2 * h + scene.h2
        face_label, far_label = "Contact", "Stamp"
    elif body == "lower":  # Omega3 = [0, l] x [0, h]; coated face at the top
        y_face, y_far = h, 0.0
        face_label, far_label = "Bond", "Clamped"
    else:                  # [0, l] x [0, h + h2], in contact with Omega1 itself
        y_face, y_far = h + scene.h2, 0.0
        face_label, far_label = "Contact", "Clamped"
    interface_size = l2 / elements

    with _gmsh_session():
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(body)
        geo = gmsh.model.geo
        corner = geo.addPoint(0, y_face, 0)
        coating_end = geo.addPoint(l2, y_face, 0)
        face_end = geo.addPoint(l, y_face, 0)
        far_right = geo.addPoint(l, y_far, 0)
        far_left = geo.addPoint(0, y_far, 0)
        coated = geo.addLine(corner, coating_end)
        uncoated = geo.addLine(coating_end, face_end) if l2 < l else None
        right = geo.addLine(face_end, far_right)
        far = geo.addLine(far_right, far_left)
        left = geo.addLine(far_left, corner)
        face_curves = [c for c in (coated, uncoated) if c is not None]
        surface = geo.addPlaneSurface([geo.addCurveLoop(face_curves + [right, far, left])])
        geo.synchronize()

        gmsh.model.mesh.setTransfiniteCurve(coated, elements + 1)
        fields = gmsh.model.mesh.field
        distance = fields.add("Distance")
        fields.setNumbers(distance, "CurvesList", face_curves)
        fields.setNumber(distance, "Sampling", 100 * level)
        size = fields.add("MathEval")
        fields.setString(size, "F", f"Min({interface_size} + {GROWTH / level}*F{distance}, "
                                    f"{MAX_SIZE / level})")
        fields.setAsBackgroundMesh(size)
        for option in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints",
                       "MeshSizeFromCurvature"):
            gmsh.option.setNumber(f"Mesh.{option}", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 6)  # Frontal-Delaunay: well-shaped triangles

        groups = {face_label: [coated], far_label: [far], "Symmetry": [left],
                  "Free": [c for c in (uncoated, right) if c is not None]}
        for name, curves in groups.items():
            gmsh.model.addPhysicalGroup(1, curves, LABELS[name], name=name)
        gmsh.model.addPhysicalGroup(2, [surface], 1, name=body)
        gmsh.model.mesh.generate(2)
        mesh = _to_meshio()
    _snap_to_interface_nodes(mesh.points, y_face, interface_nodes(l2, elements), interface_size)
    return mesh


@contextmanager
def _gmsh_session():
    """gmsh initialised for one model. gmsh installs its own C-level signal handlers;
    the driver's (SIGINT, SIGTERM: clean up the workers) are put back afterwards. Only
    the main thread has signal handlers (a Dask worker meshes in another thread)."""
    main_thread = threading.current_thread() is threading.main_thread()
    handlers = ({sig: signal.getsignal(sig) for sig in (signal.SIGINT, signal.SIGTERM)}
                if main_thread else {})
    gmsh.initialize(interruptible=False)
    try:
        yield
    finally:
        gmsh.finalize()
        for sig, handler in handlers.items():
            if handler is not None:
                signal.signal(sig, handler)


def _snap_to_interface_nodes(points, y_face, nodes, spacing):
    """Put the coated face's nodes exactly on the shell's nodes (gmsh is off by ~1e-12)."""
    on_face = np.abs(points[:, 1] - y_face) < 1e-9 * spacing
    for i in np.flatnonzero(on_face):
        nearest = np.argmin(np.abs(nodes - points[i, 0]))
        if abs(nodes[nearest] - points[i, 0]) < 1e-6 * spacing:
            points[i, 0] = nodes[nearest]
        points[i, 1] = y_face


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
    return meshio.Mesh(points, cells, cell_data={"medit:ref": refs})


def _counterclockwise(points, triangles):
    """FreeFEM wants positively oriented triangles; gmsh follows the curve loop."""
    a, b, c = (points[triangles[:, i]] for i in range(3))
    area2 = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    flipped = triangles.copy()
    flipped[area2 < 0] = flipped[area2 < 0][:, [0, 2, 1]]
    return flipped


def write_medit(mesh, path):
    """Write a mesh in medit ``.mesh`` format, which FreeFEM's ``readmesh`` reads."""
    meshio.write(Path(path), mesh, file_format="medit")
