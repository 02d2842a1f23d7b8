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


def key_table(scene):
    """Markdown-like lines: every key of ``scene``'s kind (its file's value, the default, unit, range, meaning),
    the [integrator] options, and the kind's docstring's first line; what ``spinorbit show`` prints."""
    import math
    import tomllib

    from .integrators import METHODS, get_method
    from .scenarios import COMMON_SCHEMA
    from .scenes import scene_module
    from .schema import INTEGRATOR_OPTIONS, REQUIRED, dotted_items

    path = resolve(scene)
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    kind = data.get("scene", {}).get("kind")
    module = scene_module(kind)
    given = dict(dotted_items(data))
    method = given.get("integrator.method", COMMON_SCHEMA["integrator.method"].default)
    options = get_method(method).options if method in METHODS else {}
    lines = [f"{path.stem} (kind {kind}): {(module.__doc__ or '').strip().splitlines()[0]}", "",
             f"{'key':34} {'value in the file':24} {'default':22} {'unit':8} {'range':18} meaning"]
    for key, spec in {**COMMON_SCHEMA, **module.SCHEMA, **{f"integrator.{name}": spec for name, spec in
                                                           INTEGRATOR_OPTIONS.items() if name in options}}.items():
        name = key.removeprefix("integrator.")
        default = repr(options[name]) if key.startswith("integrator.") and name in options else \
            "(required)" if spec.default is REQUIRED else repr(spec.default)
        if spec.choices:
            span = "|".join(map(str, spec.choices))
        elif math.isfinite(spec.min) or math.isfinite(spec.max) or spec.positive:
            span = f"{'>0' if spec.positive else f'{spec.min:g}'} .. {spec.max:g}"
        else:
            span = ""
        value = repr(given[key]) if key in given else ""
        lines.append(f"{key:34} {value[:24]:24} {default[:22]:22} {spec.unit or '':8} {span[:18]:18} {spec.help}")
    return lines
