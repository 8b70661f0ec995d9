"""A run's CSV tables (orchestrate/files/writing.py's csv_bytes): every number reads back
as the very value written, integers stay integers, and the text is what Python's csv
module reads into the same rows."""

import csv
import io

import numpy as np

from orchestrate.files.writing import csv_bytes


def _rows(data):
    return list(csv.reader(io.StringIO(data.decode(), newline="")))


def test_floats_of_every_magnitude_read_back_exactly():
    rng = np.random.default_rng(7)
    values = rng.random(20000) * np.exp(rng.normal(0.0, 40.0, 20000)) * rng.choice([-1, 1], 20000)
    values[:6] = [0.0, -0.0, 5e-324, 1.7976931348623157e308, 1e16, 1e-5]
    table = {"x1": values, "x2": values[::-1].copy(), "u1": values / 3.0}
    data = csv_bytes(table)
    assert data.endswith(b"\r\n") and data.count(b"\r\n") == 20001
    header, *rows = _rows(data)
    read = np.array([[float(x) for x in row] for row in rows])
    assert header == list(table)
    for j, column in enumerate(table.values()):
        np.testing.assert_array_equal(read[:, j], column)
    assert np.signbit(read[1, 0])               # -0.0 keeps its sign


def test_integers_stay_integers_beside_floats():
    cells = {"n0": np.arange(4), "n1": np.arange(4) * 1000003}
    assert _rows(csv_bytes(cells)) == [["n0", "n1"], *[[str(i), str(i * 1000003)]
                                                        for i in range(4)]]
    mixed = {"label": np.array([3, 7]), "R1": np.array([0.1, -2.5e-12])}
    assert _rows(csv_bytes(mixed)) == [["label", "R1"], ["3", "0.1"], ["7", "-2.5e-12"]]


def test_non_finite_numbers_and_other_values_are_written_as_the_csv_module_does():
    table = {"a": np.array([1.5, np.nan, -np.inf]), "b": np.array([1, 2, 3])}
    assert _rows(csv_bytes(table)) == [["a", "b"], ["1.5", "1"], ["nan", "2"], ["-inf", "3"]]
    names = {"interface": np.array(["contact", "bond"]), "s": np.array([0.25, 1.0])}
    assert _rows(csv_bytes(names)) == [["interface", "s"], ["contact", "0.25"], ["bond", "1.0"]]


def test_an_empty_table_is_its_header():
    assert csv_bytes({"a": np.zeros(0), "b": np.zeros(0)}) == b"a,b\r\n"
    assert csv_bytes({"n": np.zeros(0, dtype=int), "x": np.zeros(0)}) == b"n,x\r\n"
