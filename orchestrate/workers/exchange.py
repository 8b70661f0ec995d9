"""The records the driver and a FreeFEM worker exchange, each defined once here and once
in freefem/exchange.idp, with the same fields in the same order
(tests/workers/test_protocol.py sends every one through FreeFEM and back).

What travels through the FIFOs is binary (an integer as an int64, a number as a
float64, an array count-first, the machine's byte order): the text of a body's fields
cost more to print and parse than to compute. The files the driver writes for a worker
(a sides file, a shell's numbers) are text in full precision: a number as it is, an
array count-first (its length, then its values). A request is its command's number,
then its record; a reply is its record, then the word "end" (worker.py).

    Sides          a subdomain's sides file, read once at its start
    RobinRequest   Command.SOLVE and Command.MAP: alpha and g on every side
    TraceReply     the reply to SOLVE: the traces, CPU seconds, the stamp's descent
    MapReply       the reply to MAP: the Robin-to-trace map (robin_map.py)
    OutputRequest  Command.OUTPUT: the fields, or a body's reactions alone
    BodyOutput     a body's reply to OUTPUT: nodal fields, cells, reactions
    ShellOutput    a shell's reply to OUTPUT: its fields along the mid-line (a plane
                   shell's or a shell of revolution's)
    ShellNumbers   a shell's numbers: shell.edp's arguments, monolithic.edp's problem file

Every record has ``encode()`` (a file's text, or the bytes a FIFO carries) and
``decode(numbers, ...)`` (from a file's ``Numbers`` or a FIFO's ``BinaryNumbers``, with
the sizes the record does not hold).
"""

from dataclasses import astuple, dataclass, fields
import enum
import math
from typing import ClassVar

import numpy as np


class Command(enum.IntEnum):
    """The first number of a request."""
    STOP = 0      # leave the loop and exit
    SOLVE = 1     # RobinRequest: solve, reply TraceReply
    OUTPUT = 2    # OutputRequest: reply BodyOutput or ShellOutput
    MAP = 3       # RobinRequest: reply MapReply


class RecordError(ValueError):
    """A text that is not the record it should be."""


def encode(*values):
    """Numbers and arrays as a record's text: integers (and flags) as integers, other
    numbers in full precision, arrays count-first."""
    parts = []
    for value in values:
        if isinstance(value, (bool, int, np.integer)):
            parts.append(str(int(value)))
        elif isinstance(value, (float, np.floating)):
            parts.append(repr(float(value)))
        else:                                     # integers stay integers, floats repr
            items = np.asarray(value).ravel().tolist()
            parts.append(f"{len(items)}\n" + " ".join(map(repr, items)))
    return "\n".join(parts) + "\n"


class Numbers:
    """A record's numbers as they arrived, read field by field in order."""

    def __init__(self, values, what="a record"):
        self.values = np.asarray(values, dtype=float)
        self.what = what
        self.at = 0

    @classmethod
    def parse(cls, text, what="a record"):
        """From a record's text (str or bytes)."""
        try:            # every number at once: a map's reply holds tens of thousands
            return cls(np.fromstring(text, sep=" "), what)
        except ValueError:
            raise RecordError(f"{what} that is not numbers: {text[:200]!r}") from None

    def number(self):
        if self.at >= len(self.values):
            raise RecordError(f"{self.what} that ends early ({len(self.values)} numbers)")
        self.at += 1
        return float(self.values[self.at - 1])

    def integer(self):
        value = self.number()
        if not (math.isfinite(value) and value >= 0 and value == int(value)):
            raise RecordError(f"{self.what} with {value!r} where a count or flag is due")
        return int(value)

    def array(self, size=None):
        """The next count-first array; ``size``: the length it must have."""
        n = self.integer()
        if size is not None and n != size:
            raise RecordError(f"{self.what} with an array of {n} values where {size} are due")
        if self.at + n > len(self.values):
            raise RecordError(f"{self.what} that ends early ({len(self.values)} numbers)")
        self.at += n
        return self.values[self.at - n:self.at]

    def end(self):
        """The record is read: nothing may follow."""
        if self.at != len(self.values):
            raise RecordError(f"{self.what} with {len(self.values) - self.at} unexpected values")


REPLY_END = b"end"      # the word closing every reply


def encode_binary(*values):
    """Numbers and arrays as the bytes a FIFO carries (freefem/exchange.idp's binary
    streams):
    integers and flags as int64, other numbers as float64, arrays count-first (an int64
    count, then the values: int64 for an array of integers, else float64)."""
    parts = []
    for value in values:
        if isinstance(value, (bool, int, np.integer)):
            parts.append(np.int64(value).tobytes())
        elif isinstance(value, (float, np.floating)):
            parts.append(np.float64(value).tobytes())
        else:
            array = np.asarray(value).ravel()
            kind = np.int64 if array.dtype.kind in "biu" else np.float64
            parts += [np.int64(len(array)).tobytes(), array.astype(kind).tobytes()]
    return b"".join(parts)


def encode_reply(*values):
    """A reply's bytes: its record (encode_binary), then its closing word."""
    return encode_binary(*values) + REPLY_END


class BinaryNumbers:
    """A record's numbers as a FIFO carries them (binary), read field by field in order;
    ``take(n)`` returns the next n bytes, writable (a worker's replies as they arrive:
    worker.py; bytes at hand: ``of_bytes``). ``closing``: the word after the record (a
    reply's; a request has none)."""

    def __init__(self, take, what="a reply", unread=lambda: 0, closing=REPLY_END):
        self.take = take
        self.what = what
        self.unread = unread     # bytes known to follow the record: none on a FIFO (the
                                 # next reply comes only after the next request)
        self.closing = closing

    @classmethod
    def of_bytes(cls, data, what="a reply", closing=REPLY_END):
        """From a whole record's bytes: ``end`` then also checks that nothing follows."""
        data, at = memoryview(data), 0

        def take(n):
            nonlocal at
            if at + n > len(data):
                raise RecordError(f"{what} that ends early ({len(data)} bytes)")
            at += n
            return bytearray(data[at - n:at])

        return cls(take, what, lambda: len(data) - at, closing)

    def _values(self, n, dtype):
        return np.frombuffer(self.take(8 * n), dtype=dtype)

    def number(self):
        return float(self._values(1, np.float64)[0])

    def integer(self):
        value = int(self._values(1, np.int64)[0])
        if value < 0:
            raise RecordError(f"{self.what} with {value} where a count or flag is due")
        return value

    def _count(self, size):
        n = self.integer()
        if size is not None and n != size:
            raise RecordError(f"{self.what} with an array of {n} values where {size} are due")
        return n

    def array(self, size=None):
        """The next count-first array of numbers; ``size``: the length it must have."""
        return self._values(self._count(size), np.float64)

    def integers(self, size=None):
        """The next count-first array of integers; ``size``: the length it must have."""
        return self._values(self._count(size), np.int64)

    def end(self):
        """The record is read: its closing word must follow, and nothing after it."""
        closing = bytes(self.take(len(self.closing)))
        if closing != self.closing or self.unread():
            raise RecordError(f"{self.what} that does not end where its record does "
                              f"({closing!r}, {self.unread()} bytes after)")


# ---- Sides ------------------------------------------------------------------------------

BODY_PLACE = ("x1", "x2")           # a body's points: where on its mesh
SHELL_PLACE = ("xi",)               # a shell's: arc length along its mid-line
BODY_TRACE_FIELDS = ("u1", "u2")    # a body's trace = c1 u1 + c2 u2; a shell's one
                                    # coefficient per field (freefem/shell.idp)


@dataclass(frozen=True, eq=False)
class SideArrays:
    """One side in a sides file: the weights omega of its points, their place (one array
    per coordinate, BODY_PLACE or SHELL_PLACE) and for each trace component its
    coefficients (one array per field)."""
    omega: np.ndarray
    place: tuple
    coefficients: tuple       # per component: a tuple of arrays, one per field

    @classmethod
    def of(cls, interface, side):
        """From an interface and its Side (orchestrate/mesh/discretization.py)."""
        place = np.asarray(side.place, dtype=float)
        return cls(np.asarray(interface.weight, dtype=float),
                   tuple(place.T) if place.ndim == 2 else (place,),
                   tuple(tuple(np.asarray(c, dtype=float).T) for c in side.coefficients))


@dataclass(frozen=True, eq=False)
class Sides:
    """A sides file (freefem/interface.idp reads it): the number of sides; each side's
    trace components and points; then side by side its arrays (SideArrays: omega, the
    place, each component's coefficients)."""
    sides: tuple

    def encode(self):
        header = [len(self.sides)]
        for side in self.sides:
            header += [len(side.coefficients), len(side.omega)]
        arrays = [array for side in self.sides
                  for array in (side.omega, *side.place, *(a for c in side.coefficients
                                                          for a in c))]
        return encode(*header, *arrays)

    @classmethod
    def decode(cls, numbers, coordinates, fields_per_component):
        """``coordinates``, ``fields_per_component``: the place's and a component's
        arrays (a body: 2, 2; a shell: 1 and its field count)."""
        count = numbers.integer()
        shape = [(numbers.integer(), numbers.integer()) for _ in range(count)]
        sides = []
        for components, points in shape:
            omega = numbers.array(points)
            place = tuple(numbers.array(points) for _ in range(coordinates))
            coefficients = tuple(tuple(numbers.array(points) for _ in range(fields_per_component))
                                 for _ in range(components))
            sides.append(SideArrays(omega, place, coefficients))
        return cls(tuple(sides))


# ---- A Robin iteration: request and replies -------------------------------------------

@dataclass(frozen=True, eq=False)
class RobinRequest:
    """Command.SOLVE, Command.MAP: for every side of the subdomain, in interface order,
    its Robin coefficient alpha at every point, then its data g, one array per trace
    component."""
    alphas: tuple             # per side: (points,)
    data: tuple               # per side: (components, points)

    @classmethod
    def of(cls, sides, robin_data):
        """``sides``: (interface index, side) of the subdomain in order; ``robin_data``:
        {(interface index, side): (alpha, g)} (ddm/robin.py's robin_data)."""
        return cls(tuple(np.asarray(robin_data[key][0], dtype=float) for key in sides),
                   tuple(np.atleast_2d(np.asarray(robin_data[key][1], dtype=float))
                         for key in sides))

    def encode(self):
        return encode_binary(*(array for alpha, g in zip(self.alphas, self.data)
                               for array in (alpha, *g)))

    @classmethod
    def decode(cls, numbers, components):
        """``components``: every side's trace components, in order."""
        alphas, data = [], []
        for count in components:
            alphas.append(numbers.array())
            data.append(np.array([numbers.array(len(alphas[-1])) for _ in range(count)]))
        return cls(tuple(alphas), tuple(data))

    @property
    def g(self):
        """Every datum in order: side by side, component by component, point by point
        (the order of a map's columns)."""
        return np.concatenate([g.ravel() for g in self.data])


@dataclass(frozen=True, eq=False)
class TraceReply:
    """The reply to Command.SOLVE: for every side, in the request's order, its trace, one
    array per component; then the CPU seconds of the request, those of its
    back-substitution alone, the stamp's descent and its shift along x1 (0 but for the
    stamp's body, the shift 0 but under partial slip)."""
    traces: tuple             # per side: (components, points)
    seconds: float
    back_seconds: float
    descent: float
    shift: float = 0.0

    def encode(self):
        return encode_reply(*(row for trace in self.traces for row in trace),
                            self.seconds, self.back_seconds, self.descent, self.shift)

    @classmethod
    def decode(cls, numbers, shape):
        """``shape``: every side's (components, points), in order."""
        traces = tuple(np.array([numbers.array(points) for _ in range(components)])
                       for components, points in shape)
        return cls(traces, numbers.number(), numbers.number(), numbers.number(),
                   numbers.number())

    def by_side(self, sides):
        """{side: trace} for ``sides``, the request's sides in order: a trace of one
        component (a contact's) of shape (points,), else (components, points)."""
        return {side: trace[0] if len(trace) == 1 else trace
                for side, trace in zip(sides, self.traces)}


@dataclass(frozen=True, eq=False)
class MapReply:
    """The reply to Command.MAP, the Robin-to-trace map at the request's alpha:
    traces = matrix g + constant, descent = descent_row g + descent0 (g in
    RobinRequest.g's order). The response to g = 0 (every trace value in that order,
    then the descent), then the response to each unit datum (a column of matrix, then
    of descent_row), each one array; then the CPU seconds of the request and of its
    back-substitutions."""
    constant: np.ndarray
    descent0: float
    matrix: np.ndarray        # (unknowns, unknowns)
    descent_row: np.ndarray
    seconds: float
    back_seconds: float

    def encode(self):
        responses = [np.append(self.constant, self.descent0)]
        responses += [np.append(column, d) for column, d in zip(self.matrix.T, self.descent_row)]
        return encode_reply(*responses, self.seconds, self.back_seconds)

    @classmethod
    def decode(cls, numbers, unknowns):
        """``unknowns``: the interface unknowns, the length of g."""
        base = numbers.array(unknowns + 1)
        table = np.array([numbers.array(unknowns + 1) for _ in range(unknowns)]).T
        table = table.reshape(unknowns + 1, unknowns)        # no unknowns: still a table
        return cls(base[:unknowns].copy(), float(base[unknowns]), table[:unknowns],
                   table[unknowns], numbers.number(), numbers.number())


# ---- Output -----------------------------------------------------------------------------

@dataclass(frozen=True)
class OutputRequest:
    """Command.OUTPUT: 1 for the fields (and a body's reactions), 0 for a body's reactions
    alone."""
    fields: bool

    def encode(self):
        return encode_binary(self.fields)

    @classmethod
    def decode(cls, numbers):
        return cls(bool(numbers.integer()))


# At a body's P2 nodes: the place where the worker's mesh lies, the displacement, the von
# Mises stress and the stress tensor (plane strain), recovered at the nodes
BODY_COLUMNS = ("x1", "x2", "u1", "u2", "sigma_eq", "s11", "s22", "s12", "s33")
# A P2 triangle's nodes: its vertices, then the midpoints of edges 01, 12, 20 (VTK's
# triangle6)
CELL_NODES = 6
# Along a shell's mid-line: arc length, fields and forces (freefem/shell.idp)
SHELL_COLUMNS = ("xi", "v", "w", "gamma", "epsilon", "T11", "T13", "M11", "T33")
# Along a shell of revolution's: radius, fields and forces per unit length of a circle
# (freefem/shell_revolution.idp; N_z is its T33, the normal force through the thickness)
REVOLUTION_SHELL_COLUMNS = ("xi", "u", "w", "beta", "epsilon", "N_r", "N_theta", "Q", "M_r",
                            "M_theta", "N_z")


@dataclass(frozen=True, eq=False)
class BodyOutput:
    """A body's reply to Command.OUTPUT: the number of its P2 nodes (rows), of its
    triangles (cells) and of its supports; BODY_COLUMNS at every node, one array each;
    the triangles' nodes (rows of the columns, CELL_NODES per triangle) as one array;
    the supports' labels (freefem/labels.idp), the consistent reactions R1, R2 on them.
    Without the fields rows and cells are 0."""
    columns: dict             # name -> (rows,)
    cells: np.ndarray         # (cells, CELL_NODES) of int
    reactions: dict           # label -> (R1, R2)

    def encode(self):
        labels = list(self.reactions)
        r1, r2 = (np.array([self.reactions[label][k] for label in labels], dtype=float)
                  for k in (0, 1))
        return encode_reply(len(self.columns[BODY_COLUMNS[0]]), len(self.cells), len(labels),
                            *(self.columns[name] for name in BODY_COLUMNS),
                            np.asarray(self.cells, dtype=np.int64),
                            np.array(labels, dtype=np.int64), r1, r2)

    @classmethod
    def decode(cls, numbers):
        rows, cells, supports = numbers.integer(), numbers.integer(), numbers.integer()
        columns = {name: numbers.array(rows) for name in BODY_COLUMNS}
        nodes = numbers.integers(CELL_NODES * cells).reshape(cells, CELL_NODES)
        labels = numbers.integers(supports)
        r1, r2 = numbers.array(supports), numbers.array(supports)
        return cls(columns, nodes, {int(label): (float(a), float(b))
                                    for label, a, b in zip(labels, r1, r2)})


@dataclass(frozen=True, eq=False)
class ShellOutput:
    """A shell's reply to Command.OUTPUT: the number of its samples along the mid-line
    (rows), then its columns at every sample, one array each (the ends and inner points
    of every element: a node appears twice, its forces jump): SHELL_COLUMNS, or a shell
    of revolution's REVOLUTION_SHELL_COLUMNS. Without the fields rows is 0."""
    columns: dict             # name -> (rows,), in the record's order

    def encode(self):
        return encode_reply(len(next(iter(self.columns.values()))), *self.columns.values())

    @classmethod
    def decode(cls, numbers, names=SHELL_COLUMNS):
        """``names``: the columns, SHELL_COLUMNS or REVOLUTION_SHELL_COLUMNS."""
        rows = numbers.integer()
        return cls({name: numbers.array(rows) for name in names})


# ---- A shell's numbers ------------------------------------------------------------------

@dataclass(frozen=True)
class ShellNumbers:
    """A shell's numbers, in b and E: shell.edp takes each after its flag (FLAGS),
    monolithic.edp's problem file lists them in this order."""
    E: float
    nu: float
    thickness: float          # h2
    shear_factor: float       # k'
    curvature: float          # k21 of the mid-line (1/its radius)
    stretch: bool             # with thickness stretch
    symmetric_start: bool     # its start on the symmetry axis of a half model

    FLAGS: ClassVar[tuple] = ("-E", "-nu", "-h2", "-kshear", "-curvature", "-stretch",
                              "-symmetric")

    @classmethod
    def of(cls, subdomain):
        """A shell subdomain's (orchestrate/mesh/discretization.py)."""
        plan = subdomain.plan
        return cls(subdomain.E, subdomain.nu, plan.thickness, plan.shear_factor,
                   plan.curvature, bool(plan.thickness_stretch), bool(plan.symmetric_start))

    def _values(self):
        return [int(v) if isinstance(v, bool) else v for v in astuple(self)]

    def encode(self):
        return encode(*self._values())

    def arguments(self):
        """Its flags and values, as shell.edp's command line takes them."""
        return [item for flag, value in zip(self.FLAGS, self._values()) for item in (flag, value)]

    @classmethod
    def decode(cls, numbers):
        values = [numbers.number() for _ in fields(cls)]
        return cls(*values[:5], bool(values[5]), bool(values[6]))
