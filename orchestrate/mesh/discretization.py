"""The scene as a list of subdomains and of the interfaces between them.

Subdomains: the indenter and the base (P2 elastic bodies meshed by gmsh; a rigid
indenter has one unknown and no mesh), and one per coating patch (a shell on its
mid-line, of revolution in an axisymmetric scene, or a P2 body on a structured mesh).
Interfaces:

    bond-coatingI     patch I's bottom bonded to the base (side A: the patch, side B:
                      the base), two components: tangential and normal displacement;
    contact-coatingI  the indenter (side A) over patch I's top (side B);
    contact-baseJ     the indenter over the J-th stretch of bare base (from left to
                      right) inside the contact zone;
    friction-...      under friction (Scene.frictional), one per contact, at its points:
                      the tangential displacements of the same two sides, which carry
                      the friction traction the contact's pressure sets (robin.py).

Contact interfaces come first, ordered along the face, then bonds, patch by patch, then
the friction interfaces in their contacts' order.
Every interface is a set of points shared by its two sides: the P2 nodes of its
elements (ends and midpoints) with Simpson's weights of the face's arc length, so that
the Robin loop and the monolithic solve integrate every coupling term alike and the
penalty acts node to node. (Gauss points, 5 per element, exact for the P2 x P4
products, were tried first: they constrain more points per element than a P2 trace has
nodes, and the contact pressure oscillated near the edge of the contact zone; at the
nodes it is smooth and the contact set settles in fewer updates.) Each side evaluates its trace
at its own place for each point: a body at the point of its (polygonal) mesh, a shell
at its mid-line's xi (ShellSpec: an arc length, or a shell of revolution's radius); a
contact trace is the displacement along the side's outward normal n (towards the other
body), a friction trace the displacement along the side's tangent (n2, -n1) (the
face's tangent t on the partner, -t on the indenter: the two sides' sum is the slip,
and the traction is the same number on both, as a contact's pressure is), a bond trace
the tangential and normal components in the face's basis (t, n).

Elements along the faces have the length Settings.element_size / mesh_level; where
that is not given, it is sized to the contact (Settings.sized_to: contact_elements across
the a priori half-width a) and graded back to element_size_far away from it: fine up to
FINE_REACH a from the contact's centre, then growing by ALONG_GROWTH per unit length
(FaceSpacing). A 2D coating has one layer of cells per b/8 of thickness, and cells at
most MAX_ASPECT as wide as high at its patch's ends and the a priori contact's edges, so
a thin 2D coating refines its interface there; away from them its cells grow from that
width as the face's elements do, up to the face's own length. A
mirror-symmetric full model (Scene.mirror_symmetric) gets mirror-symmetric elements and
meshes.
"""

from dataclasses import dataclass
import math

import numpy as np

from orchestrate.errors import LengthsError
from orchestrate.mesh.body_plans import base_plan, indenter_plan
from orchestrate.model.estimate import predicted_half_width
from orchestrate.model.geometry import IndenterFace, base_face, lowest_point
from orchestrate.model.scene import MODELS, SHELL_MODELS, ParameterError

# The 2D coating: one layer of cells per b/8 of height, as the paper's 64 ... 512
# triangles for h2 = b/8 ... b, and at least one; a cell at most MAX_ASPECT times as
# wide as it is high (the cost the paper alludes to for h2 <= b/16) along a uniform
# face. On a graded face only at a patch's ends and the a priori contact's edges, where
# the bond's stresses vary over a few thicknesses; away from them the cells grow as the
# face's elements do, up to the face's length: the fields vary there as slowly along the
# layer as on the face (docs/method.md, "A mesh sized to the contact", has the counts).
COATING_LAYER_HEIGHT = 0.125
MAX_ASPECT = 2.0
# Faces sized to the contact: fine up to FINE_REACH a priori half-widths from the
# contact's centre (a contact wider than estimated stays resolved), then each element
# about ALONG_GROWTH of its distance beyond longer (neighbours differ by ~15 %).
FINE_REACH = 1.5
ALONG_GROWTH = 0.15


@dataclass(frozen=True, eq=False)
class Side:
    """Where one side of an interface takes its trace, point by point.

    body:  ``place`` (n, 2) points of its mesh; ``coefficients`` one (n, 2) array per
           component: trace = c1 u1 + c2 u2 there.
    shell: ``place`` (n,) its mid-line's xi (ShellSpec); ``coefficients`` one (n, 3)
           array per component: trace = cV v + cW w + cG gamma there, or (n, 4) with
           + cE epsilon for a shell with thickness stretch."""
    subdomain: str
    place: np.ndarray
    coefficients: tuple


@dataclass(frozen=True, eq=False)
class Interface:
    name: str
    kind: str                  # "contact", "bond" or "friction"
    s: np.ndarray              # points: arc length along the base's top face
    position: np.ndarray       # (n, 2): the points on the partner (contact) or base (bond) face
    normal: np.ndarray         # (n, 2): unit normal of that face, towards the indenter
    tangent: np.ndarray        # (n, 2)
    weight: np.ndarray         # Simpson's weights of the face's arc length
    gap: np.ndarray            # initial gap along the normal (zero on a bond)
    sides: tuple               # (Side A, Side B)
    mismatch: np.ndarray = None  # contact: angle (rad) between the paired faces' normals
    # friction: Coulomb's mu at each point (the traction is -mu times the contact's
    # normal stress, compression negative) and the index of its contact interface
    friction: np.ndarray = None
    contact: int = None

    @property
    def size(self):
        return len(self.s)

    @property
    def components(self):
        return 2 if self.kind == "bond" else 1

    def integrate(self, values):
        return float(np.dot(self.weight, values))


@dataclass(frozen=True)
class CoatingPlan:
    """A 2D coating on a structured mesh: columns at ``nodes`` (arc length on the base's
    face), ``layers`` layers up to ``thickness``."""
    face: object
    nodes: np.ndarray
    thickness: float
    layers: int
    top_label: str             # "Contact", or "Free" outside the contact zone
    start_label: str           # "Symmetry" on the axis of a half model, else "Free"


@dataclass(frozen=True)
class ShellSpec:
    """A coating patch as a shell on its mid-line: nodes xi, constant curvature, with or
    without thickness stretch (the fibre's transverse strain epsilon), its start on the
    symmetry axis of a half model or free. In a plane scene a Timoshenko-type shell, xi
    the arc length from its start; in an axisymmetric one a shell of revolution with a
    flat mid-line, a disc or a ring (freefem/shell_revolution.idp), xi the radius r, which
    its hoop strains u/r need (``revolution``)."""
    nodes: np.ndarray
    curvature: float
    thickness: float
    shear_factor: float
    thickness_stretch: bool
    symmetric_start: bool
    face: object
    s_start: float             # arc length on the base's face where xi = 0: the patch's
                               # start, or the axis for a shell of revolution
    stretch: float             # mid-line length per unit base-face length
    revolution: bool           # a shell of revolution (the scene is axisymmetric)


@dataclass(frozen=True)
class Subdomain:
    name: str
    kind: str                  # "body", "shell" or "rigid" (a rigid indenter)
    E: float
    nu: float
    plan: object               # BodyPlan, CoatingPlan, ShellSpec, or None (rigid)
    stamp: bool = False        # the indenter: loaded by the stamp
    coating: bool = False      # a coating patch: its interfaces meet the bodies only


@dataclass(frozen=True)
class Problem:
    scene: object
    settings: object
    subdomains: dict           # name -> Subdomain, in a fixed order
    interfaces: tuple
    lowest: float              # height of the indenter's lowest point at first touch
    penalty: float             # theta, in the scene's units (Settings.theta b/E)
    robin: float               # gamma, in the scene's units (Settings.robin_parameter E/b)

    def sides_of(self, *names):
        """(interface index, side index) of every side of the subdomains ``names``, one
        subdomain after the other (a worker of several answers in that order), each in
        interface order."""
        return [(i, k) for name in names for i, interface in enumerate(self.interfaces)
                for k, side in enumerate(interface.sides) if side.subdomain == name]

    @property
    def sweep(self):
        """The groups of subdomains of one multiplicative Robin iteration, solved one after
        the other, each from the state the groups before it left (robin.py): the bodies,
        then the coating patches, which meet bodies only, so each group's solves stay
        independent."""
        bodies = tuple(name for name, sub in self.subdomains.items() if not sub.coating)
        patches = tuple(name for name, sub in self.subdomains.items() if sub.coating)
        return tuple(group for group in (bodies, patches) if group)

    @property
    def contacts(self):
        return [i for i in self.interfaces if i.kind == "contact"]

    @property
    def bonds(self):
        return [i for i in self.interfaces if i.kind == "bond"]

    @property
    def frictions(self):
        return [i for i in self.interfaces if i.kind == "friction"]


# ---- elements along the face -----------------------------------------------------------

# Elements along one interface, and layers across one 2D coating, at most: beyond, the
# arrays alone would exhaust the memory before the size check (problem_size.py) can run.
MAX_ELEMENTS = 200_000


def _count(length, size):
    return _bounded(max(1, round(length / size)))


def _bounded(count, what="interface elements"):
    if count > MAX_ELEMENTS:
        raise ParameterError(f"mesh_level, element_size: the scene would need {count:.3g} "
                             f"{what} on one face (at most {MAX_ELEMENTS}): coarsen the mesh, "
                             "or thicken a 2D coating (its cells are at most twice as wide as "
                             "high)", "mesh_level")
    return count


def element_nodes(s0, s1, count, split_at_zero=False):
    """Ends of ``count(length)`` equal elements on [s0, s1]; with ``split_at_zero`` an
    interval across 0 has a node there, its left half the mirror image of its right."""
    if split_at_zero and s0 < 0 < s1:
        left, right = count(-s0), count(s1)
        return np.concatenate([-np.linspace(0.0, -s0, left + 1)[::-1][:-1],
                               np.linspace(0.0, s1, right + 1)])
    return np.linspace(s0, s1, count(s1 - s0) + 1)


@dataclass(frozen=True)
class FaceSpacing:
    """The interface elements' length along the base's face (arc length s): ``fine`` up
    to ``reach`` from ``centre``, then growing by ``growth`` per unit length up to
    ``far``; uniform where far == fine. ``edges``: the a priori contact's edges (s), where
    a thin 2D coating's cells are narrowest, as at its patch's ends."""
    fine: float
    far: float
    centre: float = 0.0
    reach: float = 0.0
    growth: float = ALONG_GROWTH
    edges: tuple = ()

    @property
    def graded(self):
        return self.far > self.fine

    def length(self, s, cap=math.inf, ends=()):
        """The element length at s; ``cap``: a thin 2D coating's widest cell, which holds
        at the patch's ``ends`` (s) and the contact's edges, and grows from there as the
        face's elements do, up to the face's own length."""
        beyond = np.maximum(np.abs(s - self.centre) - self.reach, 0.0)
        face = np.minimum(self.fine + self.growth * beyond, max(self.far, self.fine))
        narrowest = tuple(ends) + self.edges
        if math.isinf(cap) or not narrowest:
            return face
        distance = np.min([np.abs(s - at) for at in narrowest], axis=0)
        return np.minimum(face, cap + self.growth * distance)

    def nodes(self, s0, s1, cap=math.inf, split_at_zero=False, ends=()):
        """Element ends on [s0, s1], each element about length(s, cap, ends) long (a
        uniform face's at most ``cap`` throughout); with ``split_at_zero`` (a
        mirror-symmetric model, centre 0) mirrored about 0."""
        if not self.graded:
            def count(length):
                uniform = _count(length, self.fine)
                return uniform if math.isinf(cap) else max(uniform,
                                                           _bounded(math.ceil(length / cap)))
            return element_nodes(s0, s1, count, split_at_zero)
        if split_at_zero and s0 < 0 < s1:
            mirrored = tuple(-end for end in ends)
            left = -self._graded(0.0, -s0, cap, mirrored)[::-1]
            return np.concatenate([left[:-1], self._graded(0.0, s1, cap, ends)])
        return self._graded(s0, s1, cap, ends)

    def _graded(self, s0, s1, cap, ends):
        """Nodes at equal steps of the element count, the integral of 1/length(s)
        (sampled 20 times per face element, and geometrically away from a patch's ends
        and the contact's edges, where a thin coating's cells are shorter)."""
        samples = _bounded(int(min(20 * (s1 - s0) / self.fine, 2e6)) + 2, "samples of the face")
        s = np.linspace(s0, s1, samples)
        finest = min(self.fine, cap)
        if finest < self.fine:
            # steps growing by 5 % from a twentieth of the end's cell to the face's
            steps = finest / 20.0 * 1.05 ** np.arange(
                math.ceil(math.log(20.0 * self.fine / finest) / math.log(1.05)) + 1)
            offsets = np.cumsum(steps)
            near = np.concatenate([[at - offsets, at + offsets]
                                   for at in tuple(ends) + self.edges]).ravel()
            s = np.union1d(s, near[(near > s0) & (near < s1)])
        density = 1.0 / self.length(s, cap, ends)
        count_at = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1])
                                                    * np.diff(s))])
        count = _bounded(max(1, round(count_at[-1])))
        nodes = np.interp(np.linspace(0.0, count_at[-1], count + 1), count_at, s)
        nodes[0], nodes[-1] = s0, s1
        return nodes


def face_spacing(scene, settings, face):
    """The FaceSpacing of a scene's interfaces at the settings' mesh level (sized to its
    contact first where element_size is not given)."""
    if settings.element_size is None:
        settings = settings.sized_to(predicted_half_width(scene), contact_reach(scene))
    level = settings.mesh_level
    fine = settings.element_size / level
    far = (settings.element_size_far or settings.element_size) / level
    if far <= fine:
        return settings, FaceSpacing(fine, fine)
    a = float(f"{predicted_half_width(scene):.12g}")     # as Settings.sized_to does
    centre = _grading_centre(scene, face)
    return settings, FaceSpacing(fine, far, centre, FINE_REACH * a,
                                 edges=(centre - a, centre + a))


def simpson(nodes, stretch=1.0):
    """The P2 nodes of the elements (ends, midpoints) and Simpson's weights L/6, 4L/6,
    L/6 of their length, ``stretch`` times the length in s."""
    size = np.diff(nodes)
    s = np.empty(2 * len(size) + 1)
    s[0::2] = nodes
    s[1::2] = nodes[:-1] + 0.5 * size
    length = size * stretch
    weight = np.zeros_like(s)
    weight[0:-1:2] += length / 6.0
    weight[1::2] += 4.0 * length / 6.0
    weight[2::2] += length / 6.0
    return s, weight


def revolved(scene, weight, position):
    """An interface's weights: of its arc length, or in an axisymmetric scene of the
    surface it sweeps about the axis, 2 pi r ds (the bodies' forms weigh their volume
    alike, freefem/elasticity.idp), so that its integrals are the whole body's."""
    if not scene.axisymmetric:
        return weight
    return 2.0 * math.pi * position[:, 0] * weight


def chord_points(exact):
    """A body's mesh points for the P2 nodes whose exact places are ``exact``: the ends
    of the elements, and the midpoints of the straight edges between them."""
    points = exact.copy()
    points[1::2] = exact[0:-2:2] + 0.5 * (exact[2::2] - exact[0:-2:2])
    return points


# ---- the problem ------------------------------------------------------------------------

def coating_layers(coating, level):
    return _bounded(level * max(1, round(coating.thickness / COATING_LAYER_HEIGHT)),
                    "layers of cells")


def discretize(scene, settings, cell_aspect=MAX_ASPECT):
    """The subdomains and interfaces of a scene at the settings' mesh (every patch's
    model decided: run/plan.py's choose_models turns "auto" into one).
    ``cell_aspect``: a thin 2D coating's cells at most this many times as wide as high
    (at its ends and the contact's edges on a graded face); a coarse level takes them
    wider (it models the loop's smooth modes only)."""
    undecided = [n for n, c in enumerate(scene.coatings, start=1) if c.model not in MODELS]
    if undecided:
        raise ValueError(f"coating{undecided[0]}: model {scene.coatings[undecided[0] - 1].model!r} "
                         "must be decided before the scene is discretised")
    face = base_face(scene.base)
    settings, spacing = face_spacing(scene, settings, face)
    level = settings.mesh_level
    mirror = scene.mirror_symmetric

    def patch_cap(coating):
        """A 2D patch's cells are at most cell_aspect times as wide as its layers at its
        ends and the contact's edges (FaceSpacing.length)."""
        if coating.model != "elastic":
            return math.inf
        return cell_aspect * (coating.thickness / coating_layers(coating, level))

    patches = []
    for number, coating in enumerate(scene.coatings, start=1):
        s0, s1 = face.s_of_x1(coating.start), face.s_of_x1(coating.end)
        ends = tuple(face.s_of_x1(end) for end in scene.patch_ends(coating))
        patches.append((number, coating, spacing.nodes(s0, s1, patch_cap(coating), mirror,
                                                       ends)))
    patches.sort(key=lambda item: item[2][0])
    patch_nodes = {number: nodes for number, _, nodes in patches}

    def partners_in(s_lo, s_hi):
        """(s-nodes, offset, name, patch number or None) of every face the indenter may
        touch in [s_lo, s_hi], along the face; the patches among them."""
        partners, in_zone = [], set()
        for number, coating, nodes in patches:
            if nodes[-1] <= s_lo or nodes[0] >= s_hi:
                continue
            # a patch reaching beyond the zone (a coating wider than the indenter's face):
            # its top is a contact on the zone's part, from node to node, and free beyond
            inside = nodes[(nodes >= s_lo - 1e-12) & (nodes <= s_hi + 1e-12)]
            if len(inside) < 2:
                continue
            partners.append((inside, coating.thickness, f"contact-coating{number}", number))
            in_zone.add(number)
        bare = _bare_stretches(s_lo, s_hi, [nodes for _, _, nodes in patches])
        for number, (a, b) in enumerate(bare, start=1):
            partners.append((spacing.nodes(a, b, split_at_zero=mirror),
                             0.0, f"contact-base{number}", None))
        partners.sort(key=lambda item: item[0][0])
        if not partners:
            raise ParameterError("the contact zone is empty: the indenter's face, the base's "
                                 "face and contact_zone do not overlap", "contact_zone")
        return partners, in_zone

    def lowest_over(partners):
        """The indenter's lowest point: its face passes above every partner face."""
        samples = [face.point(np.linspace(n[0], n[-1], 50 * len(n)), offset)
                   for n, offset, _, _ in partners]
        samples += [face.point(n, offset) for n, offset, _, _ in partners]
        return lowest_point(scene.indenter, np.vstack(samples))

    s_lo, s_hi = _contact_range(scene, face)
    partners, in_zone = partners_in(s_lo, s_hi)
    lowest = lowest_over(partners)
    # on a curved base, the normals of the zone's far points may pass beside the
    # indenter's face: the zone ends where they reach the face's end
    clipped = _under_indenter(scene, face, IndenterFace(scene.indenter, lowest), s_lo, s_hi)
    if clipped != (s_lo, s_hi):
        partners, in_zone = partners_in(*clipped)
        lowest = lowest_over(partners)
    indenter_face = IndenterFace(scene.indenter, lowest)

    contacts = []
    for nodes, offset, name, number in partners:
        s, weight = simpson(nodes, face.stretch(offset))
        position = face.point(s, offset)
        weight = revolved(scene, weight, position)
        normal, tangent = face.normal(s), face.tangent(s)
        gap, touching = indenter_face.pair(position, normal)
        if np.any(gap < -1e-12 * (1.0 + np.abs(position[:, 1]))):
            raise AssertionError("negative initial gap: the lowest point is wrong")
        indenter_place = _indenter_place(touching, scene.indenter, lowest)
        _check_under_indenter(scene, indenter_place)
        partner = f"coating{number}" if number is not None else "base"
        if number is not None and scene.coatings[number - 1].model in SHELL_MODELS:
            coating = scene.coatings[number - 1]
            spec_stretch = face.stretch(0.5 * coating.thickness)
            xi = (s - _xi_origin(scene, patch_nodes[number])) * spec_stretch
            partner_side = Side(partner, xi, (  # the top face's w
                _shell_coefficients(len(s), coating, 0.0, 1.0, 0.0, 0.5),))
        else:
            partner_side = Side(partner, chord_points(position), (normal.copy(),))
        indenter_side = Side("indenter", indenter_place, (-normal,))
        face_normal = indenter_face.normal(touching[:, 0])
        angle = np.arccos(np.clip(-np.sum(face_normal * normal, axis=1), -1.0, 1.0))
        contacts.append(Interface(name, "contact", s, position, normal, tangent, weight,
                                  np.maximum(gap, 0.0), (indenter_side, partner_side), angle))

    bonds, subdomains = [], {}
    for number, coating, nodes in sorted(patches, key=lambda item: item[0]):
        s, weight = simpson(nodes)
        position = face.point(s)
        weight = revolved(scene, weight, position)
        normal, tangent = face.normal(s), face.tangent(s)
        name = f"coating{number}"
        on_axis = scene.symmetric and nodes[0] == 0.0
        if coating.model in SHELL_MODELS:
            stretch = face.stretch(0.5 * coating.thickness)
            origin = _xi_origin(scene, nodes)
            spec = ShellSpec((nodes - origin) * stretch, face.curvature / stretch,
                             coating.thickness, coating.shear_factor,
                             coating.model == "stretch_shell", on_axis, face,
                             float(origin), stretch, scene.axisymmetric)
            n = len(s)
            coating_side = Side(name, (s - origin) * stretch, (   # the bottom face's v, w
                _shell_coefficients(n, coating, 1.0, 0.0, -0.5 * coating.thickness, 0.0),
                _shell_coefficients(n, coating, 0.0, 1.0, 0.0, -0.5)))
            subdomains[name] = Subdomain(name, "shell", coating.E, coating.nu, spec,
                                         coating=True)
        else:
            plan = CoatingPlan(face, nodes, coating.thickness, coating_layers(coating, level),
                               "Contact" if number in in_zone else "Free",
                               "Symmetry" if on_axis else "Free")
            coating_side = Side(name, chord_points(position), (tangent.copy(), normal.copy()))
            subdomains[name] = Subdomain(name, "body", coating.E, coating.nu, plan,
                                         coating=True)
        base_side = Side("base", chord_points(position), (tangent.copy(), normal.copy()))
        bonds.append(Interface(f"bond-{name}", "bond", s, position, normal, tangent, weight,
                               np.zeros_like(s), (coating_side, base_side)))

    interfaces = tuple(contacts + bonds + _friction_interfaces(scene, contacts))
    # the finest element on any face, as length / elements (the mesh's size field)
    face_size = min(float(i.s[-1] - i.s[0]) / ((i.size - 1) // 2) for i in interfaces)
    grading = None
    if spacing.graded:         # the bodies' size field follows the face's (meshes.py)
        face_size = min(float(np.min(np.diff(i.s[0::2]))) for i in interfaces)
        x_c, y_c = face.point(np.array([spacing.centre]))[0]
        grading = (float(x_c), float(y_c), spacing.reach, spacing.growth, spacing.far)
    if scene.indenter.rigid:           # one unknown, no mesh (freefem/subdomain_rigid.idp)
        indenter = Subdomain("indenter", "rigid", math.inf, scene.indenter.nu, None,
                             stamp=True)
    else:
        indenter = Subdomain(
            "indenter", "body", scene.indenter.E, scene.indenter.nu,
            indenter_plan(scene, settings, indenter_face, contacts, face_size, grading),
            stamp=True)
    ordered = {"indenter": indenter}
    ordered.update((name, subdomains[name]) for name in sorted(
        subdomains, key=lambda n: int(n[len("coating"):])))
    ordered["base"] = Subdomain("base", "body", scene.base.E, scene.base.nu,
                                base_plan(scene, settings, face, contacts, bonds, face_size,
                                          grading))
    return Problem(scene, settings, ordered, interfaces, lowest,
                   settings.theta / scene.modulus, settings.robin_parameter * scene.modulus)


def _friction_interfaces(scene, contacts):
    """Under friction, an interface per contact at its points (its index in the
    problem's interfaces, contacts coming first): each side's displacement along its
    tangent (n2, -n1), the indenter's -t, the partner's t (a shell's top face: v +
    h2 gamma / 2)."""
    if not scene.frictional:
        return []
    frictions = []
    for k, contact in enumerate(contacts):
        indenter, partner = contact.sides
        n = contact.size
        coating = (scene.coatings[int(partner.subdomain[len("coating"):]) - 1]
                   if partner.subdomain.startswith("coating") else None)
        if coating is not None and coating.model in SHELL_MODELS:
            along = _shell_coefficients(n, coating, 1.0, 0.0, 0.5 * coating.thickness, 0.0)
        else:
            along = contact.tangent.copy()
        frictions.append(Interface(
            "friction-" + contact.name[len("contact-"):], "friction", contact.s,
            contact.position, contact.normal, contact.tangent, contact.weight,
            np.zeros(n), (Side("indenter", indenter.place, (-contact.tangent,)),
                          Side(partner.subdomain, partner.place, (along,))),
            friction=np.full(n, float(scene.friction_on(coating))), contact=k))
    return frictions


def _xi_origin(scene, nodes):
    """The arc length on the base's face where a shell's xi is 0: its start (``nodes``:
    its element ends), or in an axisymmetric scene the axis, so that xi is the radius."""
    return 0.0 if scene.axisymmetric else nodes[0]


def _shell_coefficients(n, coating, c_v, c_w, c_gamma, face):
    """Trace coefficients of a shell's face at n points: cV v + cW w + cG gamma, and with
    thickness stretch + cE epsilon, cE = face h2 c_w (face = +1/2 top, -1/2 bottom): the
    face xi3 = face h2 moves along the normal by w + xi3 epsilon. A shell of revolution's
    are the same with u, beta in the places of v, gamma: its fibre at height z moves by
    (u + z beta) e_r + (w + z epsilon) e_z, e_r and e_z the flat face's t and n."""
    row = [c_v, c_w, c_gamma]
    if coating.model == "stretch_shell":
        row.append(face * coating.thickness * c_w)
    return np.tile(row, (n, 1)).astype(float)


def contact_reach(scene):
    """How far (b, along the base's face) contact may happen from the contact's centre
    (_contact_range, _grading_centre): a full model's is its half's."""
    face = base_face(scene.base)
    s_lo, s_hi = _contact_range(scene, face)
    centre = _grading_centre(scene, face)
    return max(s_hi - centre, centre - s_lo, 0.0)


def _grading_centre(scene, face):
    """Where a face sized to the contact is finest: the contact's centre."""
    return face.s_of_x1(scene.contact_centre)


def _contact_range(scene, face):
    """The arc-length range of the base's face where contact may happen: under the
    indenter's face, on the base's face (a roller's upper half), inside contact_zone."""
    indenter, base = scene.indenter, scene.base
    lo = 0.0 if scene.symmetric else max(indenter.centre - indenter.width, -base.top)
    hi = min(indenter.width if scene.symmetric else indenter.centre + indenter.width, base.top)
    if scene.contact_zone is not None:
        lo, hi = max(lo, scene.contact_zone[0]), min(hi, scene.contact_zone[1])
    return face.s_of_x1(lo), face.s_of_x1(hi)


def _under_indenter(scene, face, indenter_face, s_lo, s_hi):
    """[s_lo, s_hi] shrunk so that the normal of every point in it (of the base's face,
    and of the coatings' tops on it) meets the indenter's face within its ends."""
    indenter = scene.indenter
    lo = 0.0 if scene.symmetric else indenter.centre - indenter.width
    hi = indenter.width if scene.symmetric else indenter.centre + indenter.width
    offsets = [0.0] + [c.thickness for c in scene.coatings]

    def reach(s):
        points = np.vstack([face.point(np.array([s]), t) for t in offsets])
        normals = np.repeat(face.normal(np.array([s])), len(offsets), axis=0)
        _, touching = indenter_face.pair(points, normals)
        return touching[:, 0].min(), touching[:, 0].max()

    def inside(s):
        low, high = reach(s)
        return low >= lo - 1e-12 and high <= hi + 1e-12

    ends = []
    for end, other in ((s_lo, s_hi), (s_hi, s_lo)):
        if inside(end):
            ends.append(end)
            continue
        good, bad = other, end            # bisect between a point under it and the end
        for _ in range(60):
            middle = 0.5 * (good + bad)
            good, bad = (middle, bad) if inside(middle) else (good, middle)
        ends.append(good)
    return tuple(ends)


def _bare_stretches(s_lo, s_hi, patch_nodes, shortest=1e-9):
    """The parts of [s_lo, s_hi] no patch covers."""
    stretches, start = [], s_lo
    for nodes in sorted(patch_nodes, key=lambda n: n[0]):
        a, b = nodes[0], nodes[-1]
        if a - start > shortest and a > s_lo and start < s_hi:
            stretches.append((start, min(a, s_hi)))
        start = max(start, b)
    if s_hi - start > shortest:
        stretches.append((start, s_hi))
    return stretches


def _indenter_place(touching, indenter, lowest):
    """The indenter's mesh points for the contact points: on its face (``shaped``) or on
    the flat line of its lowest point (``flat``), chord midpoints between the ends."""
    if indenter.face_mesh == "flat":
        touching = np.column_stack([touching[:, 0], np.full(len(touching), lowest)])
    return chord_points(touching)


def _check_under_indenter(scene, place):
    indenter = scene.indenter
    lo = 0.0 if scene.symmetric else indenter.centre - indenter.width
    hi = indenter.width if scene.symmetric else indenter.centre + indenter.width
    x = place[:, 0]
    if np.any(x < lo - 1e-9) or np.any(x > hi + 1e-9):
        raise LengthsError(
            "indenter.width = {width}: the indenter's face (x1 from {lo} to {hi}) does not "
            "reach every point of the contact zone (x1 from {first} to {last}): widen it or "
            "narrow contact_zone", "indenter.width", width=indenter.width, lo=lo, hi=hi,
            first=x.min(), last=x.max())
