"""``spinorbit show``: every key a scene reads, its value in the file, default, unit, range and meaning."""
import math

from ..integrators import METHODS, get_method
from ..scene.schema import INTEGRATOR_OPTIONS, REQUIRED, dotted_items
from .scenarios import load_scenario


def key_table(scene):
    """(heading, rows): the kind's docstring's first paragraph, and every key of ``scene``'s kind as a row of
    texts, nothing cut (key, its file's value, the default, unit, range, meaning), the [integrator] options
    among them; what ``spinorbit show`` prints."""
    from ..scenes import scene_module

    scenario = load_scenario(scene)
    path, kind = scenario.path, scenario.params.scene.kind
    module = scene_module(kind)
    given = dict(dotted_items(scenario.data))
    method = scenario.params.integrator.method
    options = get_method(method).defaults() if method in METHODS else {}
    summary = " ".join((module.__doc__ or "").strip().split("\n\n")[0].split())
    rows = [("key", "value in the file", "default", "unit", "range", "meaning")]
    options_keys = {f"integrator.{name}": spec for name, spec in INTEGRATOR_OPTIONS.items() if name in options}
    for key, spec in {**scenario.schema, **options_keys}.items():
        name = key.removeprefix("integrator.")
        default = repr(options[name]) if key.startswith("integrator.") and name in options else \
            "(required)" if spec.default is REQUIRED else repr(spec.default)
        if spec.choices:
            span = " | ".join(map(str, spec.choices))
        elif math.isfinite(spec.min) or math.isfinite(spec.max) or spec.positive:
            span = f"{'>0' if spec.positive else f'{spec.min:g}'} .. {spec.max:g}"
        else:
            span = ""
        rows.append((key, repr(given[key]) if key in given else "", default, spec.unit or "", span, spec.help))
    return f"{path.stem} (kind {kind}): {summary}", rows
