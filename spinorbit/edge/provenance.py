"""Where a run's numbers come from: spinorbit version and commit, scene file, settings, libraries.

``provenance(scenario)`` is written to summary.json and to the ECSV table's meta.
It holds no wall-clock time, so two runs of one scene on one checkout give the
same ECSV byte for byte.
"""
import hashlib
import platform
import subprocess
from functools import cache
from importlib import metadata
from pathlib import Path

DEPENDENCIES = ("numpy", "scipy", "numba", "astropy", "pyerfa", "jplephem", "skyfield", "de421",
                "rebound", "reboundx", "matplotlib")

def provenance(scenario):
    """JSON-ready dict: versions, git commit (or None), scene file sha256, resolved settings, platform."""
    return {
        "spinorbit_version": _version("spinorbit"),
        "git_commit": git_commit(),
        "scene_file": None if scenario.path is None else scenario.path.name,
        "scene_file_sha256": _sha256(scenario.path),
        "settings": _jsonable(scenario.data),
        "dependencies": {name: v for name in DEPENDENCIES if (v := _version(name)) is not None},
        "ephemeris": ephemeris(scenario),
        "platform": {"python": platform.python_version(), "system": platform.platform(),
                     "machine": platform.machine()},
    }


def ephemeris(scenario):
    """{"name", "span"} of the ephemeris the scene reads (its orbit source says), or None for analytic orbits."""
    from ..orbits.sources import OrbitSource
    from ..scene.params import values_of

    values = values_of(scenario.params)
    source = values.get("orbit.source")
    start = values.get("orbit.ephemeris")                  # deep time: the state its N-body run starts from
    if isinstance(source, OrbitSource):
        return source.provenance()
    if isinstance(start, OrbitSource):
        return {"name": f"{start.name} (the solar system's state at J2000 its N-body run starts from)",
                "span": start.provenance()["span"]}
    return None


@cache
def git_commit():
    """HEAD of the git checkout whose root holds this package, or None (installed copy, no git)."""
    root = Path(__file__).resolve().parents[2]
    try:
        out = subprocess.run(["git", "rev-parse", "--show-toplevel", "HEAD"], cwd=root, capture_output=True,
                             text=True, timeout=5)
    except (OSError, subprocess.SubprocessError):
        return None
    lines = out.stdout.split()
    if out.returncode != 0 or len(lines) != 2 or Path(lines[0]).resolve() != root:
        return None
    return lines[1]


def _version(name):
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return None


def _sha256(path):
    return None if path is None or not Path(path).is_file() else hashlib.sha256(Path(path).read_bytes()).hexdigest()


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    return str(value)              # TOML dates and times
