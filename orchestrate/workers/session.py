"""Workers that outlive a scene.

The scenes of a sweep often share bodies: every figure scene has the same indenter (only
lifted by h2) and the same base, whose matrices therefore do not change. A Session keeps
the workers of the scene it last served; a subdomain of the next scene whose worker would
read the same mesh (up to a shift of the whole body), material, load and sides takes
that worker as it is, factorisation and all, and its fields are put at the scene's place
(Subdomains.outputs shifts the nodes it sends). Workers the next scene does not use are
stopped when it ends.

A kept worker is asked once for its Robin-to-trace map (orchestrate/workers/robin_map.py),
which the loop then evaluates instead of a solve, when its solves in the scenes it served
have cost what the map costs (orchestrate/workers/subdomains.py).

A worker compiles its forms (freefem/*.idp) when it starts. So that an edited form
takes effect in the next scene, a kept worker serves a scene only while the forms' digest
(orchestrate/workers/provenance.py) is the one it started with; after an edit every kept worker
is stopped and started anew.

    with Session() as session:
        for scene in scenes:
            solve(scene, settings, out, session=session)

Without a session, solve() makes one for the run alone. close() stops every worker and
removes the folder of their FIFOs; a process killed before it closes leaves a folder that
the next run removes (folders.remove_dead_work_folders).
"""

import hashlib
import itertools
import threading
import weakref

import numpy as np

from orchestrate.files.folders import WorkFolder
from orchestrate.workers.provenance import forms_digest
from orchestrate.workers.worker import Worker

# Coordinates that agree to this fraction of a body's extent are the same point.
_SAME_POINT = 1e-9


def body_fingerprint(mesh, sides):
    """(fingerprint, origin) of a body's mesh and sides: what its worker reads, with every coordinate
    taken from the lower-left corner ``origin`` of the mesh's bounding box, so that a
    shifted body has the same fingerprint; the order of the mesh's vertices and
    elements does not count (gmsh numbers a shifted outline differently).

    ``sides``: (interface, Side) pairs as written to the sides file."""
    points = np.asarray(mesh.points[:, :2], dtype=float)
    origin = points.min(axis=0)
    scale = _SAME_POINT * max(float(np.ptp(points, axis=0).max()), 1e-300)
    key = np.round((points - origin) / scale).astype(np.int64)
    order = np.lexsort(key.T[::-1])
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    digest = hashlib.sha256()
    digest.update(key[order].tobytes())
    refs = mesh.cell_data.get("medit:ref", [None] * len(mesh.cells))
    for block, ref in zip(mesh.cells, refs):
        cells = np.sort(rank[block.data], axis=1)
        labelled = np.column_stack([cells, np.zeros(len(cells), np.int64) if ref is None
                                    else np.asarray(ref, np.int64)])
        digest.update(block.type.encode())
        digest.update(labelled[np.lexsort(labelled.T[::-1])].tobytes())
    for interface, side in sides:
        place = np.asarray(side.place, dtype=float)
        digest.update(np.asarray(interface.weight, dtype=float).tobytes())
        digest.update(np.round((place - origin) / scale).astype(np.int64).tobytes())
        for coefficients in side.coefficients:
            digest.update(np.asarray(coefficients, dtype=float).tobytes())
    return digest.hexdigest(), origin


def files_fingerprint(paths):
    """(fingerprint, origin 0) of the files a worker reads (a shell: its nodes and sides,
    which hold no coordinates of the plane)."""
    digest = hashlib.sha256()
    for path in paths:
        with open(path, "rb") as data:
            digest.update(data.read())
    return digest.hexdigest(), np.zeros(2)


class Entry:
    """A kept worker: where its mesh lies, how many scenes it served, its map, the thread
    that started it."""

    def __init__(self, worker, dofs, origin, forms):
        self.worker = worker
        self.dofs = dofs
        self.origin = origin
        self.forms = forms         # the digest of the forms when it started
        self.scenes = 0
        self.solves = 0            # the real Robin solves it answered, over every scene
        self.robin_map = None
        # it dies with this thread (children.die_with_parent: the kernel's parent-death
        # signal follows the thread that started a process, not its process)
        self.thread = threading.current_thread()


class Session:
    """The workers of the last scene served, by fingerprint (see the module's text).

    One scene at a time: solve() holds the session's lock for the whole run, so scenes
    solved with one Session from several threads are solved one after the other, each
    with the answer it has alone (requests of two runs never interleave on a worker);
    a thread does not take the workers another thread started (they die with it).
    ``with Session() as session:`` stops its workers at the end of the block; a Session
    never closed stops them when it is garbage-collected, or when the interpreter exits.
    ``map_kept``: whether a kept worker gives its Robin map once its solves paid for it
    (orchestrate/workers/subdomains.py), which pays over a sweep; a load path's own
    session of two or three steps does not ask it (a coated base's map cost 8 s where
    its step took 3 s)."""

    def __init__(self, map_kept=True):
        self.map_kept = map_kept
        self._workers = _Workers()
        self.lock = threading.RLock()
        self._finalizer = weakref.finalize(self, self._workers.close)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def take(self, name, script, arguments, fingerprint, origin, timeout):
        """The entry of a worker that reads what ``fingerprint`` stands for: kept from an
        earlier scene, or started now (not yet ready: call ``ready``)."""
        return self._workers.take(name, script, arguments, fingerprint, origin, timeout)

    def ready(self, entry):
        """Wait for a new worker's set-up; return its dof count."""
        if entry.dofs is None:
            entry.dofs = entry.worker.wait_ready()
        return entry.dofs

    def keep_only(self, fingerprints):
        """End of a scene: stop every worker it did not use."""
        self._workers.keep_only(fingerprints)

    def drop(self, fingerprint):
        self._workers.drop(fingerprint)

    @property
    def workers(self):
        """The kept workers."""
        return [entry.worker for entry in self._workers.entries.values()]

    @property
    def folder(self):
        """The folder of the kept workers' FIFOs and logs."""
        return self._workers.folder

    def close(self):
        """Stop every worker; remove their folder."""
        self._finalizer()


class _Workers:
    """A Session's kept workers and their folder: apart from the Session, so that its
    finaliser can stop them without keeping it alive."""

    def __init__(self):
        self.folder_owner = self.path = None
        self.entries = {}
        self.names = itertools.count()

    @property
    def folder(self):
        if self.folder_owner is None:
            owner = WorkFolder()
            self.path = owner.__enter__()
            self.folder_owner = owner
        return self.path

    def take(self, name, script, arguments, fingerprint, origin, timeout):
        forms = forms_digest()
        entry = self.entries.get(fingerprint)
        if (entry is None or entry.worker.process.poll() is not None   # died
                or entry.forms != forms                                  # edited forms
                or entry.thread is not threading.current_thread()):      # would die with it
            self.drop(fingerprint)
            worker = Worker(name, script, arguments, self.folder, timeout,
                            stem=f"{name}-{next(self.names)}")
            entry = self.entries[fingerprint] = Entry(worker, None, np.asarray(origin), forms)
        entry.worker.timeout = timeout
        entry.scenes += 1
        return entry

    def keep_only(self, fingerprints):
        for fingerprint in [f for f in self.entries if f not in fingerprints]:
            self.drop(fingerprint)

    def drop(self, fingerprint):
        entry = self.entries.pop(fingerprint, None)
        if entry is not None:
            entry.worker.stop()

    def close(self):
        try:
            workers = [self.entries.pop(fingerprint).worker for fingerprint in list(self.entries)]
            try:
                for worker in workers:          # all asked first: they exit side by side
                    worker.ask_to_stop()
                for worker in workers:
                    worker.wait_stopped()
            finally:
                for worker in workers:          # any left by an interruption (kill: twice safe)
                    worker.kill()
        finally:
            if self.folder_owner is not None:
                self.folder_owner.__exit__()
                self.folder_owner = None
