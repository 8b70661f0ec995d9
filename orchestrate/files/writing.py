"""Files written whole or not at all: each goes to a partial name beside its place and is
renamed once written, so a file that exists is complete (a run's files, sweep tables,
figures). A run itself writes into a private scratch folder (folders.py) that takes its
output folder's name once complete. A CSV table or a VTU mesh may be rendered in memory
first (csv_bytes, vtu_bytes), to be written and kept as the same bytes."""

import csv
import io
import json
import os
from pathlib import Path

import numpy as np
import orjson

from orchestrate.errors import system_failure


def partial_path(path):
    """Where ``written`` writes ``path`` before the rename."""
    path = Path(path)
    return path.with_name(f".{path.name}.partial")


def _atomic(path):
    return Path(path), partial_path(path)


def written(path, write):
    """Run write(partial path), then rename; a failed write leaves nothing and says why."""
    path, partial = _atomic(path)
    try:
        write(partial)
        os.replace(partial, path)
    except OSError as error:
        partial.unlink(missing_ok=True)
        raise system_failure(error, f"writing {path.name}") from None


def write_json(path, data):
    write_text(path, json.dumps(data, indent=2) + "\n")


def write_text(path, text):
    written(path, lambda partial: Path(partial).write_text(text))


def write_bytes(path, data):
    written(path, lambda partial: Path(partial).write_bytes(data))


def _write_vtu(path, mesh):
    """Binary, the arrays' own precision, not compressed: zlib took a third of the time
    a run spent writing its files, to make them less than half smaller."""
    import meshio      # loaded where a VTU is written: a refusal needs none (0.1 s)
    meshio.write(path, mesh, file_format="vtu", binary=True, compression=None)


def write_vtu(path, mesh):
    """Write a meshio mesh as VTU (_write_vtu)."""
    written(path, lambda partial: _write_vtu(partial, mesh))


def vtu_bytes(mesh, name="a VTU file"):
    """The VTU file of a meshio mesh (as write_vtu writes it), in memory: meshio writes
    only to a file it opens by name, here one in memory (memfd)."""
    try:
        fd = os.memfd_create("vtu")
        try:
            _write_vtu(f"/proc/self/fd/{fd}", mesh)
            return os.pread(fd, os.lseek(fd, 0, os.SEEK_END), 0)
        finally:
            os.close(fd)
    except OSError as error:            # a file size limit holds in memory too
        raise system_failure(error, f"writing {name}") from None


def csv_bytes(columns):
    """``{name: values}`` as CSV, columns in the given order, full precision (Python's
    csv module's text: None empty, lines ended by CRLF; a number as its shortest text
    that reads back exactly, an integer as an integer)."""
    names = list(columns)
    values = [np.asarray(columns[n]) for n in names]
    header = ",".join(names).encode() + b"\r\n"
    if values and all(v.dtype.kind in "fiu" for v in values) and all(
            np.isfinite(v).all() for v in values if v.dtype.kind == "f"):
        return header + number_rows(values)
    out = io.StringIO(newline="")
    writer = csv.writer(out)
    writer.writerow(names)
    writer.writerows(zip(*(v.tolist() for v in values)))
    return out.getvalue().encode()


def number_rows(values, separator=b",", newline=b"\r\n"):
    """Finite numbers' rows, one column per array of ``values``, rendered by orjson
    (ryu's shortest round-trip text, in C: a tenth of the time of Python's repr, which a
    body's fields spent 0.1-0.25 s in); columns of one kind as one array, whose JSON rows
    become the lines."""
    if not len(values[0]):
        return b""
    columns = [v.astype(float if v.dtype.kind == "f" else np.int64) for v in values]
    if len({v.dtype for v in columns}) == 1:
        text = orjson.dumps(np.column_stack(columns), option=orjson.OPT_SERIALIZE_NUMPY)
        rows = text[2:-2].replace(b"],[", newline)
        return (rows if separator == b"," else rows.replace(b",", separator)) + newline
    texts = [orjson.dumps(v, option=orjson.OPT_SERIALIZE_NUMPY)[1:-1].split(b",")
             for v in columns]
    return b"".join(separator.join(row) + newline for row in zip(*texts))


def write_csv(path, columns):
    """Write ``{name: values}`` as CSV (csv_bytes)."""
    write_bytes(path, csv_bytes(columns))
