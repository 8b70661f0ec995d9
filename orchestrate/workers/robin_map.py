"""A subdomain's Robin-to-trace map, asked of its worker once and evaluated in its stead.

For a fixed Robin coefficient alpha a subdomain's solve is affine in its Robin data g:
its traces are M g + m and the stamp's descent d'g + d0 (d = 0 unless the stamp carries
a force). The worker computes M column by column, one back-substitution per interface
unknown (freefem/robin.idp, CmdMap; exchange.py's MapReply), which costs about as many
Robin iterations as the subdomain has interface unknowns. It pays where a worker serves
many scenes (orchestrate/workers/session.py): from then on a solve of that subdomain is
a small dense product. The answer is the same: the last solve of a run is a real one,
checked against the map (``check``).
"""

import time

import numpy as np

from orchestrate.workers.exchange import Command, MapReply, TraceReply
from orchestrate.workers.worker import WorkerError

# A real solve and the map's evaluation agree to rounding: the map's columns are solves
# of the same factorisation. More than this relative difference means a stale map.
AGREEMENT = 1e-9


class RobinMap:
    """traces = M g + m, descent = d'g + d0, valid at the Robin coefficients ``alphas``.
    ``components``: for every side in order, its number of trace components."""

    def __init__(self, alphas, components, matrix, constant, descent_row, descent0):
        self.alphas = [np.array(a, dtype=float) for a in alphas]
        self.components = list(components)
        self.matrix = matrix
        self.constant = constant
        self.descent_row = descent_row
        self.descent0 = descent0

    def serves(self, request):
        """Whether the RobinRequest has the map's Robin coefficients."""
        return all(np.array_equal(a, alpha) for a, alpha in zip(request.alphas, self.alphas))

    def reply(self, request):
        """The worker's TraceReply to a solve of the RobinRequest, from the map."""
        start = time.process_time()
        traces = self.matrix @ request.g + self.constant
        descent = float(self.descent_row @ request.g + self.descent0)
        ends = np.cumsum([g.size for g in request.data])[:-1]
        shaped = tuple(t.reshape(g.shape) for t, g in zip(np.split(traces, ends), request.data))
        return TraceReply(shaped, time.process_time() - start, 0.0, descent)


def send_map_request(worker, request):
    """Ask ``worker`` for its map at the Robin coefficients of the RobinRequest (its data
    do not matter); ``receive_map`` reads the answer."""
    worker.send(Command.MAP, request)


def receive_map(worker, request, components):
    """The map asked by ``send_map_request(worker, request)``; ``components`` as
    RobinMap's."""
    unknowns = sum(len(a) * c for a, c in zip(request.alphas, components))
    answer = worker.receive(MapReply.decode, unknowns)
    return RobinMap(request.alphas, components, answer.matrix, answer.constant,
                    answer.descent_row, answer.descent0)


def check(worker_name, robin_map, request, reply):
    """Raise WorkerError unless a real solve's TraceReply ``reply`` to the RobinRequest
    agrees with the map's."""
    predicted = np.concatenate([t.ravel() for t in robin_map.reply(request).traces])
    solved = np.concatenate([t.ravel() for t in reply.traces])
    scale = max(float(np.max(np.abs(solved))), 1e-300)
    difference = float(np.max(np.abs(predicted - solved))) / scale
    if difference > AGREEMENT:
        raise WorkerError(f"worker {worker_name}: its Robin-to-trace map and its solve differ "
                          f"by {difference:.2e} of the traces (more than {AGREEMENT:g})")
