"""One writer per result store: the lock a sweep holds while it writes rows.

Two ``voot-bench plan`` (or ``bbfo``, ``ablation``, ``compact``) processes pointed at one
``--out`` would each compute the same pending runs and run them all twice; worse, the
store's "never replace a finished row" check and its write are two steps, so two
writers could interleave them and replace a finished row with the other's failed one.
Rather than make every row write safe against a second writer (a ``link``-based
no-clobber write, which not every file system has) and still waste the doubled work, a
sweep takes the store's *writer lock* first and a second writer is refused at once, with
the holder named::

    StoreBusyError: results/plan: another voot-bench process is writing this store
    (pid 4121 on host build-7, since 2026-12-03T09:20:11+00:00: voot-bench plan ...)

How (:class:`WriterLock`):

* The lock is ``fcntl.flock(LOCK_EX | LOCK_NB)`` on the file :data:`LOCK_NAME` in the
  store directory, which holds the holder's pid, host, start time and command line (JSON)
  for the refusal message. ``flock`` (not an ``O_EXCL`` file alone) because the kernel
  drops the lock when its holder dies, however it dies (SIGKILL, OOM killer, power cut on
  a local disk), so a crashed sweep never leaves a lock that needs a hand to remove: its
  leftover file is *stale* (unlocked) and the next writer takes it over, saying whose it
  was. A pid check on an ``O_EXCL`` file cannot tell a reused pid or a holder on another
  host from the real one.
* The holder deletes the file when it releases the lock. A process that opened the old
  file just before would lock a deleted inode, so after locking, a writer checks that
  the path still names the file it locked and otherwise tries again.
* The descriptor is close-on-exec: a spawned worker does not inherit (and so cannot
  keep) the lock.
* Readers (``report``, ``claims``, ``plot``) take no lock: every row file appears
  atomically (:func:`voot.bench.store.index.write_atomic`).

POSIX only (``fcntl``); on a network file system the lock is as good as its ``flock``
(Linux NFS maps it onto POSIX byte-range locks, served by the server's lock manager).
"""

from __future__ import annotations

import datetime as _dt
import errno
import fcntl
import json
import os
import socket
import sys
from pathlib import Path
from typing import Any

from voot.bench.store.format import StoreError

#: The lock file of a store's writer (in the store directory, next to the header).
LOCK_NAME = ".voot-writer.lock"
#: Attempts to lock a file that its holder deleted meanwhile (see :meth:`WriterLock.acquire`).
_ATTEMPTS = 20


class StoreBusyError(StoreError):
    """Another process holds the store's writer lock; ``holder`` is what it recorded."""

    def __init__(self, message: str, holder: dict[str, Any]) -> None:
        super().__init__(message)
        self.holder = holder


def holder_info() -> dict[str, Any]:
    """What a writer records in the lock file: pid, host, start time, command line."""
    return {
        "pid": os.getpid(),
        "host": socket.gethostname(),
        "started": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "command": " ".join([Path(sys.argv[0]).name if sys.argv else "python", *sys.argv[1:]]),
    }


def describe_holder(holder: dict[str, Any]) -> str:
    """``"pid 4121 on host h, since <time>: <command>"`` (or what is known of it)."""
    if not holder:
        return "a process that has not recorded itself yet"
    return (
        f"pid {holder.get('pid', '?')} on host {holder.get('host', '?')},"
        f" since {holder.get('started', '?')}: {holder.get('command', '?')}"
    )


def _read_holder(fd: int) -> dict[str, Any]:
    """The holder recorded in the open lock file ``fd`` ({} if empty or unreadable)."""
    try:
        data = os.pread(fd, 64 * 1024, 0)
        holder = json.loads(data) if data.strip() else {}
    except (OSError, ValueError):
        return {}
    return holder if isinstance(holder, dict) else {}


class WriterLock:
    """The writer lock of the store in ``store_path`` (see the module docstring).

    Use as a context manager, or :meth:`acquire` / :meth:`release`. ``stale`` is the
    holder recorded in a lock file left by a writer that died without releasing it
    (None if there was none), set by :meth:`acquire`.
    """

    def __init__(self, store_path: str | os.PathLike[str]) -> None:
        self.path = Path(store_path) / LOCK_NAME
        self.stale: dict[str, Any] | None = None
        self._fd: int | None = None

    @property
    def held(self) -> bool:
        """Whether this object holds the lock."""
        return self._fd is not None

    def acquire(self) -> WriterLock:
        """Take the lock or raise :class:`StoreBusyError` naming its holder.

        Never blocks: a second writer is refused rather than queued (it would otherwise
        wait, then find nothing left to run).
        """
        if self._fd is not None:
            raise RuntimeError(f"{self.path}: this lock is already held by this object")
        for _ in range(_ATTEMPTS):
            try:
                fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666)
            except OSError as exc:  # a folder, or an unwritable store: no lock file to hold
                what = "a folder" if self.path.is_dir() else exc.strerror or type(exc).__name__
                raise StoreError(
                    f"{self.path}: the store's writer lock cannot be opened ({what}); it must"
                    f" be a file voot-bench may write (remove or rename what is there if no"
                    f" voot-bench process is writing {self.path.parent})"
                ) from None
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError as exc:
                holder = _read_holder(fd)
                os.close(fd)
                if exc.errno not in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                    raise
                raise StoreBusyError(
                    f"{self.path.parent}: another voot-bench process is writing this store"
                    f" ({describe_holder(holder)}); wait for it to finish, or give another"
                    " --out",
                    holder,
                ) from None
            try:
                same = os.stat(self.path).st_ino == os.fstat(fd).st_ino
            except FileNotFoundError:
                same = False
            if not same:  # its holder released (deleted) it between our open and lock
                os.close(fd)
                continue
            previous = _read_holder(fd)
            self.stale = previous or None
            data = json.dumps(holder_info()).encode()
            os.ftruncate(fd, 0)
            os.pwrite(fd, data, 0)
            os.fsync(fd)
            self._fd = fd
            return self
        raise StoreError(  # pragma: no cover - needs _ATTEMPTS releases in a row
            f"{self.path}: could not take the writer lock (its file kept being replaced)"
        )

    def release(self) -> None:
        """Delete the lock file and drop the lock (nothing if not held)."""
        fd, self._fd = self._fd, None
        if fd is None:
            return
        try:
            os.unlink(self.path)
        except FileNotFoundError:  # pragma: no cover - removed by hand
            pass
        finally:
            os.close(fd)  # closing the last descriptor drops the flock

    def __enter__(self) -> WriterLock:
        return self.acquire()

    def __exit__(self, *exc_info: object) -> None:
        self.release()

    def __repr__(self) -> str:
        return f"WriterLock({str(self.path.parent)!r}, held={self.held})"
