"""The protocol between the driver and its FreeFEM workers: every record of
orchestrate/workers/exchange.py, encoded in Python, read by FreeFEM with
freefem/exchange.idp's macros and written back with the same macros
(tests/forms/freefem/exchange_round_trip.edp), decodes equal to what was sent, to the
last bit: the files a worker reads as text, what the FIFOs carry in binary. In between
FreeFEM marks every field by its name (MARKS: a factor of its own, a flag flipped, an
integer shifted), so a field that one side reads into another's place fails the test,
as do a count, a size or an order that differ. A shell's numbers also pass through
shell.edp's way of reading them, its command-line flags."""

from dataclasses import replace

import numpy as np
import pytest

from orchestrate.workers.exchange import (BODY_COLUMNS, BODY_PLACE, BODY_TRACE_FIELDS,
                                          CELL_NODES, REPLY_END, SHELL_COLUMNS, SHELL_PLACE,
                                          BinaryNumbers, BodyOutput, MapReply, Numbers,
                                          OutputRequest, RecordError, RobinRequest,
                                          ShellNumbers, ShellOutput, SideArrays, Sides,
                                          TraceReply)

SHELL_FIELDS = 4                 # a shell with thickness stretch: v, w, gamma, epsilon
BODY_SIDES = ((1, 5), (2, 7))    # (components, points): a contact's side, a bond's


def _sides(rng, shape, coordinates, fields):
    return Sides(tuple(SideArrays(rng.random(points),
                                  tuple(rng.normal(size=points) for _ in range(coordinates)),
                                  tuple(tuple(rng.normal(size=points) for _ in range(fields))
                                        for _ in range(components)))
                       for components, points in shape))


def _records(rng):
    """Each record with values of every sign and scale, by its file name."""
    unknowns = sum(c * p for c, p in BODY_SIDES)
    rows, cells = 11, 4
    return {
        "body.sides": _sides(rng, BODY_SIDES, len(BODY_PLACE), len(BODY_TRACE_FIELDS)),
        "shell.sides": _sides(rng, ((1, 6), (2, 6)), len(SHELL_PLACE), SHELL_FIELDS),
        "robin_request": RobinRequest(tuple(rng.random(p) * 1e3 for _, p in BODY_SIDES),
                                      tuple(rng.normal(size=(c, p)) * 1e-4 for c, p in BODY_SIDES)),
        "trace_reply": TraceReply(tuple(rng.normal(size=(c, p)) for c, p in BODY_SIDES),
                                  0.012, 3.5e-4, -2.779e-3, 1.25e-4),
        "map_reply": MapReply(rng.normal(size=unknowns), 0.25,
                              rng.normal(size=(unknowns, unknowns)) / 7, rng.normal(size=unknowns),
                              1.5, 0.75),
        "output_request": OutputRequest(True),
        "body_output": BodyOutput({name: rng.normal(size=rows) * 10.0 ** k
                                   for k, name in enumerate(BODY_COLUMNS, start=-8)},
                                  rng.integers(0, rows, size=(cells, CELL_NODES)),
                                  {1: (1e-5, -2e-6), 3: (0.0, -7.5e-4), 4: (3e-19, 7.5e-4)}),
        "shell_output": ShellOutput({name: rng.normal(size=rows) for name in SHELL_COLUMNS}),
        "shell_numbers": ShellNumbers(5.0, 0.25, 0.125, 5.0 / 6.0, -0.0125, True, False),
    }


# What FreeFEM does to each field by its name before writing it back (the script's marks)
BODY_MARKS = dict(zip(BODY_COLUMNS, 2.0 ** np.arange(1, 10)))
SHELL_MARKS = dict(zip(SHELL_COLUMNS, 2.0 ** np.arange(1, 10)))
MARKS = {
    "body.sides": lambda r: Sides(tuple(_marked_side(side) for side in r.sides)),
    "shell.sides": lambda r: Sides(tuple(_marked_side(side) for side in r.sides)),
    "robin_request": lambda r: RobinRequest(tuple(2 * a for a in r.alphas),
                                            tuple(4 * g for g in r.data)),
    "trace_reply": lambda r: TraceReply(tuple(2 * t for t in r.traces), 4 * r.seconds,
                                        8 * r.back_seconds, 16 * r.descent, 32 * r.shift),
    "map_reply": lambda r: replace(r, constant=2 * r.constant, descent0=2 * r.descent0,
                                   seconds=4 * r.seconds, back_seconds=8 * r.back_seconds),
    "output_request": lambda r: OutputRequest(not r.fields),
    "body_output": lambda r: BodyOutput(
        {name: BODY_MARKS[name] * values for name, values in r.columns.items()}, r.cells + 1,
        {label + 10: (2 * r1, 4 * r2) for label, (r1, r2) in r.reactions.items()}),
    "shell_output": lambda r: ShellOutput({name: SHELL_MARKS[name] * values
                                           for name, values in r.columns.items()}),
    "shell_numbers": lambda r: ShellNumbers(2 * r.E, 4 * r.nu, 8 * r.thickness,
                                            16 * r.shear_factor, 32 * r.curvature,
                                            not r.stretch, not r.symmetric_start),
}


def _marked_side(side):
    return SideArrays(2 * side.omega, tuple(4 * p for p in side.place),
                      tuple(tuple(8 * c for c in component) for component in side.coefficients))


REQUESTS = ("robin_request", "output_request")                            # in binary
REPLIES = ("trace_reply", "map_reply", "body_output", "shell_output")     # the same, closed
BINARY = REQUESTS + REPLIES                                               # by "end"


def _decode(name, data, closing=REPLY_END):
    """``closing``: the word after a binary record (FreeFEM closes every record it writes
    back as a reply; a request as sent has none)."""
    numbers = (BinaryNumbers.of_bytes(data, name, closing) if name in BINARY
               else Numbers.parse(data, name))
    decoders = {
        "body.sides": lambda n: Sides.decode(n, len(BODY_PLACE), len(BODY_TRACE_FIELDS)),
        "shell.sides": lambda n: Sides.decode(n, len(SHELL_PLACE), SHELL_FIELDS),
        "robin_request": lambda n: RobinRequest.decode(n, [c for c, _ in BODY_SIDES]),
        "trace_reply": lambda n: TraceReply.decode(n, BODY_SIDES),
        "map_reply": lambda n: MapReply.decode(n, sum(c * p for c, p in BODY_SIDES)),
        "output_request": OutputRequest.decode,
        "body_output": BodyOutput.decode,
        "shell_output": ShellOutput.decode,
        "shell_numbers": ShellNumbers.decode,
        "shell_arguments": ShellNumbers.decode,
    }
    record = decoders[name](numbers)
    numbers.end()
    return record


def _same(a, b, where):
    """Equal to the bit, field by field (arrays, tuples, dicts, numbers)."""
    if isinstance(a, dict):
        assert list(a) == list(b), where
        for key in a:
            _same(a[key], b[key], f"{where}[{key!r}]")
    elif isinstance(a, (tuple, list)):
        assert len(a) == len(b), where
        for k, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}[{k}]")
    elif hasattr(a, "__dataclass_fields__"):
        assert type(a) is type(b), where
        for field in a.__dataclass_fields__:
            _same(getattr(a, field), getattr(b, field), f"{where}.{field}")
    else:
        assert np.array_equal(np.asarray(a), np.asarray(b)), where
        assert np.asarray(a).shape == np.asarray(b).shape, where


@pytest.fixture(scope="module")
def records():
    return _records(np.random.default_rng(2024))


def test_every_record_comes_back_from_freefem_equal(run_freefem, tmp_path, records):
    for name, record in records.items():
        data = record.encode()
        assert isinstance(data, bytes) == (name in BINARY), name
        (tmp_path / name).write_bytes(data if name in BINARY else data.encode())
    numbers = records["shell_numbers"]
    run_freefem("exchange_round_trip.edp", "-dir", tmp_path, "-fields", SHELL_FIELDS,
                *numbers.arguments())
    for name, record in records.items():
        _same(_decode(name, (tmp_path / f"{name}.back").read_bytes()), MARKS[name](record), name)
    _same(_decode("shell_arguments", (tmp_path / "shell_arguments.back").read_bytes()),
          MARKS["shell_numbers"](numbers), "a shell's numbers from its arguments")


def test_every_record_decodes_its_own_encoding(records):
    for name, record in records.items():
        _same(_decode(name, record.encode(), b"" if name in REQUESTS else REPLY_END),
              record, name)


def _first_half(text):
    """The lines of the first half of ``text`` (cut inside a number, the rest of the
    number may read as another number, or as not one)."""
    return text[:text.rindex("\n", 0, len(text) // 2)]


@pytest.mark.parametrize("cut, message", [(_first_half, "ends early"),
                                          (lambda text: text + " 1.0", "unexpected values"),
                                          (lambda text: text.replace("\n", " x ", 1),
                                           "not numbers")])
def test_a_file_cut_short_or_padded_is_refused(records, cut, message):
    with pytest.raises(RecordError, match=message):
        _decode("body.sides", cut(records["body.sides"].encode()))


def _recounted(data):
    """The reply with one more row said than it holds."""
    return (np.frombuffer(data[:8], np.int64) + 1).tobytes() + data[8:]


@pytest.mark.parametrize("cut, message", [
    (lambda data: data[:len(data) // 2], "ends early"),
    (lambda data: data + np.float64(1.0).tobytes(), "does not end where its record does"),
    (lambda data: data[:-3] + b"xyz", "does not end where its record does"),
    (_recounted, "an array of 11 values where 12 are due")])
def test_a_reply_cut_short_padded_or_miscounted_is_refused(records, cut, message):
    """A reply not whole (a worker killed while it wrote) is never taken for a record."""
    with pytest.raises(RecordError, match=message):
        _decode("body_output", cut(records["body_output"].encode()))


def test_a_trace_reply_gives_a_contact_one_trace_and_a_bond_two(records):
    traces = records["trace_reply"].by_side([(0, 1), (1, 0)])
    assert traces[0, 1].shape == (5,) and traces[1, 0].shape == (2, 7)
