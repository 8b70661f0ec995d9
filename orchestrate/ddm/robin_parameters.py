"""The Robin parameter of every interface side, and whether the side holds its inactive
contact points.

A Robin-Robin exchange converges fastest when each side's coefficient equals its
neighbour's Dirichlet-to-Neumann response (the stiffness the neighbour offers at the
interface): the error of one exchange is then zero at the wavelength where they match,
and small at all others whichever body is stiffer (the choice of optimised Schwarz
methods, Gander's "Optimized Schwarz methods", SIAM J. Numer. Anal. 44, 2006, and its
heterogeneous versions). An elastic half-plane's response at wavenumber k is
E* k / 2 with E* = E / (1 - nu^2) (plane strain), so the rule "neighbour" scales one
number, the run's gamma (E/b, set for bodies of the stiffer body's modulus), by the
neighbour's E* over the stiffer body's: the soft side of a contact gets the stiff one's
large coefficient (almost a Dirichlet condition), the stiff side the soft one's small
one (almost a Neumann condition). With equal bodies every side has gamma, as under the
rule "equal" (one number for all sides, the rule of the figures' first runs). The
paper's loop has gamma = 1/theta on every side.

Holding the inactive points (robin.robin_laws' hold): the Robin coefficient on all of a
contact, the side's own trace as data where Psi = 0, so that no matrix depends on the
contact set. A held point relaxes towards its free position by a share gamma_side /
(gamma_side + E*_own k / 2) per iteration only: at once on a body much stiffer than its
neighbour (whose small coefficient it gets), slowly on a body as soft as or softer
than its neighbour, at the long wavelengths of a face much larger than the contact.
So a side holds only where its body is at least hold_contrast times as stiff (E*) as
its neighbour: its worker then factorises once per run. Every other side releases its
inactive points (alpha = gamma Psi), and its worker factorises again when the contact
set changes (measured, one level at mesh level 1: the gallery's coating scenes took
30-55 % fewer iterations released than held; docs/method.md). A solve from the
subdomains' Robin maps, and a coarse level, need every matrix fixed: every side holds
(robin_laws' ``direct``; side_parameters' ``hold_all``).
"""

from dataclasses import dataclass, replace
import math

from orchestrate.model.estimate import contact_half_width

NEIGHBOUR, EQUAL = "neighbour", "equal"
RULES = (NEIGHBOUR, EQUAL)
# A friction side's Robin parameter over the one its own body would give a neighbour (gamma
# times its own E* over the stiffer body's). Its traction is given (mu p: a Neumann
# condition), which a Robin side reaches by relaxation, at each wavelength by the share
# alpha / (alpha + its body's stiffness there) per iteration: the long waves of a large
# body, soft, barely moved under the contact's gamma (measured: estimates stuck near
# 2e-10 on a 4 b block; under a rigid indenter's 1/theta, 90 iterations against 21
# without friction). A small alpha makes each solve nearly the Neumann problem itself;
# the fixed point does not depend on it.
FRICTION_SHARE = 1e-3
# A bond's two sides (rule "neighbour"): each side's coefficient should approximate the
# other side's Dirichlet-to-Neumann response at the contact's wavenumber k = pi / a (a the
# a priori contact half-width). The base offers E3* k; a coating of thickness h2 on it
# offers E2* k where it is thick (k h2 >= 1) and only about E2* h2 k^2 where it is thin
# (its membrane: a thin free layer follows what its bond imposes). The ratio
# r = E3* / (E2* min(1, k h2)) is split about gamma, sqrt(r) on the coating's side and
# 1 / sqrt(r) on the base's (measured on the gallery's thin-coating scenes: a split of
# 8 and 1/8 took 34-39 iterations against 49-55 with gamma on both), within
# [1, BOND_RATIO_LIMIT]: a stiff thick coating keeps gamma on both sides. Where r > 1
# and the scene has no friction, the split is widened further by Settings.bond_split, as
# a contact's is (the note below), up to sqrt(BOND_RATIO_LIMIT) (beyond, the 1 um DLC
# film's sides at 64 and 1/64 sent its contact set wandering at mesh level 2: 267
# iterations over 23 sets against 31 in one): with the contact's sides split, the gallery's
# coatings at mesh level 1 took 2-10 iterations fewer in their final contact set at 4-16
# than at 1 (at 4: TiN 33 -> 27, thick ceramic 31 -> 29, anodised 30 -> 20),
# the paper's scene iterated 67 -> 47; at 8 that scene diverged with a short Anderson
# history (anderson_depth 5), at 4 it converged. Under friction it slowed partial slip
# (63 -> 116 iterations) and the fretting example (69 -> 150). By default (bond_split 16)
# every such split reaches the limit: a thin coating's bond is solved inside the base's
# worker wherever the loop iterates on one level (strategy._bonds_inside), and what is
# left exchanged is a thick coating's, two elastic faces, which the far split suits as it
# suits a contact (the note below: the thick ceramic 21/22/22 at mesh levels 1/2/3,
# against 29/34/38 at 4).
BOND_RATIO_LIMIT = 256.0
# A contact's two sides (rule "neighbour", iterated on one level, frictionless): the
# stiffer side's coefficient is divided by the split (Settings.contact_split) and the
# softer side's multiplied (capped at 1/theta), widening the neighbour rule's own
# asymmetry. Split far (256, the default), the exchange nears a Dirichlet-Neumann one:
# the soft side takes the stiff side's displacements, the stiff side the soft side's
# tractions. Its
# error at wavenumber k is then multiplied by minus the ratio of the two faces'
# responses, and two elastic faces both respond as E* k / 2: the ratio is about the same
# at every wavelength from the contact's width down to the element's, the map's
# eigenvalues cluster, and the accelerated loop takes about as many iterations on every
# mesh, far fewer than at a split of 4 (make iterations: results/iterations.md).
# A small split (4: two coefficients matching the band's two ends, Gander's two-sided
# optimised Robin conditions) contracts the band too, but by a factor that nears 1 as
# the band widens with the mesh. A thin coating's bond is no such pair (its response is
# E2* h2 k^2 against the base's E3* k): where it is exchanged, not solved inside the
# base's worker, its ratio spans the band. Faces within CONTACT_TIE of each other count
# as equal and the indenter, a plain body, takes the smaller coefficient (thin hard
# coatings, at a split of 4: 28-33 iterations; the other way round, 34-39). Under
# friction the contact's normal exchange steers the slip, and splitting it slowed
# partial slip (63 -> 154 iterations at 4); under a coarse level, whose sides are held,
# it slowed the loop (TiN at mesh level 2: 28 -> 47 at 4).
CONTACT_TIE = 1.5


# Under an indenter more than hold_contrast times as stiff as the base (E*), whose side
# the split leaves nearly free (a Neumann side on the body the force holds), a wider
# split lengthened the contact set's walk: the near-rigid cylinder's scene at mesh level
# 1/2, 256 against 4, E1/E3 = 10: 77/75 iterations against 46/45 (final set 13/16
# against 18/24), E1/E3 = 100: 44/57 against 29/33, E1 = 1000 E3: 30 against 22, a rigid
# one 55 against 27. Under a softer indenter the far split is the faster (E1/E3 = 0.1:
# 13/15 iterations against 23/28, 0.01: 7/11 against 10/14).
CONTACT_SPLIT_UNDER_CONTRAST = 4.0
# Where the stamp's partner carries its force (force_balance.py) the walk was the
# descent's, found at once: split wider, the final set took fewer iterations at mesh
# level 3 (splits 4/8/16/32: the contrast study's E1/E3 = 10 23/17/16/20, E1/E3 = 100
# 14/10/11/14, the gallery's near-rigid cylinder 10/7/7/9, steel on coated polymer
# 17/13/10/10; at 256, E1/E3 = 10 31), at levels 1 and 2 about as many or fewer.
CONTACT_SPLIT_BALANCED_UNDER_CONTRAST = 16.0


def _stiff_indenter(stiffness, interface, hold_contrast):
    """Whether a contact's side A (the indenter) is more than hold_contrast times as stiff
    (E*) as side B's body (a coating counted as its base, as in side_parameters)."""
    indenter, partner = (stiffness[side.subdomain] for side in interface.sides)
    return indenter > hold_contrast * partner


@dataclass(frozen=True)
class SideParameter:
    """One side of one interface: its Robin parameter and whether it holds its inactive
    points where the loop iterates."""

    interface: str
    side: int                   # 0: side A (the indenter, or the coating of a bond)
    subdomain: str
    neighbour: str
    gamma: float                # E/b, in the solver's units
    hold_inactive: bool
    stiff_neighbour: bool       # the neighbour more than hold_contrast times as stiff
    # where each contact set is solved directly the fixed point is all that counts: split
    # sides (a bond's, a contact's) keep the unsplit gamma (its system's rounding is today's)
    direct_gamma: float

    def solved_directly(self):
        return replace(self, gamma=self.direct_gamma)


def contrast_exceeds(problem, rule, hold_contrast):
    """Whether some side's neighbour is more than hold_contrast times as stiff as its body
    (E*): a coarse level, whose maps need every side held, cannot model the loop there,
    and a held side crawls under such a neighbour's coefficient."""
    return any(side.stiff_neighbour for side in
               side_parameters(problem, problem.robin, rule, hold_contrast))


def soft_coating(problem, hold_contrast):
    """Whether some coating is more than hold_contrast times softer (E*) than the base it
    is bonded to."""
    base = problem.subdomains[_base(problem)]
    return any(plane_strain_modulus(sub) * hold_contrast < plane_strain_modulus(base)
               for sub in problem.subdomains.values() if sub.coating)


def _base(problem):
    """The name of the base: the subdomain neither a coating nor the stamp's."""
    return next(name for name, sub in problem.subdomains.items()
                if not sub.coating and not sub.stamp)


def plane_strain_modulus(subdomain):
    """E* = E / (1 - nu^2): the stiffness of the body's face per wavenumber, times 2."""
    return subdomain.E / (1.0 - subdomain.nu ** 2)


def _patch(problem, coating):
    """The scene's patch of the subdomain named ``coating`` (coatingN: the N-th)."""
    return problem.scene.coatings[int(coating[len("coating"):]) - 1]


def face_stiffness(problem, name):
    """The E* the contact meets on subdomain ``name``'s face at the contact's scale: a
    coating's layered with its base's, the coating's where it is thick against the
    contact half-width a (compliance (1 - w) / E2* + w / E3*, w = exp(-2 pi h2 / a)),
    a body's own E*."""
    subdomains = problem.subdomains
    sub = subdomains[name]
    if not sub.coating:
        return plane_strain_modulus(sub)
    base = plane_strain_modulus(subdomains[_base(problem)])
    a = contact_half_width(problem.scene)
    if not a > 0:
        return base
    w = math.exp(-2.0 * math.pi * _patch(problem, name).thickness / a)
    return 1.0 / ((1.0 - w) / plane_strain_modulus(sub) + w / base)


def _smaller_contact_side(problem, own, neighbour, side):
    """Whether a contact's side takes the smaller coefficient of the split (contact_split):
    its face the stiffer, the indenter's where the faces are within CONTACT_TIE."""
    face_own, face_neighbour = face_stiffness(problem, own), face_stiffness(problem, neighbour)
    if side == 0:
        return face_own * CONTACT_TIE > face_neighbour
    return face_own > CONTACT_TIE * face_neighbour


def bond_ratio(problem, coating):
    """r of a bond between ``coating`` (a subdomain's name) and its base (the module's
    note); 1 where the scene has no contact estimate."""
    scene, subdomains = problem.scene, problem.subdomains
    a = contact_half_width(scene)
    if not a > 0:
        return 1.0
    base = subdomains[_base(problem)]
    thin = min(1.0, math.pi * _patch(problem, coating).thickness / a)
    ratio = plane_strain_modulus(base) / (plane_strain_modulus(subdomains[coating]) * thin)
    return min(max(ratio, 1.0), BOND_RATIO_LIMIT)


def side_parameters(problem, gamma, rule, hold_contrast, paper=False, hold_all=False,
                    split_sides=True, balanced=False):
    """Every side's SideParameter, in the order of problem.interfaces, sides A then B.
    ``gamma``: the run's Robin parameter in the solver's units (a side's is never above
    1/theta, as the run's is not: Settings.robin_choice); ``rule``: NEIGHBOUR or
    EQUAL; ``hold_contrast``: a side holds its inactive points unless its neighbour is
    more than this many times as stiff as its body (E*); ``paper``: the paper's loop (gamma on
    every side, nothing held); ``split_sides``: a bond's gamma split (bond_ratio, and
    Settings.bond_split without friction), and a frictionless contact's
    (Settings.contact_split), where the loop iterates on one level (split
    on both levels, the coated roller took 68-76 iterations at mesh level 2 against 37-46
    unsplit); ``balanced``: the stamp's partner carries its force (force_balance.py),
    so the stamp's sides release their inactive points whatever its stiffness (held,
    they hold back the descent the balance sets at once: the contrast study's E1/E3 =
    10 at mesh level 2, 29 iterations balanced and held, 21 released) and a contact
    under a stiff indenter is split up to CONTACT_SPLIT_BALANCED_UNDER_CONTRAST."""
    subdomains = problem.subdomains
    base = _base(problem)
    # a thin coating counts as the base it is bonded to: at the contact's scale the
    # coated base offers the base's stiffness (to be refined for thick coatings)
    stiffness = {name: plane_strain_modulus(subdomains[base] if sub.coating else sub)
                 for name, sub in subdomains.items()}
    # gamma is set for the stiffer elastic body; a rigid one's (infinite) caps its
    # neighbours' sides at 1/theta
    reference = max(value for value in stiffness.values() if value < float("inf"))
    frictional = any(interface.kind == "friction" for interface in problem.interfaces)
    contact_split, bond_split = problem.settings.contact_split, problem.settings.bond_split
    sides = []
    for interface in problem.interfaces:
        for side in (0, 1):
            own, neighbour = (interface.sides[side].subdomain,
                              interface.sides[1 - side].subdomain)
            scale = stiffness[neighbour] / reference if rule == NEIGHBOUR and not paper else 1.0
            hold = not paper and (hold_all or (
                stiffness[own] >= hold_contrast * stiffness[neighbour]
                and not (balanced and subdomains[own].stamp)))
            direct_gamma = min(gamma * scale, 1.0 / problem.penalty)
            if interface.kind == "bond" and rule == NEIGHBOUR and split_sides and not paper:
                ratio = bond_ratio(problem, interface.sides[0].subdomain)
                split = math.sqrt(ratio) * (bond_split if ratio > 1 and not frictional else 1.0)
                split = min(split, math.sqrt(BOND_RATIO_LIMIT))
                scale *= split if side == 0 else 1.0 / split
            if (interface.kind == "contact" and rule == NEIGHBOUR and split_sides
                    and not paper and not frictional):
                split = (min(contact_split, CONTACT_SPLIT_BALANCED_UNDER_CONTRAST if balanced
                                 else CONTACT_SPLIT_UNDER_CONTRAST)
                         if _stiff_indenter(stiffness, interface, hold_contrast)
                         else contact_split)
                scale *= (1.0 / split if _smaller_contact_side(problem, own, neighbour, side)
                          else split)
            side_gamma = min(gamma * scale, 1.0 / problem.penalty)
            if interface.kind == "friction":    # held: its alpha is too small to matter
                own_scale = stiffness[own] / reference if not paper else 1.0
                side_gamma = direct_gamma = FRICTION_SHARE * min(gamma * own_scale,
                                                                 1.0 / problem.penalty)
                hold = True
            sides.append(SideParameter(interface.name, side, own, neighbour, side_gamma, hold,
                                       stiffness[neighbour] > hold_contrast * stiffness[own],
                                       direct_gamma))
    return tuple(sides)
