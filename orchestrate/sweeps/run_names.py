"""The names of a sweep's run folders: a point's values, read as the sweep file gives them.

A point {eps_u: 1e-6, model: "shell", h2: 0.125} runs in
``eps_u=1e-06_model=shell_h2=0.125``: its keys in the file's order ([fixed] first, then
the grid's or run's), numbers as ``:g`` writes them, lists comma-joined, the brackets of
``coating[2].E`` dropped and every character that is not a letter, a digit or one of
``. , _ + = -`` replaced by ``_``. A name is a function of the point's values alone, so a
point keeps its folder when the sweep grows, unless:

- two points of the sweep would share a name (values that differ only in replaced
  characters, 5 and 5.0, beyond ``:g``'s six digits, or in letter case, which some file
  systems ignore): each of them then takes ``@`` and a short hash of its values as a
  suffix (a point that had the name alone before is run again, into its suffixed
  folder: which point the old folder holds is not known);
- the name would be longer than MAX_LENGTH: it is cut, and takes the suffix.

No name without ``@`` holds one, so a suffixed name is never another point's plain name.
"""

import hashlib
import json
import re
from collections import Counter

MAX_LENGTH = 120        # characters: a name one can read, list and type
SUFFIX = "@"            # never in a plain name
HASH_LENGTH = 8         # hex digits of the suffix (more if two points' would agree)
DEFAULT = "default"     # the name of a point of no values: no other name lacks "="
UNSAFE = re.compile(r"[^A-Za-z0-9.,_+=-]")


def values_hash(values):
    """The hex digest of a point's values (the order of its keys aside)."""
    text = json.dumps({k: values[k] for k in sorted(values)}, sort_keys=True)
    return hashlib.sha1(text.encode()).hexdigest()


def value_text(value):
    """A value as a name shows it: numbers as ``:g`` writes them (six digits: two points
    whose values agree to six digits share that name, and take the hash suffix)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    if isinstance(value, (list, tuple)):
        return ",".join(value_text(item) for item in value)
    if isinstance(value, dict):
        return json.dumps(value, sort_keys=True)
    return str(value)


def plain_name(values):
    """key=value pairs in the point's order, joined by ``_``, unsafe characters replaced;
    a point of no values (every default) is ``default``."""
    pairs = (f"{key.replace('[', '').replace(']', '')}={value_text(value)}"
             for key, value in values.items())
    return UNSAFE.sub("_", "_".join(pairs)) or DEFAULT


def run_names(points):
    """The folder names of distinct points, in their order: plain names where they are
    unique and short enough, else suffixed with a hash of the values."""
    hashes = [values_hash(values) for values in points]
    if len(set(hashes)) != len(hashes):
        raise ValueError("run_names: the points must be distinct")
    plain = [plain_name(values) for values in points]
    shared = Counter(name.casefold() for name in plain)
    length = HASH_LENGTH
    while True:
        names = [name if shared[name.casefold()] == 1 and len(name) <= MAX_LENGTH
                 else name[:MAX_LENGTH - 1 - length] + SUFFIX + digest[:length]
                 for name, digest in zip(plain, hashes)]
        if len({name.casefold() for name in names}) == len(names):
            return names
        length += 4             # two points' short hashes agree: longer hashes
