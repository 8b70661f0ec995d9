"""What can go wrong in a run, and the exit status each gets.

    0    converged
    1    not converged: the loop diverged, stagnated, hit its iteration limit, or its
         contact reached the end of contact_zone (the report is in the run's folder)
    2    refused: bad input, or an output folder that is not free, before any work
    3    failed: a worker died or hung, a file could not be written (disk full, file size
         limit, permission), or a system resource ran out
    4    an internal error (a bug), with its traceback
    5    under --strict only: warnings (orchestrate/run/validity.py), the scene leaves what the
         tool models: known before any work, the run is refused and writes nothing; found
         by the run, its results are written
    130  interrupted by Ctrl-C (SIGINT); 143 terminated (SIGTERM); 129 hung up (SIGHUP);
         131 quit (SIGQUIT)
"""

import errno
import re
import signal

EXIT_CONVERGED, EXIT_NOT_CONVERGED, EXIT_REFUSED, EXIT_FAILED, EXIT_INTERNAL = 0, 1, 2, 3, 4
EXIT_WARNINGS = 5
LONGEST_WORD = 120     # characters of a word of a message (a path, a value) shown whole
EXIT_INTERRUPTED = {signal.SIGINT: 130, signal.SIGTERM: 143, signal.SIGHUP: 129,
                    signal.SIGQUIT: 131}


class ParameterError(ValueError):
    """Input refused before any work; the message names the parameter (and the file and
    key of a scene file) and its allowed range.

    ``key`` is the offending key (``coating[1].E``), so that callers that set it under
    another name (a command-line flag) can say so."""

    def __init__(self, message, key=None):
        super().__init__(_elided(message))
        self.key = key


def _elided(message):
    """The message with the middle of every word longer than LONGEST_WORD cut out: a
    value of ten kilobytes is named, not echoed."""
    return re.sub(r"\S{%d,}" % (LONGEST_WORD + 1),
                  lambda word: f"{word[0][:48]}...({len(word[0])} characters)...{word[0][-16:]}",
                  message)


class LengthsError(ParameterError):
    """A ParameterError found on the scene in b (the mesh's checks), whose message quotes
    lengths: ``template`` names them ({name}), ``lengths`` gives them in b. The message
    says them in b; ``in_units(length)`` is the same error with each length as the
    function ``length`` (b -> text in the scene's units) says it."""

    def __init__(self, template, key, **lengths):
        self.template, self.lengths = template, lengths
        super().__init__(self._text(lambda value: f"{value:.4g} b"), key)

    def _text(self, length):
        return self.template.format(**{name: length(value)
                                       for name, value in self.lengths.items()})

    def in_units(self, length):
        return ParameterError(self._text(length), self.key)


class WarnedBeforeWork(RuntimeError):
    """Under --strict, a run refused before any work for the warnings its scene already
    has (orchestrate/run/validity.py: a mesh too coarse for the predicted contact, a coating
    model off by its estimate, ...): exit status EXIT_WARNINGS, nothing written."""

    def __init__(self, warnings):
        super().__init__(f"{len(warnings)} warning(s) before any work")
        self.warnings = warnings


class RunFailed(RuntimeError):
    """The Robin loop did not converge; ``summary`` is its report."""

    def __init__(self, summary):
        super().__init__(f"{summary['status']}: {summary['reason']}")
        self.summary = summary


class SystemFailure(RuntimeError):
    """A run could not go on for a reason outside its numbers: a worker, a file, the
    machine. The message names the cause."""


class Interrupted(KeyboardInterrupt):
    """A signal asked the run to stop (SIGINT, SIGTERM, SIGHUP, SIGQUIT); clean-up runs
    as for Ctrl-C."""

    def __init__(self, signum):
        super().__init__(f"signal {signum}")
        self.signum = signum


_CAUSES = {
    errno.ENOSPC: "the disk is full",
    errno.EDQUOT: "the disk quota is exhausted",
    errno.EFBIG: "a file size limit was reached (ulimit -f)",
    errno.EACCES: "permission denied",
    errno.EPERM: "operation not permitted",
    errno.EROFS: "the file system is read-only",
    errno.ENOENT: "no such file or folder",
    errno.EMFILE: "too many open files",
    errno.ENOMEM: "out of memory",
}


def cause(error):
    """The plain cause of an OSError."""
    return _CAUSES.get(getattr(error, "errno", None), getattr(error, "strerror", None) or str(error))


def system_failure(error, doing):
    """A SystemFailure for an OSError met while ``doing`` something ("writing X")."""
    where = f" ({error.filename})" if getattr(error, "filename", None) else ""
    return SystemFailure(f"{doing} failed: {cause(error)}{where}")
