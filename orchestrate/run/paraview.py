"""ParaView collections (.pvd): one file that opens several VTU files together.

    write_collection(path, files)           a run's run.pvd: every subdomain's VTU
    collection_text(files)                  its text (a run renders its files first)
    write_sweep_collection(path, folders)   a sweep's: every run's VTUs, one time step
                                            per run (ParaView's time slider steps
                                            through the runs)

Paths inside a .pvd are relative to its folder, so a run folder (renamed from its
scratch name when complete) or a sweep folder can be moved whole. A .pvd is written
to a temporary name and renamed, like every output (orchestrate/files/writing.py).
"""

import os
import xml.etree.ElementTree as ElementTree

from orchestrate.files.writing import write_text

RUN_COLLECTION = "run.pvd"
SWEEP_COLLECTION = "sweep.pvd"


def _collection(path, datasets):
    """Write a VTK Collection of ``datasets``: dicts of DataSet attributes (file, ...)."""
    write_text(path, _collection_text(datasets))


def _collection_text(datasets):
    root = ElementTree.Element("VTKFile", type="Collection", version="0.1",
                               byte_order="LittleEndian")
    collection = ElementTree.SubElement(root, "Collection")
    for attributes in datasets:
        ElementTree.SubElement(collection, "DataSet",
                               {key: str(value) for key, value in attributes.items()})
    ElementTree.indent(root)
    return '<?xml version="1.0"?>\n' + ElementTree.tostring(root, encoding="unicode") + "\n"


def write_collection(path, files):
    """A .pvd at ``path`` listing ``files`` (VTU paths, absolute or relative to the .pvd's
    folder) as the parts of one data set, named after the files: File > Open this one
    file and ParaView shows them all."""
    write_text(path, collection_text(files, os.path.dirname(os.path.abspath(path))))


def collection_text(files, folder="."):
    """The text of write_collection's .pvd in ``folder``."""
    return _collection_text([{"timestep": 0, "group": "", "part": part,
                              "file": _relative(name, folder),
                              "name": os.path.splitext(os.path.basename(name))[0]}
                             for part, name in enumerate(files)])


def run_files(run_folder):
    """The VTU files of a finished run (absolute paths): those its run.pvd lists, else
    every .vtu in the folder, sorted."""
    run_folder = os.path.abspath(run_folder)
    pvd = os.path.join(run_folder, RUN_COLLECTION)
    if os.path.exists(pvd):
        root = ElementTree.parse(pvd).getroot()
        return [os.path.normpath(os.path.join(run_folder, dataset.get("file")))
                for dataset in root.iter("DataSet")]
    return sorted(os.path.join(run_folder, name) for name in os.listdir(run_folder)
                  if name.endswith(".vtu"))


def write_sweep_collection(path, run_folders, names=None):
    """A .pvd at ``path`` for a sweep: run k of ``run_folders`` is time step k, its
    subdomains the parts of that step (``names``: one label per run, default the
    folders' names). Runs without VTU files (not converged, failed) are left out; the
    runs kept are returned as (time step, folder)."""
    folder = os.path.dirname(os.path.abspath(path))
    names = list(names) if names is not None else [os.path.basename(os.path.normpath(f))
                                                   for f in run_folders]
    datasets, kept = [], []
    for run, name in zip(run_folders, names):
        files = [f for f in run_files(run) if os.path.exists(f)] if os.path.isdir(run) else []
        if not files:
            continue
        step = len(kept)
        kept.append((step, run))
        for part, file in enumerate(files):
            datasets.append({"timestep": step, "group": name, "part": part,
                             "file": _relative(file, folder),
                             "name": f"{name}/{os.path.splitext(os.path.basename(file))[0]}"})
    _collection(path, datasets)
    return kept


def _relative(path, folder):
    return os.path.relpath(os.path.join(folder, path), folder).replace(os.sep, "/")
