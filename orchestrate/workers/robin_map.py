"""A subdomain's Robin-to-trace map, asked of its worker once and evaluated in its stead.

For a fixed Robin coefficient alpha a subdomain's solve is affine in its Robin data g:
its traces are M g + m and the stamp's descent d'g + d0 (d = 0 unless the stamp carries
a force). The worker computes M column by column, one back-substitution per interface
unknown (freefem/robin.idp, CmdMap), which costs about as many Robin iterations as the
subdomain has interface unknowns. It pays where a worker serves many scenes
(orchestrate/workers/session.py): from then on a solve of that subdomain is a small dense
product. The answer is the same: the last solve of a run is a real one, checked against
the map (``check``).
"""

import time

import numpy as np

from orchestrate.workers.worker import CMD_MAP, WorkerError

# A real solve and the map's evaluation agree to rounding: the map's columns are solves
# of the same factorisation. More than this relative difference means a stale map.
AGREEMENT = 1e-9


class RobinMap:
    """traces = M g + m, descent = d'g + d0, valid at the Robin coefficients ``alphas``.
    ``components``: for every side in order, its number of trace components."""

    def __init__(self, alphas, components, matrix, constant, descent_row, descent0):
        self.alphas = [np.array(a, dtype=float) for a in alphas]
        self.components = list(components)
        self.starts = _side_starts(components)      # each side's alpha in a request
        self.matrix = matrix
        self.constant = constant
        self.descent_row = descent_row
        self.descent0 = descent0

    def serves(self, arrays):
        """Whether the request has the map's Robin coefficients."""
        return all(np.array_equal(arrays[i], alpha)
                   for i, alpha in zip(self.starts, self.alphas))

    def reply(self, arrays):
        """The worker's reply to a solve request (its traces, then [seconds, 0, descent]),
        from the map."""
        start = time.process_time()
        data = [arrays[i + 1 + c] for i, components in zip(self.starts, self.components)
                for c in range(components)]
        g = np.concatenate(data)
        traces = self.matrix @ g + self.constant
        descent = float(self.descent_row @ g + self.descent0)
        ends = np.cumsum([len(d) for d in data])[:-1]
        return np.split(traces, ends) + [np.array([time.process_time() - start, 0.0, descent])]


def send_map_request(worker, arrays):
    """Ask ``worker`` for its map at the Robin coefficients of the request ``arrays``
    (its data do not matter); ``receive_map`` reads the answer."""
    worker.send(CMD_MAP, arrays)


def receive_map(worker, arrays, components):
    """The map asked by ``send_map_request(worker, arrays)``; ``components`` as
    RobinMap's."""
    alphas = [arrays[i] for i in _side_starts(components)]
    unknowns = sum(len(a) * c for a, c in zip(alphas, components))
    columns = worker.receive_arrays(unknowns + 2)
    if any(len(column) != unknowns + 1 for column in columns[:-1]):
        raise WorkerError(f"worker {worker.name} sent a map of the wrong size")
    base = columns[0]
    table = np.array(columns[1:-1]).T                     # column j: the response to e_j
    return RobinMap(alphas, components, table[:unknowns], base[:unknowns],
                    table[unknowns], base[unknowns])


def _side_starts(components):
    starts, i = [], 0
    for c in components:
        starts.append(i)
        i += 1 + c
    return starts


def check(worker_name, robin_map, arrays, reply):
    """Raise WorkerError unless a real solve's traces ``reply`` agree with the map's."""
    predicted = np.concatenate(robin_map.reply(arrays)[:-1])
    solved = np.concatenate(reply[:-1])
    scale = max(float(np.max(np.abs(solved))), 1e-300)
    difference = float(np.max(np.abs(predicted - solved))) / scale
    if difference > AGREEMENT:
        raise WorkerError(f"worker {worker_name}: its Robin-to-trace map and its solve differ "
                          f"by {difference:.2e} of the traces (more than {AGREEMENT:g})")
