"""The verdict of a run: does the comparison a scene exists for meet its tolerance?

A scene declares its ``verdict`` (spinorbit.scene.declaration.Scene): a ``Verdict``, or a function ``verdict(p,
comparison) -> Verdict`` when the question depends on the scene's parameters ``p`` (or, for P96, on whether
the run met the resonance), naming the reference, and ``Check``s on keys of
``summary["comparison"]`` with a tolerance in the metric's unit and its source.  ``evaluate`` turns it into
``summary["verdict"]``:

    {"result": "pass" | "fail" | "not-compared", "reference": ..., "checks": [...], "headline": ...}

A check passes when ``|figure| <= tolerance``; the figure is the metric itself, its
difference from ``expected``, or (``versus``) its difference from, or ratio - 1 to,
another metric.  A boolean metric passes when true.  A metric that is missing or
null, or a span shorter than ``min_span_d``, makes the check "not-compared" with the
reason; the verdict is "fail" if any check fails, else "pass" if at least one
check passes (the headline names those not compared), else "not-compared".
``status`` (the run finished) is a different thing.
"""
import math
from dataclasses import dataclass

PASS, FAIL, NOT_COMPARED = "pass", "fail", "not-compared"


@dataclass(frozen=True)
class Check:
    """One figure against its tolerance.  ``unit`` is printed after figure and tolerance."""

    label: str
    metric: str
    tolerance: float = 0.0
    unit: str = ""
    source: str = ""
    expected: float | None = None
    versus: str | None = None
    relative: bool = False
    min_span_d: float = 0.0


@dataclass(frozen=True)
class Verdict:
    """The comparison a scene exists for: ``reference`` (e.g. "DE421"), its checks, a note."""

    reference: str
    checks: tuple
    note: str = ""


def evaluate(spec, comparison, span_d, name="", span_label="", not_measured=None):
    """``summary["verdict"]`` of a run from its spec, comparison dict and span (days); ``not_measured``: the
    summary's reasons for the metrics it could not measure ("comparison.<metric>": why)."""
    checks = [] if spec is None else [_check(c, comparison or {}, span_d, not_measured or {}) for c in spec.checks]
    results = {c["result"] for c in checks}
    result = FAIL if FAIL in results else PASS if PASS in results else NOT_COMPARED
    verdict = {"result": result, "reference": None if spec is None else spec.reference, "checks": checks}
    if spec is not None and spec.note:
        verdict["note"] = spec.note
    verdict["headline"] = headline(name, verdict, span_label)
    return verdict


def _check(check, comparison, span_d, not_measured):
    out = {"label": check.label, "metric": check.metric, "tolerance": check.tolerance, "unit": check.unit,
           "source": check.source}
    if check.expected is not None:
        out["expected"] = check.expected
    if check.versus is not None:
        out["versus"] = check.versus
    if span_d < check.min_span_d:
        return {**out, "figure": None, "result": NOT_COMPARED,
                "reason": f"span {span_d / 365.25:.3g} yr < {check.min_span_d / 365.25:.3g} yr needed"}
    value = comparison.get(check.metric)
    if isinstance(value, bool):
        return {**out, "figure": value, "result": PASS if value else FAIL}
    figure = _figure(check, value, comparison.get(check.versus) if check.versus else None)
    if figure is None:
        missing = check.metric if not _finite(value) else check.versus
        reason = not_measured.get(f"comparison.{missing}", f"{missing} missing or not finite")
        return {**out, "figure": None, "result": NOT_COMPARED, "reason": reason}
    return {**out, "figure": figure, "result": PASS if abs(figure) <= check.tolerance else FAIL}


def _figure(check, value, other):
    if not _finite(value):
        return None
    value = float(value)
    if check.versus is not None:
        if not _finite(other) or (check.relative and other == 0):
            return None
        return value / float(other) - 1 if check.relative else value - float(other)
    return value - check.expected if check.expected is not None else value


def _finite(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def headline(name, verdict, span_label=""):
    """One line: ``moon_libration: pass — pole 0.0036″ ≤ 0.1″, longitude 0.0005″ ≤ 0.01″ vs DE421 (1900–2050)``."""
    if not verdict["checks"]:
        return f"{name}: {verdict['result']} — this scene declares no comparison"
    parts = [_describe(c) for c in verdict["checks"]]
    where = f" vs {verdict['reference']}" if verdict["reference"] else ""
    span = f" ({span_label})" if span_label else ""
    return f"{name}: {verdict['result']} — {', '.join(parts)}{where}{span}"


def _describe(check):
    label, unit, figure = check["label"], check["unit"], check["figure"]
    if check["result"] == NOT_COMPARED:
        return f"{label} not compared ({check['reason']})"
    if isinstance(figure, bool):
        return f"{label} {'met' if figure else 'not met'}"
    ok = check["result"] == PASS
    tol = f"{_num(check['tolerance'])}{unit}"
    if "expected" in check:
        return (f"{label} {_num(check['expected'] + figure)}{unit} = {_num(check['expected'])}{unit} "
                f"{'within' if ok else 'outside'} ±{tol}")
    if "versus" in check:
        figure = abs(figure)
    if figure < 0:
        return f"{label} {_num(figure)}{unit} {'within' if ok else 'outside'} ±{tol}"
    return f"{label} {_num(figure)}{unit} {'≤' if ok else '>'} {tol}"


def _num(x):
    return f"{x:.2g}" if abs(x) < 1 else f"{x:.4g}"
