"""The verified-cache room (spinorbit.base.verified): what it writes reads back bit for bit; a file damaged in any way,
or of another record, is refused in one line; a failed write leaves nothing; the lock waits no longer than asked;
leftovers of dead writers go, a live writer's stay; a folder others can write is refused.

References: the arrays written (compared byte for byte), the time limit asked, the process table."""
import errno
import fcntl
import os
import subprocess
import sys
import time

import numpy as np
import pytest

from spinorbit.base import verified
from spinorbit.base.errors import InputError

RECORD = {"code": "1.0+abc", "settings": {"step": 2.5}}


@pytest.fixture
def written(tmp_path):
    path = tmp_path / "a.npz"
    arrays = {"x": np.arange(12.0).reshape(3, 4), "label": np.array("moon")}
    verified.write(path, arrays, RECORD, {"wall_s": 1.5})
    return path, arrays


def test_what_is_written_reads_back_bit_for_bit(written):
    path, arrays = written
    entry = verified.read(path, RECORD)
    assert set(entry.arrays) == set(arrays)
    assert entry.arrays["x"].tobytes() == arrays["x"].tobytes() and str(entry.arrays["label"]) == "moon"
    assert entry.record == RECORD and entry.meta == {"wall_s": 1.5}
    assert verified.read(path.with_name("none.npz")) is None


@pytest.mark.parametrize("damage", ["truncated", "bit flipped", "zero bytes", "text", "edited", "added",
                                    "folder", "fifo"])
def test_a_damaged_file_is_refused_in_one_line(written, damage):
    path, arrays = written
    data = bytearray(path.read_bytes())
    if damage in ("edited", "added"):
        with np.load(path) as npz:
            held = {name: npz[name] for name in npz.files}
        if damage == "edited":
            held["x"][0, 0] += 1e-12
        else:
            held["extra"] = np.zeros(2)
        with open(path, "wb") as f:
            np.savez(f, **held)
    elif damage in ("folder", "fifo"):
        path.unlink()
        path.mkdir() if damage == "folder" else os.mkfifo(path)
    else:
        data = {"truncated": data[: len(data) // 2], "zero bytes": b"", "text": b"not an npz\n" * 50}.get(damage)\
            or data[:len(data) // 3] + bytes([data[len(data) // 3] ^ 0x10]) + data[len(data) // 3 + 1:]
        path.write_bytes(bytes(data))
    with pytest.raises(verified.Damaged) as info:
        verified.read(path, RECORD)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("field, offset, value", [("version needed", 6, 0xFF), ("flags: encrypted", 8, 0x01),
                                                  ("compression method", 10, 0xFF)])
def test_a_zip_member_the_room_never_writes_is_refused_in_one_line(written, field, offset, value):
    """A field of the first member's central-directory entry (PKWARE APPNOTE 4.3.12) set to what numpy's savez
    never writes: zipfile raises NotImplementedError or RuntimeError, refused as Damaged like any other."""
    path, _ = written
    data = bytearray(path.read_bytes())
    data[data.index(b"PK\x01\x02") + offset] = value
    path.write_bytes(bytes(data))
    with pytest.raises(verified.Damaged, match="not a file spinorbit wrote") as info:
        verified.read(path, RECORD)
    assert "\n" not in str(info.value), field


def test_a_record_that_is_not_an_object_is_refused(written):
    path, arrays = written
    held = {**arrays, "record": np.array("[1, 2]"), "meta": np.array("{}"), "room_format": np.array(verified.FORMAT)}
    with open(path, "wb") as f:
        np.savez(f, sha256=np.array(verified.arrays_hash(held)), **held)
    with pytest.raises(verified.Damaged, match="not a JSON object"):
        verified.read(path, RECORD)


def test_another_record_is_refused_naming_what_differs(written):
    path, _ = written
    with pytest.raises(verified.Damaged, match="another code"):
        verified.read(path, {**RECORD, "code": "1.0+def"})


def test_a_write_that_fails_leaves_nothing_and_keeps_the_old_file(written, monkeypatch):
    path, arrays = written
    before = path.read_bytes()

    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "fsync", full)
    with pytest.raises(OSError, match="No space"):
        verified.write(path, {"x": np.zeros(5)}, RECORD)
    assert sorted(p.name for p in path.parent.iterdir()) == ["a.npz"] and path.read_bytes() == before


def test_the_lock_waits_no_longer_than_asked(written):
    path, _ = written
    handle = open(verified.lock_path(path), "w")
    fcntl.flock(handle, fcntl.LOCK_EX)
    assert verified.locked_elsewhere(path)
    started = time.monotonic()
    with pytest.raises(verified.Busy):
        with verified.lock(path, wait_s=0.3):
            pass
    assert 0.3 <= time.monotonic() - started < 2.0
    handle.close()
    with verified.lock(path, wait_s=0):
        pass
    assert not verified.locked_elsewhere(path)


def test_leftovers_of_dead_writers_go_a_live_ones_stay(written):
    path, _ = written
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True).stdout.strip()
    stale, live = path.with_name(f".a.npz.tmp-{dead}-x1"), path.with_name(f".a.npz.tmp-{os.getppid()}-x2")
    for leftover in (stale, live):
        leftover.write_bytes(b"part")
    assert verified.remove_leftovers(path) == 1
    assert not stale.exists() and live.exists()


def test_clear_keeps_what_another_process_holds_and_prune_keeps_the_bound(tmp_path, capsys):
    for k in range(3):
        verified.write(tmp_path / f"{k}.npz", {"x": np.zeros(10_000)}, RECORD)
        os.utime(tmp_path / f"{k}.npz", ns=(k * 10**9, k * 10**9))
    size = (tmp_path / "0.npz").stat().st_size
    assert [p.name for p in verified.prune(tmp_path, "*.npz", 2 * size)] == ["0.npz"]
    handle = open(verified.lock_path(tmp_path / "1.npz"), "w")
    fcntl.flock(handle, fcntl.LOCK_EX)
    verified.clear(tmp_path)
    assert sorted(p.name for p in tmp_path.glob("*.npz")) == ["1.npz"]
    assert "kept" in capsys.readouterr().out
    handle.close()


def test_a_folder_others_can_write_is_refused(tmp_path):
    folder = tmp_path / "cache"
    assert verified.private(folder) == folder and oct(folder.stat().st_mode & 0o777) == oct(0o700)
    folder.chmod(0o777)
    with pytest.raises(InputError, match="writable by others") as info:
        verified.private(folder)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("what", ["fifo", "folder", "device"])
def test_a_lock_that_is_not_a_regular_file_is_made_again_in_one_line(written, capfd, what):
    """Found by benchmarks/fuzz_store.py: a FIFO at the lock's place was a traceback (ENXIO)."""
    path, _ = written
    place = verified.lock_path(path)
    {"fifo": os.mkfifo, "folder": os.mkdir, "device": lambda p: os.symlink("/dev/zero", p)}[what](place)
    with verified.lock(path, wait_s=0):
        pass
    assert place.is_file() and not place.is_symlink()
    assert capfd.readouterr().err.count("\n") == 1
    os.unlink(place)
    os.mkfifo(place)
    with pytest.raises(OSError):
        with verified.lock(path, wait_s=0, repair=False):
            pass
