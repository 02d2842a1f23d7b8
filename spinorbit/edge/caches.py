"""Every cache spinorbit keeps, by name: where it is, what it holds and how much, and emptying it
(``spinorbit cache``, ``spinorbit cache clear``).

All live in spinorbit's private cache directory (spinorbit.base.linker.cache: ``$SPINORBIT_CACHE_DIR``, else
``~/.cache/spinorbit``): the compiled kernels, heyoka's compiled integrators, the deep-time orbital solutions
(spinorbit.orbits.solution), the stored continuous solutions (spinorbit.solutions.store) and the tidal
history's ocean tables.  To add a cache:
an entry in :data:`CACHES` (a name, its folder, and how to clear it).
"""
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Callable


@dataclass(frozen=True)
class Cache:
    """A named cache: ``folder()`` gives its directory (None when it does not exist), ``clear(folder)`` empties
    it and returns the number of files removed."""

    name: str
    folder: Callable[[], Path]
    clear: Callable[[Path], int]

    def usage(self):
        """(files, bytes) under the folder, links not followed; (0, 0) when there is no folder."""
        folder = self.folder()
        sizes = [] if folder is None else [os.lstat(Path(path) / name).st_size
                                           for path, _, names in os.walk(folder) for name in names]
        return len(sizes), sum(sizes)


def _kernels():
    from ..base.linker import cache

    return cache.kernels_dir()


def _clear_kernels(folder):
    from ..base.linker import cache

    return cache.clear()


def _heyoka():
    """heyoka's on-disk cache of compiled Taylor integrators (spinorbit.integrators.taylor)."""
    from ..base.linker import cache

    folder = cache.kernels_dir().parent / "heyoka"
    return folder if folder.is_dir() and not folder.is_symlink() else None


def _clear_files(folder):
    """Delete every file under ``folder`` (the folder is spinorbit's alone), keeping the folders."""
    removed = 0
    for path, _, names in os.walk(folder):
        for name in names:
            os.unlink(Path(path) / name)
            removed += 1
    return removed


def _solutions():
    from ..orbits import solution

    return solution.cache_directory()


def _clear_solutions(folder):
    """Delete the orbital solutions no process is working on (their lock free) and the leftovers of killed
    saves; a solution another run is extending is kept and said (spinorbit.base.verified.clear)."""
    from ..base import verified

    return verified.clear(folder, "*.npz")


def _stored():
    from ..solutions import store

    return store.directory()


def _clear_stored(folder):
    from ..solutions import store

    return store.clear()


def _tables():
    """The tidal history's tables (the ocean basins' responses: starts.earth_moon_history.keep_table)."""
    from ..base.linker import cache

    folder = cache.kernels_dir().parent / "tables"
    return folder if folder.is_dir() and not folder.is_symlink() else None


CACHES = (Cache("compiled kernels", _kernels, _clear_kernels),
          Cache("heyoka's compiled integrators", _heyoka, _clear_files),
          Cache("orbital solutions", _solutions, _clear_solutions),
          Cache("stored solutions", _stored, _clear_stored),
          Cache("tidal-history tables", _tables, _clear_solutions))


def listing():
    """One line per cache: its name, folder, files and size."""
    lines = []
    for entry in CACHES:
        folder = entry.folder()
        files, size = entry.usage()
        where = f"{folder}/" if folder is not None else "(none yet)"
        lines.append(f"{entry.name:32s} {files:6d} files {size / 1e6:9.3g} MB  {where}")
    return lines


def clear():
    """Empty every cache; one line per cache saying how many files it removed."""
    lines = []
    for entry in CACHES:
        folder = entry.folder()
        removed = 0 if folder is None else entry.clear(folder)
        lines.append(f"{entry.name}: removed {removed} files" + (f" from {folder}/" if folder else ""))
    return lines
