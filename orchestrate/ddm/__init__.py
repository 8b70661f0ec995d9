"""The Robin domain decomposition on the interface state: the state's layout
(state.py), the contact and bond laws (contact.py), the Robin loops and their laws
(robin.py), Anderson acceleration (acceleration.py), a contact set's fixed point solved
directly (interface_system.py), the coarse-mesh correction (coarse.py), and the
strategy a run is solved by, decided once and handed to the loop (strategy.py). It
calls the subdomains' solves through a function it is given: it starts no process."""

from orchestrate.ddm.coarse import coarse_element_size
from orchestrate.ddm.contact import contact_half_width

__all__ = ["coarse_element_size", "contact_half_width"]
