"""The package's layering (docs/DEVELOPING.md): imports point downward only, only edge modules import astropy,
no import cycle between rooms; scene modules are thin; only the models write a compiled right-hand side."""
import ast
import re
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).parents[1] / "spinorbit"
LAYERS = {
    "base": 0,
    "bodies": 1, "orbits": 1,                       # bodies/de421_orientation.py: DE421's libration series
    "models": 2, "integrators": 2, "analysis": 2,   # integrators/simulation.py: the one door
}
EDGE = 9          # scenarios, scenes, starts, comparisons, references, runner, reports, cli, bench, ...
EDGE_ONLY_LIBRARIES = {"astropy", "matplotlib", "dask", "distributed", "erfa", "skyfield"}


def layer_of(module_path):
    top = module_path.relative_to(PACKAGE).parts[0].removesuffix(".py")
    return LAYERS.get(top, EDGE), top


def imports(path):
    """(absolute library names, spinorbit top-level modules) imported anywhere in a file."""
    tree = ast.parse(path.read_text())
    libraries, internal = set(), set()
    depth = len(path.relative_to(PACKAGE).parts) - 1
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                name = alias.name.split(".")
                (internal.add(name[1]) if name[0] == "spinorbit" and len(name) > 1 else libraries.add(name[0]))
        elif isinstance(node, ast.ImportFrom):
            if node.level == 0:
                name = node.module.split(".")
                if name[0] == "spinorbit":
                    internal.update([name[1]] if len(name) > 1 else [a.name for a in node.names])
                else:
                    libraries.add(name[0])
            elif node.level > depth:          # from ..x import y, reaching the package root
                internal.update([node.module.split(".")[0]] if node.module else [a.name for a in node.names])
    return libraries, internal


MODULES = sorted(p for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_imports_point_downward(path):
    layer, top = layer_of(path)
    libraries, internal = imports(path)
    for name in internal - {top}:
        assert LAYERS.get(name, EDGE) <= layer, f"{top} (layer {layer}) imports {name} (layer {LAYERS.get(name, EDGE)})"
    if layer < EDGE:
        assert not libraries & EDGE_ONLY_LIBRARIES, f"core module {top} imports {libraries & EDGE_ONLY_LIBRARIES}"


def test_torque_free_scene_imports_no_ephemeris_or_nbody_library(tmp_path):
    code = (
        "import sys, spinorbit;"
        f"spinorbit.run_scenario('{PACKAGE.parent / 'scenarios' / 'free_body.toml'}', ['span.end=20 d']);"
        "print(' '.join(sorted(m.split('.')[0] for m in sys.modules)))"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    loaded = set(proc.stdout.split())
    assert not loaded & {"skyfield", "jplephem", "rebound", "reboundx", "dask", "distributed", "matplotlib"}


def room_imports():
    """{(room, imported room): ["file:line", ...]} over every import in the package, inside functions too.

    A room is a subpackage (``scenes``, ``integrators`` ...) or a top-level module (``scenarios``, ``bench``).
    """
    rooms = {p.relative_to(PACKAGE).parts[0].removesuffix(".py") for p in MODULES}
    edges = {}
    for path in MODULES:
        room = path.relative_to(PACKAGE).parts[0].removesuffix(".py")
        depth = len(path.relative_to(PACKAGE).parts) - 1
        for node in ast.walk(ast.parse(path.read_text())):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name.split(".")[1] for a in node.names if a.name.startswith("spinorbit.")]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and (node.module or "").startswith("spinorbit"):
                parts = node.module.split(".")
                names = parts[1:2] or [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level > depth:      # relative, reaching the package root
                names = [node.module.split(".")[0]] if node.module else [a.name for a in node.names]
            for name in names:
                if name in rooms and name != room:
                    edges.setdefault((room, name), []).append(f"{path.relative_to(PACKAGE)}:{node.lineno}")
    return edges


def find_cycle(edges):
    """One cycle [a, b, ..., a] of the directed graph, or None."""
    graph = {}
    for a, b in edges:
        graph.setdefault(a, []).append(b)
    state = {}

    def visit(node, path):
        state[node] = "open"
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == "open":
                return path[path.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt, path + [nxt])
                if found:
                    return found
        state[node] = "done"
        return None

    for start in sorted(graph):
        if start not in state:
            found = visit(start, [start])
            if found:
                return found
    return None


def test_no_import_cycle_between_rooms():
    """No cycle between rooms (imports inside functions count): each room can be read and changed from below."""
    edges = room_imports()
    assert ("scenes", "scene") in edges          # the graph sees the package's imports
    cycle = find_cycle(edges)
    assert cycle is None, "import cycle between rooms: " + " -> ".join(cycle) + "\n" + "\n".join(
        f"  {a} -> {b}: {', '.join(edges[a, b])}" for a, b in zip(cycle, cycle[1:]))


# --- compiled right-hand sides -------------------------------------------------------------------------

COMPILERS = {"njit", "jit", "cfunc", "template", "generated_jit", "cached"}   # numba's, the linker's
RHS_SIGNATURE = ["t", "y", "p"]
GENERATED_RHS = re.compile(r"def \w+\(\s*t\s*,\s*y\s*,\s*p\s*\)")
RHS_HOMES = ("models", "integrators")          # the models write every rhs, the integrators their steps


def _called_name(node):
    target = node.func if isinstance(node, ast.Call) else node
    return target.attr if isinstance(target, ast.Attribute) else getattr(target, "id", None)


def compiled_rhs(source):
    """Names of the compiled right-hand sides a module defines: a function of the signature (t, y, p) that
    numba compiles or the linker links (decorated with njit/jit/cfunc/template/cached, or passed to one of
    them), or source text defining one for the linker to compile (``link_source``)."""
    tree = ast.parse(source)
    functions = {node.name: node for node in ast.walk(tree) if isinstance(node, ast.FunctionDef)}
    shaped = {name for name, node in functions.items()
              if [a.arg for a in node.args.posonlyargs + node.args.args] == RHS_SIGNATURE}
    found = {name for name in shaped
             if any(_called_name(d) in COMPILERS for d in functions[name].decorator_list)}
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and _called_name(node) in COMPILERS:
            found |= {a.id for a in node.args if isinstance(a, ast.Name) and a.id in shaped}
        elif isinstance(node, ast.Constant) and isinstance(node.value, str):
            found |= {f"generated source: {m.group(0)}" for m in GENERATED_RHS.finditer(node.value)}
    return sorted(found)


def test_the_detector_finds_compiled_right_hand_sides():
    """Not vacuous: it finds the models' own (the planar problem's, DE421's core carried under the mantle) and
    each way of writing one, and passes a kernel of another signature and a plain Python (t, y, p)."""
    assert compiled_rhs((PACKAGE / "models" / "planar.py").read_text()) == ["planar_rhs"]
    assert "core_rhs" in compiled_rhs((PACKAGE / "models" / "start.py").read_text())
    written = ("from numba import njit, jit\nimport numba\n"
               "@njit(cache=True)\ndef a(t, y, p): pass\n@numba.njit\ndef b(t, y, p): pass\n"
               "def c(t, y, p): pass\nc_fast = jit(c)\n@template('torque')\ndef d(t, y, p): pass\n"
               "SOURCE = 'def e(t, y, p):\\n    return y'\n"
               "@njit\ndef kernel(rot, inertia, rows, gm): pass\ndef python_rhs(t, y, p): pass\n")
    assert compiled_rhs(written) == ["a", "b", "c", "d", "generated source: def e(t, y, p)"]


@pytest.mark.parametrize("path", [p for p in MODULES if p.relative_to(PACKAGE).parts[0] not in RHS_HOMES],
                         ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_compiled_rhs_outside_the_models(path):
    """Issue 22: every right-hand side is a System's, generated in spinorbit.models (the integrators' own
    steps aside); nothing else hand-writes one."""
    assert compiled_rhs(path.read_text()) == []
