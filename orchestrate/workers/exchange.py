"""The records a worker and the driver exchange, and the files a worker reads once.
freefem/robin.idp and freefem/interface.idp read and write the same, in the same order.

Sides file (one per subdomain, read at start): the number of its sides; "components
points" of each; then, side by side, count-first arrays: the weights omega, the place of
every point (a body: x1, x2; a shell: xi), and for every component its coefficients (a
body: c1, c2; a shell: cV, cW, cG).

Request (CmdSolve, CmdMap): for every side of the subdomain, in interface order, its
Robin coefficient alpha, then its data g, one array per component. (CmdMap's reply and
CmdOutput's request: freefem/robin.idp, orchestrate/workers/robin_map.py, Worker.send_output.)

Reply: for every side, in the same order, its trace, one array per component; then
[CPU seconds of the request, of its back-substitution, the stamp's descent].
"""

import numpy as np


def write_sides(path, sides):
    """``sides``: (interface, Side) pairs of one subdomain, in interface order."""
    def array(values):
        values = np.asarray(values, dtype=float)
        return f"{values.size}\n" + "\n".join(map(repr, values.tolist())) + "\n"

    with open(path, "w") as out:
        out.write(f"{len(sides)}\n")
        for interface, side in sides:
            out.write(f"{interface.components} {interface.size}\n")
        for interface, side in sides:
            out.write(array(interface.weight))
            place = np.asarray(side.place)
            if place.ndim == 2:
                out.write(array(place[:, 0]) + array(place[:, 1]))
            else:
                out.write(array(place))
            for coefficients in side.coefficients:
                for column in np.asarray(coefficients).T:
                    out.write(array(column))


def request_arrays(sides, data):
    """The arrays of one request. ``sides``: (interface index, side) of the subdomain in
    order; ``data``: {(interface index, side): (alpha, g)} (robin.robin_data)."""
    arrays = []
    for key in sides:
        alpha, g = data[key]
        arrays.append(alpha)
        arrays.extend(np.atleast_2d(g))
    return arrays


def reply_count(problem, sides):
    """Arrays in a reply: every component of every side, and the closing info array."""
    return sum(problem.interfaces[i].components for i, _ in sides) + 1


def parse_reply(problem, sides, arrays):
    """({(interface index, side): trace}, info) from a reply's arrays; a contact's trace
    has the shape (points,), a bond's (2, points)."""
    traces, k = {}, 0
    for i, side in sides:
        components = problem.interfaces[i].components
        block = arrays[k:k + components]
        traces[i, side] = block[0] if components == 1 else np.array(block)
        k += components
    return traces, arrays[k]
