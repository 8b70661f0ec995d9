"""A run's field outputs: the recovered nodal stresses, the ParaView files, fig. 5's mesh.

One run (module fixture, about 2 s): the paper's scene with the 2D coating h2 = b/8,
E2 = 5E, whose coating is one layer of P2 triangles under the edge of the contact.

* Recovery (freefem/recovery.idp). A field linear over the mesh is reproduced to
  round-off (tests/forms/freefem/recovery_exact.edp). On the run, the stresses do not ripple:
  along every mesh line no vertex and midpoint alternate by more than the field's own
  variation (the definition is at `zigzags`). The L2 projection onto P2 it replaces
  did, 38 times on the coating's top and bottom faces, by up to 5.6 % of sigma_eq's
  range (0.31e-4 E); e.g. 1.66, 1.37, 1.69e-4 E at x1 = 1.125, 1.156, 1.1875 on the
  top face, whose vertices differ by 0.03e-4 E.
* ParaView: each body's VTU has quadratic triangles (triangle6) in double precision with
  the displacement, the stress tensor and its components; run.pvd lists every
  subdomain's VTU; a shell's VTU has the fibre stresses at its faces (a shell of
  revolution's radial and hoop ones); a sweep's .pvd
  lists its runs as time steps.
* Figures 3-5 draw from a run.
"""

import json
import xml.etree.ElementTree as ElementTree
from collections import defaultdict

import meshio
import numpy as np
import pandas as pd
import pytest

from studies import figures
from orchestrate.mesh.discretization import discretize
from orchestrate.files.writing import write_vtu
from orchestrate.run.outputs import STRESS_COMPONENTS, shell_mesh, shell_table
from orchestrate.run.paraview import RUN_COLLECTION, write_collection, write_sweep_collection
from orchestrate.model.scene import Settings
from orchestrate.model.scene_file import SCENES_DIR, apply_overrides, load_scene, paper_scene
from orchestrate.run.solve import solve

BODIES = ("indenter", "base", "coating1")
FIELDS = ("sigma_eq",) + STRESS_COMPONENTS
COMPONENT_TOLERANCE = 5e-3     # of the field's range: a recovery's smoothing, not a ripple


@pytest.fixture(scope="module")
def run(coating_2d_run):
    return coating_2d_run[1]


def _nodes(run, body):
    return (pd.read_csv(run / f"{body}.csv"),
            pd.read_csv(run / f"{body}_cells.csv").to_numpy())


def mesh_lines(x, y, cells):
    """The mesh lines of P2 triangles: maximal chains of collinear edges, each as its
    nodes in order (vertex, midpoint, vertex, ..., vertex)."""
    points = np.column_stack([x, y])
    midpoint = {}
    for c in cells:
        for a, b, m in ((c[0], c[1], c[3]), (c[1], c[2], c[4]), (c[2], c[0], c[5])):
            midpoint[frozenset((a, b))] = m
    neighbours = defaultdict(list)
    for edge in midpoint:
        a, b = tuple(edge)
        neighbours[a].append(b)
        neighbours[b].append(a)

    def direction(a, b):
        d = points[b] - points[a]
        return d / np.linalg.norm(d)

    def straight_on(previous, vertex):
        d = direction(previous, vertex)
        return next((w for w in neighbours[vertex]
                     if w != previous and direction(vertex, w) @ d > 1 - 1e-9), None)

    lines, used = [], set()
    for edge in midpoint:
        if edge in used:
            continue
        chain = list(edge)
        for _ in range(2):               # grow the chain at one end, then at the other
            chain.reverse()
            while (w := straight_on(chain[-2], chain[-1])) is not None:
                chain.append(w)
        nodes = [chain[0]]
        for a, b in zip(chain, chain[1:]):
            used.add(frozenset((a, b)))
            nodes += [midpoint[frozenset((a, b))], b]
        lines.append(nodes)
    return lines


def zigzags(values, lines):
    """Where a vertex and its neighbouring midpoint alternate along a line by more than
    the field changes there: (excess, node) for every four successive nodes f0..f3 whose
    differences f1 - f0, f2 - f1, f3 - f2 alternate in sign (f1 and f2 are opposite local
    extrema, one of them a vertex, the other a midpoint).

    Why this is the comparison of alternation and variation: write the values along the
    line as a trend changing by d from node to node (half an element) plus an alternating
    part +-a between vertices and midpoints. The differences are d + 2a and d - 2a in
    turn; they alternate in sign exactly when the alternation 2a exceeds the field's
    change d over half an element, and the smallest of the three is the excess 2a - |d|.
    A smooth field, however curved, has no such four nodes except at the meeting of two
    extrema half an element apart. Lines of one edge (three nodes) cannot alternate."""
    found = []
    for line in lines:
        d = np.diff(values[line])
        for k in range(len(d) - 2):
            if d[k] * d[k + 1] < 0 and d[k + 1] * d[k + 2] < 0:
                found.append((min(abs(d[k]), abs(d[k + 1]), abs(d[k + 2])), line[k + 1]))
    return found


# ---- the recovery --------------------------------------------------------------------

def test_the_recovery_reproduces_a_linear_stress_field_to_round_off(run_freefem, tmp_path):
    run_freefem("recovery_exact.edp", "-output", tmp_path / "recovery")
    table = pd.read_csv(tmp_path / "recovery.csv")
    assert len(table) > 500
    for recovered, exact in zip(FIELDS, ("e_eq", "e11", "e22", "e12", "e33")):
        scale = np.abs(table[exact]).max()
        assert np.abs(table[recovered] - table[exact]).max() < 1e-10 * scale, recovered


def test_the_nodal_csv_keeps_its_columns_and_adds_the_recovered_tensor(run):
    for body in BODIES:
        nodes, cells = _nodes(run, body)
        assert list(nodes.columns) == ["x1", "x2", "u1", "u2", "sigma_eq", *STRESS_COMPONENTS]
        assert cells.shape[1] == 6 and cells.min() == 0 and cells.max() == len(nodes) - 1
        s11, s22, s12, s33 = (nodes[name].to_numpy() for name in STRESS_COMPONENTS)
        # plane strain: s33 = nu (s11 + s22), and the recovery is linear (nu = 0.3)
        assert np.allclose(s33, 0.3 * (s11 + s22), rtol=0, atol=1e-12 * np.abs(s33).max())
        von_mises = np.sqrt(0.5 * ((s11 - s22) ** 2 + (s22 - s33) ** 2 + (s33 - s11) ** 2)
                            + 3 * s12 ** 2)
        assert np.allclose(nodes.sigma_eq, von_mises, rtol=1e-12, atol=0)


def test_the_stresses_of_the_thin_stiff_coating_do_not_alternate_along_any_mesh_line(run):
    """sigma_eq: not once; each component: by at most 0.5 % of its range (measured: s11
    none, s22 22 times up to 0.045 %, s12 7 times up to 0.040 %, s33 twice up to 0.33 %,
    where the top face leaves the contact)."""
    nodes, cells = _nodes(run, "coating1")
    lines = mesh_lines(nodes.x1.to_numpy(), nodes.x2.to_numpy(), cells)
    long_lines = [line for line in lines if len(line) > 3]
    # the top and bottom faces, 32 elements each; the rest are single edges
    assert sorted(len(line) for line in long_lines) == [65, 65]
    assert sum(len(line) == 3 for line in lines) == len(lines) - 2
    assert zigzags(nodes.sigma_eq.to_numpy(), lines) == []
    for name in STRESS_COMPONENTS:
        values = nodes[name].to_numpy()
        excess = max((z for z, _ in zigzags(values, lines)), default=0.0)
        assert excess <= COMPONENT_TOLERANCE * np.ptp(values), name

    # the measure sees an alternation: the top face's midpoints raised by 1 % of the
    # range alternate where sigma_eq changes slowly (near the axis, beyond the contact)
    top = next(line for line in long_lines if nodes.x2[line[0]] == nodes.x2.max())
    rippled = nodes.sigma_eq.to_numpy().copy()
    rippled[top[1::2]] += 1e-2 * np.ptp(rippled)
    assert len(zigzags(rippled, lines)) > 10


def test_the_bodies_von_mises_stress_does_not_alternate_either(run):
    for body in ("indenter", "base"):
        nodes, cells = _nodes(run, body)
        lines = mesh_lines(nodes.x1.to_numpy(), nodes.x2.to_numpy(), cells)
        assert zigzags(nodes.sigma_eq.to_numpy(), lines) == [], body


# ---- ParaView ----------------------------------------------------------------------------

def test_each_body_vtu_has_quadratic_triangles_in_double_precision_with_the_tensor(run):
    for body in BODIES:
        nodes, cells = _nodes(run, body)
        mesh = meshio.read(run / f"{body}.vtu")
        assert [block.type for block in mesh.cells] == ["triangle6"]
        connectivity = mesh.cells[0].data
        assert np.array_equal(connectivity, cells)
        assert mesh.points.dtype == np.float64
        assert np.array_equal(mesh.points[:, :2], nodes[["x1", "x2"]].to_numpy())
        assert all(values.dtype == np.float64 for values in mesh.point_data.values())
        # VTK's order: the midpoints of edges 01, 12, 20 after the vertices
        p = mesh.points
        for m, (a, b) in zip((3, 4, 5), ((0, 1), (1, 2), (2, 0))):
            assert np.allclose(p[connectivity[:, m]], 0.5 * (p[connectivity[:, a]] + p[connectivity[:, b]]),
                               rtol=0, atol=1e-12)
        data = mesh.point_data
        assert data["displacement"].shape == (len(nodes), 3)
        assert np.array_equal(data["displacement"][:, :2], nodes[["u1", "u2"]].to_numpy())
        stress = data["stress"].reshape(-1, 3, 3)
        assert np.array_equal(stress, stress.transpose(0, 2, 1))
        for name, (i, j) in zip(STRESS_COMPONENTS, ((0, 0), (1, 1), (0, 1), (2, 2))):
            assert np.array_equal(stress[:, i, j], nodes[name].to_numpy())
            assert np.array_equal(data[name], nodes[name].to_numpy())
        assert np.all(stress[:, 2, :2] == 0)
        assert np.array_equal(data["sigma_eq"], nodes.sigma_eq.to_numpy())


def test_run_pvd_lists_every_subdomain_vtu(run):
    datasets = list(ElementTree.parse(run / RUN_COLLECTION).getroot().iter("DataSet"))
    files = [dataset.get("file") for dataset in datasets]
    assert sorted(files) == sorted(f"{body}.vtu" for body in BODIES)      # relative paths
    assert all((run / name).is_file() for name in files)
    assert sorted(int(d.get("part")) for d in datasets) == [0, 1, 2]


def test_a_run_without_body_fields_has_the_same_answers_and_the_bodies_reactions(run,
                                                                                  tmp_path):
    """Settings.body_fields = False (the figures' sweep): no nodal files of the indenter
    and the base, their reactions still, the coating's fields, and the summary's numbers
    of the run with them (to rounding: two runs of one scene differ by 1e-13 or so, the
    sums of a multi-threaded BLAS in no fixed order)."""
    folder = tmp_path / "run"
    solve(paper_scene(h2=0.125, E2=5.0, model="elastic"), Settings(body_fields=False),
          str(folder))
    for body in ("indenter", "base"):
        assert not list(folder.glob(f"{body}.*")) and not list(folder.glob(f"{body}_cells*"))
        reactions = [np.loadtxt(f / f"{body}_reactions.txt") for f in (folder, run)]
        assert np.allclose(*reactions, rtol=1e-9, atol=1e-9 * np.abs(reactions[1]).max())
    assert (folder / "coating1.csv").is_file() and (folder / "coating1.vtu").is_file()
    listed = [d.get("file") for d in ElementTree.parse(folder / RUN_COLLECTION).iter("DataSet")]
    assert listed == ["coating1.vtu"]
    without, with_fields = (json.loads((f / "summary.json").read_text()) for f in (folder, run))
    assert without["iterations"] == with_fields["iterations"]
    for key in ("total_force", "stamp_reaction", "base_reaction", "peak_contact_stress",
                "peak_interface_stress", "contact_half_width"):
        assert without[key] == pytest.approx(with_fields[key], rel=1e-9), key


def test_a_shell_vtu_has_the_fibre_stresses_of_its_faces(tmp_path):
    """sigma11 = T11/h2 + 12 M11 xi3/h2^3 through the thickness, xi3 along the face's
    outward normal (freefem/shell.idp: the fibre at xi3 moves by (v + xi3 gamma) t and
    M11 = D gamma'): the top face (xi3 = h2/2, the contact side) has T11/h2 + 6 M11/h2^2."""
    spec = discretize(paper_scene(h2=0.125, E2=5.0, model="shell"), Settings()).subdomains["coating1"].plan
    xi = np.linspace(0.0, 2.0, 9)
    fields = pd.DataFrame({"xi": xi, "v": 0.0, "w": 0.0, "gamma": 0.0, "epsilon": 0.0,
                           "T11": 1e-4 * (1 + xi), "T13": 2e-5 * xi, "M11": 3e-6 * (1 - xi),
                           "T33": 0.0})
    write_vtu(tmp_path / "coating1.vtu", shell_mesh(shell_table(fields, spec), spec))
    data = meshio.read(tmp_path / "coating1.vtu").point_data
    h2 = 0.125
    membrane, bending = fields.T11 / h2, 6 * fields.M11 / h2 ** 2
    assert np.allclose(data["sigma11_top"], membrane + bending, rtol=1e-14, atol=0)
    assert np.allclose(data["sigma11_bottom"], membrane - bending, rtol=1e-14, atol=0)
    assert np.allclose(data["sigma13_mean"], fields.T13 / h2, rtol=1e-14, atol=0)


def test_a_shell_of_revolution_vtu_has_its_radial_and_hoop_fibre_stresses(tmp_path):
    """A shell of revolution (an axisymmetric scene's shell, freefem/shell_revolution.idp):
    its fibre at height z moves by (u + z beta) e_r, so sigma_r = N_r/h2 + 12 M_r z/h2^3
    and sigma_theta = N_theta/h2 + 12 M_theta z/h2^3, z = +h2/2 the top face; its mid-line
    lies at x1 = xi, the radius, and its displacement is u e_r + w e_z."""
    scene, _ = load_scene(SCENES_DIR / "sphere.toml")
    spec = discretize(apply_overrides(scene, {"model": "shell"}),
                      Settings()).subdomains["coating1"].plan
    h2, xi = spec.thickness, np.linspace(0.0, 3.0, 9)
    fields = pd.DataFrame({"xi": xi, "u": 1e-3 * xi, "w": -2e-3, "beta": 0.0, "epsilon": 0.0,
                           "N_r": 1e-4 * (1 + xi), "N_theta": 2e-4 * (1 - xi), "Q": 2e-5 * xi,
                           "M_r": 3e-6 * (1 - xi), "M_theta": -4e-6 * xi, "N_z": 0.0})
    table = shell_table(fields, spec)
    assert np.array_equal(table["x1"], xi) and "N_theta" in table and "T11" not in table
    write_vtu(tmp_path / "coating1.vtu", shell_mesh(table, spec))
    data = meshio.read(tmp_path / "coating1.vtu").point_data
    for name, force, moment in (("sigma_r", "N_r", "M_r"), ("sigma_theta", "N_theta", "M_theta")):
        membrane, bending = fields[force] / h2, 6 * fields[moment] / h2 ** 2
        assert np.allclose(data[f"{name}_top"], membrane + bending, rtol=1e-14, atol=0)
        assert np.allclose(data[f"{name}_bottom"], membrane - bending, rtol=1e-14, atol=0)
    assert np.allclose(data["sigma_rz_mean"], fields.Q / h2, rtol=1e-14, atol=0)
    assert np.allclose(data["displacement"][:, :2], np.column_stack([fields.u, fields.w]))


def test_a_sweep_pvd_has_one_time_step_per_run_with_its_subdomains(run, tmp_path):
    other = tmp_path / "runs" / "b"
    other.mkdir(parents=True)
    (other / "coating1.vtu").write_bytes((run / "coating1.vtu").read_bytes())
    write_collection(other / RUN_COLLECTION, ["coating1.vtu"])
    failed = tmp_path / "runs" / "failed"          # no VTU: not converged
    failed.mkdir()
    path = tmp_path / "sweep" / "sweep.pvd"
    path.parent.mkdir()
    kept = write_sweep_collection(path, [run, failed, other], names=["a", "failed", "b"])
    assert kept == [(0, run), (1, other)]
    datasets = list(ElementTree.parse(path).getroot().iter("DataSet"))
    steps = defaultdict(list)
    for dataset in datasets:
        assert (path.parent / dataset.get("file")).resolve().is_file()
        steps[int(dataset.get("timestep"))].append(dataset.get("name"))
    assert steps == {0: [f"a/{body}" for body in ("indenter", "coating1", "base")],
                     1: ["b/coating1"]}


# ---- figures -----------------------------------------------------------------------------

def test_fig5_draws_the_quadratic_on_the_mesh_own_triangles(run):
    nodes, cells = _nodes(run, "coating1")
    x, y, values = nodes.x1.to_numpy(), nodes.x2.to_numpy(), nodes.sigma_eq.to_numpy()
    four, drawn = figures.p2_triangulation(x, y, cells, values, n=2)   # the nodes themselves
    assert len(four.triangles) == 4 * len(cells) and len(four.x) == len(nodes)
    at = {(round(a, 9), round(b, 9)): value for a, b, value in zip(x, y, values)}
    assert all(at[round(a, 9), round(b, 9)] == value for a, b, value in zip(four.x, four.y, drawn))
    fine, drawn = figures.p2_triangulation(x, y, cells, values, n=6)
    assert len(fine.triangles) == 36 * len(cells)
    assert values.min() - 0.05 * np.ptp(values) < drawn.min() and drawn.max() < values.max() * 1.05


@pytest.mark.filterwarnings("ignore:No artists with labels")      # panels this run is not in
def test_figures_3_to_5_draw_from_a_run(run, tmp_path):
    runs = figures.load_runs([str(run)])
    for name in ("fig3", "fig4", "fig5"):
        figures.FIGURES[name](runs, str(tmp_path))
        assert (tmp_path / f"{name}.png").stat().st_size > 10_000
        assert (tmp_path / f"{name}.pdf").read_bytes().rstrip().endswith(b"%%EOF")
        assert (tmp_path / f"{name}_data.csv").is_file()
    assert not list(tmp_path.glob("*partial*"))


def test_a_file_drawn_aside_reports_its_failure(capfd):
    """fig. 5's PDF is drawn in a forked process: its failure fails the drawing."""
    wait = figures._forked(lambda: 1 / 0)
    with pytest.raises(RuntimeError, match="forked process failed"):
        wait()
    assert "ZeroDivisionError" in capfd.readouterr().err
