"""A real, small filesystem for disk-full tests: a 2 MiB tmpfs that the test mounts.

Why a tmpfs: the kernel itself answers ENOSPC, with the real semantics of write, fsync, rename
and truncate on a full filesystem (a partial write, then an error; truncating frees space), in
every process that uses it, the server under test included. RLIMIT_FSIZE was the alternative; it
gives EFBIG and SIGXFSZ per process, not a full disk shared by every file, so it does not show
what the service does when the disk runs out. Mounting needs root (CAP_SYS_ADMIN), which the
project's machines and CI have; elsewhere these tests are skipped, saying why.
"""

from __future__ import annotations

import errno
import os
import subprocess
from collections.abc import Iterator
from pathlib import Path

import pytest

SIZE = "2m"


@pytest.fixture
def small_fs(tmp_path: Path) -> Iterator[Path]:
    """A fresh 2 MiB tmpfs, unmounted after the test."""
    mount_point = tmp_path / "small"
    mount_point.mkdir()
    done = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={SIZE},mode=0755", "tmpfs", str(mount_point)],
                          capture_output=True, text=True, check=False)
    if done.returncode != 0:
        pytest.skip(f"cannot mount a {SIZE} tmpfs for a real full disk (needs root / CAP_SYS_ADMIN): "
                    f"{done.stderr.strip() or done.returncode}")
    try:
        yield mount_point
    finally:
        subprocess.run(["umount", "-l", str(mount_point)], check=False)


def fill(directory: Path) -> Path:
    """Fill the filesystem of ``directory`` to the last byte; returns the filler (delete it to free)."""
    filler = directory / "filler.bin"
    fd = os.open(filler, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o644)
    try:
        for size in (65536, 4096, 1):  # big chunks, then whatever is left of the last page
            chunk = b"\0" * size
            while True:
                try:
                    os.write(fd, chunk)
                except OSError as exc:
                    if exc.errno != errno.ENOSPC:
                        raise
                    break
    finally:
        os.close(fd)
    return filler
