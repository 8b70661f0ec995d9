"""Meshes: the paper's size, the interface nodes exactly on every interface face (flat,
curved, mirrored), labels that survive the medit round trip FreeFEM reads."""

import dataclasses

import meshio
import numpy as np
import pytest

from orchestrate.mesh.discretization import discretize
from orchestrate.mesh.labels import LABELS
from orchestrate.mesh.meshes import body_mesh, coating_mesh, write_medit
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene, paper_scene
from tests.conftest import full_model


def _edges_with_label(mesh, label):
    lines = mesh.cells_dict["line"]
    refs = mesh.cell_data_dict["medit:ref"]["line"]
    return lines[refs == label]


def _interface_vertices(problem, body):
    """The exact vertices the interfaces ask of a body: element ends of its sides."""
    vertices = [problem.interfaces[i].sides[k].place[0::2] for i, k in problem.sides_of(body)]
    return np.unique(np.vstack(vertices), axis=0)


def _face_edges_match(mesh, vertices, labels):
    """Every labelled face edge joins two interface vertices bitwise, and every interface
    vertex is a mesh node."""
    edges = np.vstack([_edges_with_label(mesh, LABELS[label]) for label in labels])
    ends = mesh.points[edges].reshape(-1, 2)
    vertex_set = {tuple(v) for v in vertices}
    assert all(tuple(p) in vertex_set for p in ends)
    node_set = {tuple(p) for p in mesh.points}
    assert all(tuple(v) in node_set for v in vertices)
    return edges


@pytest.mark.parametrize("body, face", [("indenter", "Contact"), ("base", "Bond")])
@pytest.mark.parametrize("level", [1, 2])
def test_coated_face_carries_exactly_the_interface_nodes(body, face, level):
    problem = discretize(paper_scene(h2=0.25), Settings(mesh_level=level))
    mesh = body_mesh(problem.subdomains[body].plan)
    vertices = _interface_vertices(problem, body)
    edges = _face_edges_match(mesh, vertices, [face])
    assert len(edges) == 32 * level        # one edge per interface element


@pytest.mark.parametrize("body, paper_count", [("indenter", 1372), ("base", 1349)])
def test_default_meshes_are_close_to_the_papers(body, paper_count):
    problem = discretize(paper_scene(), Settings())
    triangles = len(body_mesh(problem.subdomains[body].plan).cells_dict["triangle"])
    assert abs(triangles - paper_count) < 0.05 * paper_count


def _counterclockwise(mesh):
    a, b, c = (mesh.points[mesh.cells_dict["triangle"][:, i]] for i in range(3))
    area2 = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    return np.all(area2 > 0)


def test_triangles_are_counterclockwise():
    problem = discretize(paper_scene(), Settings())
    assert _counterclockwise(body_mesh(problem.subdomains["base"].plan))


def test_medit_round_trip_keeps_points_and_labels(tmp_path):
    problem = discretize(paper_scene(), Settings())
    mesh = body_mesh(problem.subdomains["indenter"].plan)
    path = tmp_path / "indenter.mesh"
    write_medit(mesh, path)
    again = meshio.read(path)
    np.testing.assert_array_equal(again.points[:, :2], mesh.points)
    for kind in ("line", "triangle"):
        np.testing.assert_array_equal(again.cells_dict[kind], mesh.cells_dict[kind])
        np.testing.assert_array_equal(again.cell_data_dict["medit:ref"][kind],
                                      mesh.cell_data_dict["medit:ref"][kind])
    assert set(again.cell_data_dict["medit:ref"]["line"]) == {
        LABELS[name] for name in ("Contact", "Stamp", "Symmetry", "Free")}


@pytest.mark.parametrize("body", ["indenter", "base", "coating1"])
def test_a_symmetric_full_model_is_meshed_as_its_mirrored_half(body):
    half = paper_scene(model="elastic")
    full = full_model(half)
    assert full.mirror_symmetric
    settings = Settings()
    meshes = []
    for scene in (half, full):
        plan = discretize(scene, settings).subdomains[body].plan
        meshes.append(body_mesh(plan) if body != "coating1" else coating_mesh(plan))
    half_mesh, full_mesh = meshes
    mirrored = full_mesh.points * np.array([-1.0, 1.0])
    assert {tuple(p) for p in mirrored} == {tuple(p) for p in full_mesh.points}
    right = {tuple(p) for p in full_mesh.points if p[0] >= 0}
    assert right == {tuple(p) for p in half_mesh.points}
    assert len(full_mesh.cells_dict["triangle"]) == 2 * len(half_mesh.cells_dict["triangle"])
    assert _counterclockwise(full_mesh)
    assert not np.any(full_mesh.cell_data_dict["medit:ref"]["line"] == LABELS["Symmetry"])


def test_a_roller_and_its_2d_coating_meet_at_the_interface_nodes():
    scene, _ = load_scene(SCENES_DIR / "roller.toml")
    scene = apply_overrides(scene, {"model": "elastic"})
    problem = discretize(scene, Settings())
    base = body_mesh(problem.subdomains["base"].plan)
    _face_edges_match(base, _interface_vertices(problem, "base"), ["Bond", "Contact"])
    coating = coating_mesh(problem.subdomains["coating1"].plan)
    _face_edges_match(coating, _interface_vertices(problem, "coating1"), ["Bond", "Contact"])
    assert _counterclockwise(base) and _counterclockwise(coating)
    radius = scene.base.radius
    bond = _edges_with_label(base, LABELS["Bond"])
    np.testing.assert_allclose(np.linalg.norm(base.points[bond], axis=-1), radius, rtol=1e-14)
    top = _edges_with_label(coating, LABELS["Contact"])
    np.testing.assert_allclose(np.linalg.norm(coating.points[top], axis=-1),
                               radius + scene.coatings[0].thickness, rtol=1e-14)


def test_a_body_is_meshed_once_per_plan(tmp_path, monkeypatch):
    """A sweep meshes its kept bodies again scene after scene: the second time the mesh
    (and the medit text) come from the cache, equal to the first; a copy the caller
    changes leaves the cache alone; another plan is meshed anew."""
    from orchestrate.mesh import meshes as meshing
    base = discretize(paper_scene(), Settings()).subdomains["base"].plan
    first = meshing.write_body_mesh(base, tmp_path / "first.mesh")
    calls = []
    monkeypatch.setattr(meshing, "_gmsh_body", lambda plan: calls.append(plan) or first)
    monkeypatch.setattr(meshing.meshio, "write", lambda *a, **k: calls.append(a))
    again = meshing.write_body_mesh(discretize(paper_scene(), Settings()).subdomains["base"].plan,
                                    tmp_path / "again.mesh")
    assert calls == []
    np.testing.assert_array_equal(again.points, first.points)
    assert (tmp_path / "again.mesh").read_bytes() == (tmp_path / "first.mesh").read_bytes()
    again.points[:] = 0.0
    np.testing.assert_array_equal(body_mesh(base).points, first.points)
    other = dataclasses.replace(base, max_size=0.99 * base.max_size)   # no test meshed it
    body_mesh(other)
    assert calls == [other]


@pytest.mark.parametrize("dimensions", [1, 2])
def test_points_snap_onto_the_nearest_target_within_reach_as_a_search_of_all_finds(dimensions):
    """meshes._snap (a face's nodes put exactly where the interfaces have them) against
    every pair's distance: targets on a curve, some with equal x1 (a patch's step),
    points at, near and far from them."""
    from orchestrate.mesh.meshes import _snap
    rng = np.random.default_rng(7)
    x = np.sort(rng.uniform(-3.0, 3.0, 40))
    targets = np.column_stack([x, 0.1 * x ** 2])[:, :dimensions]
    targets = np.vstack([targets, targets[5] + [0.0, 0.01][:dimensions]])   # a step
    within = 1e-6
    near = targets[rng.integers(0, len(targets), 60)] + rng.normal(0, within / 3,
                                                                   (60, dimensions))
    points = np.vstack([near, rng.uniform(-3.0, 3.0, (60, dimensions))])
    which = np.arange(len(points))
    expected = points.copy()
    distance = np.linalg.norm(points[:, None, :] - targets[None, :, :], axis=2)
    nearest = np.argmin(distance, axis=1)
    close = distance[which, nearest] < within
    expected[close] = targets[nearest[close]]
    assert close.sum() > 40                     # most near points are in reach
    _snap(points, which, targets, within)
    np.testing.assert_array_equal(points, expected)
