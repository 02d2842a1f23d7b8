"""A method named on the command line over a scene file written for another method.

``--set integrator.method=taylor`` on a file that sets ``rtol`` would otherwise be refused: the file's option is
not a Taylor option.  The file's options the new method does not take are translated where one means the other
(a relative tolerance: ``rtol`` of the adaptive methods, ``tolerance`` of Taylor's) and the value lies in the
new option's range, else dropped for the method's default; each change is said in one line.  Options set on the
command line are never touched: they are checked as typed.
"""
from ..base.errors import ScenarioError
from ..scene.schema import INTEGRATOR_OPTIONS, checked_float

SAME_MEANING = {"rtol": "tolerance", "tolerance": "rtol"}
ALWAYS = ("method", "estimate_error")


def option_names(overrides):
    """The [integrator] names the ``key=value`` overrides set, e.g. {'method', 'rtol'}."""
    keys = (text.split("=", 1)[0].strip() for text in overrides)
    return {key.removeprefix("integrator.") for key in keys if key.startswith("integrator.")}


def switch_method(table, file_table, typed):
    """Fit ``table`` (the [integrator] table after the overrides) to its method when ``typed`` (the names set on
    the command line) switched it from ``file_table``'s; returns the notes saying what changed."""
    from ..integrators import METHODS, get_method

    method = table.get("method")
    if "method" not in typed or method == file_table.get("method") or method not in METHODS:
        return []
    takes = set(get_method(method).options) | set(ALWAYS)
    notes = []
    for name in [name for name in table if name not in takes and name not in typed]:
        value = table.pop(name)
        target = SAME_MEANING.get(name)
        if target in takes and target not in table and _in_range(target, value):
            table[target] = value
            notes.append(f"integrator.{name} = {value!r} from the scene file taken as integrator.{target} for "
                         f"method {method!r}")
        else:
            notes.append(f"integrator.{name} = {value!r} from the scene file dropped: method {method!r} does "
                         "not take it (its default applies)")
    return notes


def _in_range(name, value):
    try:
        checked_float(f"integrator.{name}", value, INTEGRATOR_OPTIONS[name])
    except ScenarioError:
        return False
    return True
