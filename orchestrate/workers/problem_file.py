"""The problem file of freefem/composite.idp: subdomains and the interfaces between them,
read by the monolithic solve (monolithic.edp: every subdomain and interface) and by a
coated base's worker (coated_base.edp: the base, its coatings and their bonds)."""

import numpy as np

from orchestrate.workers.exchange import ShellNumbers


def write_problem(problem, files, path, names=None, slip_origin=None):
    """The problem file of the subdomains ``names`` (None: every one, in the problem's
    order) and the interfaces between them; ``files``: write_inputs'. A part of the
    problem (``names`` given) carries no load and takes only its bonds: its contacts are
    the Robin loop's. ``slip_origin``: {friction interface index: its
    points' slips at a load path's step before}, else 0."""
    scene = problem.scene
    whole = names is None
    names = list(problem.subdomains) if whole else list(names)
    if not whole:
        load = "descent 0"
    elif scene.load.force is not None:
        load = f"force {scene.half_force!r}"
    else:
        load = f"descent {scene.load.displacement!r}"
    interfaces = [i for i, interface in enumerate(problem.interfaces)
                  if all(side.subdomain in names for side in interface.sides)
                  and (whole or interface.kind == "bond")]
    lines = [f"{problem.penalty!r} {load} {len(names)} {len(interfaces)}"]
    for name in names:
        subdomain = problem.subdomains[name]
        if subdomain.kind == "rigid":
            lines.append(" ".join(["rigid", "-", files[name]["sides"]]))
        elif subdomain.kind == "body":
            numbers = [subdomain.E, subdomain.nu]
            lines.append(" ".join(["body", files[name]["mesh"], *map(repr, numbers),
                                   files[name]["sides"]]))
        else:
            numbers = ShellNumbers.of(subdomain).encode().split()
            lines.append(" ".join(["shell", files[name]["nodes"], *numbers, files[name]["sides"]]))
    for i in interfaces:
        interface = problem.interfaces[i]
        ends = []
        for side in interface.sides:
            position = [k for k, (j, _) in enumerate(problem.sides_of(side.subdomain)) if j == i]
            ends += [names.index(side.subdomain), position[0]]
        if interface.kind == "friction":    # its contact, and mu in the gap's place
            lines.append(" ".join(map(str, [2, *ends, interfaces.index(interface.contact)])))
            values = interface.friction
        else:
            lines.append(" ".join(map(str, [0 if interface.kind == "contact" else 1, *ends])))
            values = interface.gap
        lines.append(f"{interface.size} " + " ".join(map(repr, values.tolist())))
        if interface.kind == "friction":    # the slips a sticking point keeps
            origin = (slip_origin or {}).get(i, np.zeros(interface.size))
            lines.append(f"{interface.size} " + " ".join(map(repr, np.asarray(origin).tolist())))
    with open(path, "w") as out:
        out.write("\n".join(lines) + "\n")
