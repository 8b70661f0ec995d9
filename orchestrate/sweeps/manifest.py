"""Which sweep a run folder belongs to, and from what inputs: whether a point is done.
"""

import hashlib
import json
from pathlib import Path
import uuid

from orchestrate.files.writing import write_json
from orchestrate.model.scene import to_dict

NOT_CONVERGED = ("diverged", "stagnated", "max_iterations", "contact_zone")


# A sweep's folder holds MANIFEST: the sweep's identity (made when it first runs), its
# file, and each point's values and inputs. Every run it solves records, in its
# summary.json, that identity and the hash of the inputs it was solved from (its scene as
# its file and values give it, units included, and its settings): a run folder is a
# finished point of this sweep only if both match, and its forms are the files'
# (orchestrate/workers/provenance.py). So a sweep resumed after its scene file or a default was
# edited runs the changed points again, and a run folder copied in from another sweep
# is not taken for one of its points.
MANIFEST = "sweep.json"


def point_inputs(scene, settings):
    """The hash of what a point is solved from: its scene and its settings."""
    text = json.dumps({"scene": to_dict(scene), "settings": to_dict(settings)},
                      sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def sweep_identity(sweep_dir, path, runs, inputs):
    """The sweep's identity, from its manifest (made now if it has none), rewritten with
    the points' values and inputs."""
    manifest_path = Path(sweep_dir) / MANIFEST
    try:
        identity = json.loads(manifest_path.read_text())["sweep_id"]
    except (OSError, ValueError, KeyError, TypeError):
        identity = uuid.uuid4().hex
    write_json(manifest_path, {"sweep_id": identity, "file": str(Path(path).resolve()),
                               "points": {name: {"values": values, "inputs": inputs[name]}
                                          for name, values in runs}})
    return identity


def read_manifest(sweep_dir):
    """The sweep's manifest, or None."""
    try:
        return json.loads((Path(sweep_dir) / MANIFEST).read_text())
    except (OSError, ValueError):
        return None


def point_stamp(sweep_dir, name, manifest=None):
    """What a point's run must have recorded to count (summary.json's "sweep_point"),
    from the manifest (read now unless given); None without one."""
    manifest = read_manifest(sweep_dir) if manifest is None else manifest
    try:
        return {"sweep_id": manifest["sweep_id"],
                "inputs": manifest["points"][name]["inputs"]}
    except (KeyError, TypeError):
        return None


def why_stale(folder, stamp, forms):
    """Why the run in ``folder``, which has an answer or a reason of its numbers, does
    not count as the point of ``stamp`` solved with forms ``forms``; None if it does."""
    try:
        summary = json.loads((Path(folder) / "summary.json").read_text())
    except (OSError, ValueError):
        return "no summary"
    recorded = summary.get("sweep_point") or {}
    if recorded.get("sweep_id") != stamp["sweep_id"]:
        return "not a run of this sweep (copied in, or older than its manifest)"
    if recorded.get("inputs") != stamp["inputs"]:
        return "its inputs changed (the scene file, a value or a default setting)"
    if (summary.get("provenance") or {}).get("forms_digest") != forms:
        return "solved with other FreeFEM forms than the files' now"
    return None


def finished(folder, stamp, forms, retry_failed=False):
    """Whether a point's run is done: converged, or (unless retry_failed) not converged
    for reasons of its numbers; and solved as the point of ``stamp`` (this sweep, from
    these inputs) with the forms of digest ``forms`` (why_stale). A run that is not is
    run again rather than mixed with the new ones."""
    status = run_status(folder)
    done = status == "converged" or (status in NOT_CONVERGED and not retry_failed)
    return done and why_stale(folder, stamp, forms) is None


def solved(folder):
    """Whether a point's folder holds a run that reached an answer or a reason of its
    numbers (not a report of a failure outside them)."""
    return run_status(folder) in ("converged",) + NOT_CONVERGED


def run_status(folder):
    try:
        return json.loads((Path(folder) / "summary.json").read_text()).get("status")
    except (OSError, ValueError):
        return None
