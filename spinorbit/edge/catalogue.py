"""The built-in scenes: the scenario files shipped with the package (``spinorbit/builtin_scenarios``, the
repository's ``scenarios/``), found by name, so that ``spinorbit run moon_libration`` and the Python API work
outside a checkout.  A path to any scenario file works as well.
"""
from importlib.resources import files
from pathlib import Path


def folder():
    """The folder of the built-in scenario files."""
    return Path(str(files("spinorbit") / "builtin_scenarios"))


def names():
    """{name: path} of every built-in scene (stress scenes as ``stress/<name>``), sorted."""
    root = folder()
    found = {p.stem: p for p in root.glob("*.toml")}
    found.update({f"stress/{p.stem}": p for p in (root / "stress").glob("*.toml")})
    return dict(sorted(found.items()))


def resolve(scene):
    """The scenario file of ``scene``: an existing path as given, else a built-in scene's name (with or without
    ``.toml`` or a leading ``scenarios/``); the path unchanged when neither (the loader then says what is wanted)."""
    path = Path(scene)
    if path.is_file():
        return path
    name = path.as_posix().removeprefix("scenarios/").removesuffix(".toml")
    return names().get(name, path)

