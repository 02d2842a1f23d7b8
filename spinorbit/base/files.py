"""Files spinorbit reads (and locks), opened only when they are regular files: a FIFO, a device or a socket (or
a link to one) is refused without blocking, before anything is read from it; files it writes, written aside and
renamed."""
import os
import stat
import tempfile


class NotRegular(OSError):
    """A path that names something other than a regular file."""


def open_regular(path, mode="rb", follow_links=True):
    """``path`` opened for reading (binary ``rb`` or text ``r``) if it is a regular file, links followed unless
    ``follow_links`` is false (then a link is refused: ELOOP); NotRegular otherwise (an OSError, as a missing
    file is)."""
    nofollow = 0 if follow_links else os.O_NOFOLLOW
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC | nofollow)   # a FIFO opens without a writer
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise NotRegular(0, f"not a regular file ({kind(info.st_mode)})", str(path))
        os.set_blocking(fd, True)
    except BaseException:
        os.close(fd)
        raise
    return os.fdopen(fd, mode)


def write_atomically(path, fill, prefix=".tmp-"):
    """Write ``path`` whole or not at all: ``fill(f)`` writes into a new file (named ``prefix``...) in the same
    folder, which is synced and renamed over ``path``; on an error nothing is left of it and the error is raised."""
    handle, tmp = tempfile.mkstemp(prefix=prefix, dir=os.path.dirname(os.fspath(path)) or ".")
    try:
        with os.fdopen(handle, "wb") as f:
            fill(f)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    finally:
        if os.path.lexists(tmp):
            os.unlink(tmp)


def open_lock(path):
    """A lock file at ``path`` opened for writing (created 0600 if missing), if it is a regular file: a FIFO
    there never blocks (NotRegular)."""
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_NONBLOCK | os.O_CLOEXEC, 0o600)
    info = os.fstat(fd)
    if not stat.S_ISREG(info.st_mode):
        os.close(fd)
        raise NotRegular(0, f"not a regular file ({kind(info.st_mode)})", str(path))
    return os.fdopen(fd, "w")


def kind(mode):
    """What a stat mode names, in words."""
    for test, name in ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO"), (stat.S_ISSOCK, "a socket"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device")):
        if test(mode):
            return name
    return "not a file"


def process_alive(pid):
    """Whether a process of this id exists (another user's counts)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
