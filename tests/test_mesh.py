"""Meshes: the paper's size, the shell's nodes on the coated faces, labels that survive
the medit round trip FreeFEM reads."""

import meshio
import numpy as np
import pytest

from orchestrate.labels import LABELS
from orchestrate.mesh import body_mesh, interface_elements, interface_nodes, write_medit
from orchestrate.scene import Scene, Settings


def _edges_with_label(mesh, label):
    lines = mesh.cells_dict["line"]
    refs = mesh.cell_data_dict["medit:ref"]["line"]
    return lines[refs == label]


@pytest.mark.parametrize("body, face", [("upper", "Contact"), ("lower", "Bond")])
@pytest.mark.parametrize("level", [1, 2])
def test_coated_face_carries_exactly_the_shell_nodes(body, face, level):
    scene, settings = Scene(h2=0.25), Settings(mesh_level=level)
    mesh = body_mesh(scene, settings, body)
    edges = _edges_with_label(mesh, LABELS[face])
    ends = np.sort(mesh.points[edges][:, :, 0], axis=1)
    ends = ends[np.argsort(ends[:, 0])]
    nodes = interface_nodes(scene.coating_length, interface_elements(scene, settings))
    np.testing.assert_array_equal(ends[:, 0], nodes[:-1])     # bitwise: one edge per element
    np.testing.assert_array_equal(ends[:, 1], nodes[1:])
    y_face = scene.height + scene.h2 if body == "upper" else scene.height
    assert np.all(mesh.points[edges][:, :, 1] == y_face)


@pytest.mark.parametrize("body, paper_count", [("upper", 1372), ("lower", 1349)])
def test_default_meshes_are_close_to_the_papers(body, paper_count):
    triangles = len(body_mesh(Scene(), Settings(), body).cells_dict["triangle"])
    assert abs(triangles - paper_count) < 0.05 * paper_count


def test_triangles_are_counterclockwise():
    mesh = body_mesh(Scene(), Settings(), "lower")
    a, b, c = (mesh.points[mesh.cells_dict["triangle"][:, i]] for i in range(3))
    area2 = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    assert np.all(area2 > 0)


def test_medit_round_trip_keeps_points_and_labels(tmp_path):
    mesh = body_mesh(Scene(), Settings(), "upper")
    path = tmp_path / "omega1.mesh"
    write_medit(mesh, path)
    again = meshio.read(path)
    np.testing.assert_array_equal(again.points[:, :2], mesh.points)
    for kind in ("line", "triangle"):
        np.testing.assert_array_equal(again.cells_dict[kind], mesh.cells_dict[kind])
        np.testing.assert_array_equal(again.cell_data_dict["medit:ref"][kind],
                                      mesh.cell_data_dict["medit:ref"][kind])
    assert set(again.cell_data_dict["medit:ref"]["line"]) == {
        LABELS[name] for name in ("Contact", "Stamp", "Symmetry", "Free")}
