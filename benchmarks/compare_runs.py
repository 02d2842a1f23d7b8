"""Every number of two sets of run directories' summaries side by side: what changed, and by how much.

    python benchmarks/compare_runs.py BEFORE_DIR AFTER_DIR [name ...]

Each DIR holds run directories (``spinorbit run X.toml --out DIR/<name>``); for every name found in
both, each number in summary.json (comparison, fitted terms, run point; wall times and provenance
excepted) is compared and those differing by more than 1e-9 relative (and 1e-12 absolute) are listed,
largest first.  Used to check that a refactoring leaves every scene's figures unchanged to rounding.
"""
import json
import math
import sys
from pathlib import Path

SKIPPED = ("wall", "provenance", "created", "version", "path", "elapsed", "python", "host", "command", "compile")


def numbers(tree, prefix=""):
    """(dotted key, leaf) pairs of a JSON tree."""
    if isinstance(tree, dict):
        for key, value in tree.items():
            yield from numbers(value, f"{prefix}.{key}" if prefix else key)
    elif isinstance(tree, list):
        for i, value in enumerate(tree):
            yield from numbers(value, f"{prefix}[{i}]")
    else:
        yield prefix, tree


def differences(before, after, rel=1e-9, abs_=1e-12):
    """[(relative change or inf, key, before, after)] of two summaries, largest first."""
    a, b = dict(numbers(before)), dict(numbers(after))
    out = []
    for key in sorted(set(a) | set(b)):
        if any(word in key for word in SKIPPED):
            continue
        x, y = a.get(key, "<absent>"), b.get(key, "<absent>")
        if isinstance(x, (int, float)) and isinstance(y, (int, float)) and not isinstance(x, bool):
            change = abs(x - y) / max(abs(x), abs(y), 1e-300)
            if abs(x - y) > abs_ and change > rel:
                out.append((change, key, x, y))
        elif x != y:
            out.append((math.inf, key, x, y))
    return sorted(out, key=lambda d: -d[0])


def main(before, after, names):
    names = names or sorted(p.name for p in Path(after).iterdir() if (p / "summary.json").exists())
    for name in names:
        paths = [Path(d) / name / "summary.json" for d in (before, after)]
        if not all(p.exists() for p in paths):
            print(f"== {name}: missing {[str(p) for p in paths if not p.exists()]}")
            continue
        diffs = differences(*(json.loads(p.read_text()) for p in paths))
        print(f"== {name}: {len(diffs)} differing")
        for change, key, x, y in diffs[:25]:
            print(f"   {key}: {x} -> {y}  (relative {change:.1e})")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3:])
