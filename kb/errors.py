"""Every error type of the knowledge base, each a ``KbError``: bad input, queries over budget, storage."""

from __future__ import annotations

import errno
from pathlib import Path


class KbError(Exception):
    """A request the KB cannot carry out; the message says what is wrong and where.

    When a batch raises it, nothing of the batch has been written.
    """


class StorageError(KbError):
    """The data directory could not take a write (an I/O error): nothing of it was written."""

    def __init__(self, message: str, cause_errno: int | None = None) -> None:
        super().__init__(message)
        self.errno = cause_errno


class StorageFull(StorageError):
    """The data directory's disk (or quota) is full: nothing of the write was written."""


class DataCorrupt(KbError):
    """The data directory holds damaged records; starting would lose acknowledged writes."""


class InvalidUnicode(KbError):
    """Text holding a code point that is not a Unicode scalar value."""


class InvalidCharacter(KbError):
    """Text holding a character that an RDF serialisation cannot carry (a C0 control but tab,
    newline and carriage return; U+FFFE, U+FFFF): the KB could not be exported and loaded back."""


class InvalidRegex(KbError):
    """A REGEX or REPLACE pattern that is not a valid regular expression."""


class InvalidSparql(KbError):
    """Text that does not parse as SPARQL (of the kind expected)."""


class QueryEvaluationError(KbError):
    """A query whose evaluation met values it cannot combine where SPARQL has no error value to
    give (an aggregate, an ordering): it was stopped, nothing changed."""


class UnsupportedUpdate(KbError):
    """A SPARQL Update other than INSERT DATA / DELETE DATA on the model itself."""


class TooManyRows(KbError):
    """A query with more distinct rows than the caller allows (evaluation stops there)."""

    def __init__(self, limit: int) -> None:
        super().__init__(f"the query has more than {limit} rows; make the patterns more specific")
        self.limit = limit


class QueryTooLarge(KbError):
    """A query whose text, or a string its expressions build, is over the KB's bounds (it was not
    run, or stopped; nothing changed)."""


class NotSerialisable(KbError):
    """A graph that the format asked for cannot write: RDF/XML names a predicate as an XML element,
    so a predicate that no XML name ends (``http://x.org/p/``, ``http://x.org/1``) has no RDF/XML
    form. Nothing is wrong with the graph; another format writes it."""


class TBoxTooLarge(KbError):
    """A write whose TBox change would cost the reasoner more than the KB allows (nothing of it
    was written)."""


class ReasoningTooLarge(KbError):
    """A write whose facts would cost the reasoner more derivations than one write may take
    (nothing of it was written)."""


class QueryTimeout(KbError):
    """A query that did not finish within its time budget (it was stopped, nothing changed)."""

    def __init__(self, seconds: float, waiting: bool = False) -> None:
        what = ("waited for the KB longer than" if waiting else "ran longer than")
        super().__init__(f"the query {what} its time budget of {seconds:g} s and was stopped; "
                         "make it more specific")
        self.seconds = seconds


class ModelLimit(KbError):
    """A write that would make more models than the KB may hold, or a model (other than the robot's)
    hold more statements of its own than one may (each model costs memory: kb.modelbounds)."""


class StoreUnavailable(KbError):
    """The SPARQL store could not be reached, did not answer in time or failed the request."""


class OutcomeUnknown(StoreUnavailable):
    """An update was sent and no answer came: the store may have applied it, or apply it later."""


# Errors that mean "no space", whatever the filesystem calls it.
_FULL = frozenset({errno.ENOSPC, errno.EDQUOT})


def storage_error(exc: OSError, directory: Path, what: str) -> StorageError:
    """The KB's error for an OS error while writing ``what`` in ``directory``."""
    if exc.errno == errno.EFBIG:  # the disk may have room: the file may not grow
        return StorageFull(f"a file of the data directory {directory} is at the largest size it may have "
                           f"({exc.strerror}: the process's file-size limit, ulimit -f, or the "
                           f"filesystem's): {what} was not saved and nothing changed; raise the limit or "
                           f"compact the journal (a snapshot empties it)", exc.errno)
    if exc.errno in _FULL:
        return StorageFull(f"the disk of the data directory {directory} is full ({exc.strerror}): "
                           f"{what} was not saved and nothing changed; free space and retry", exc.errno)
    return StorageError(f"cannot write to the data directory {directory} ({exc.strerror or exc}): "
                        f"{what} was not saved and nothing changed", exc.errno)
