"""The FreeFEM processes: finding FreeFEM and the forms (freefem.py), what the forms are
(provenance.py: their hashes), one persistent worker behind two FIFOs (worker.py), the
records exchanged with it (exchange.py), workers kept from scene to scene (session.py),
the workers of one run and their input files (subdomains.py), and a worker's
Robin-to-trace map (robin_map.py). The forms' Python side: nothing here solves an
equation, every solve is a worker's."""

from orchestrate.workers.provenance import forms_digest
from orchestrate.workers.session import Session
from orchestrate.workers.children import die_with_parent

__all__ = ["Session", "die_with_parent", "forms_digest"]
