"""The error types of the knowledge base: knowledge_core's ``KbError`` and the storage errors."""

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


# Errors that mean "no space", whatever the filesystem calls it.
_FULL = frozenset({errno.ENOSPC, errno.EDQUOT, errno.EFBIG})


def storage_error(exc: OSError, directory: Path, what: str) -> StorageError:
    """The KB's error for an OS error while writing ``what`` in ``directory``."""
    if exc.errno in _FULL:
        return StorageFull(f"the disk of the data directory {directory} is full ({exc.strerror}): "
                           f"{what} was not saved and nothing changed; free space and retry", exc.errno)
    return StorageError(f"cannot write to the data directory {directory} ({exc.strerror or exc}): "
                        f"{what} was not saved and nothing changed", exc.errno)
