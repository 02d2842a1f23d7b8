"""The package's layering: imports point downward only, and only edge modules import astropy."""
import ast
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).parents[1] / "spinorbit"
LAYERS = {
    "constants": 0, "errors": 0, "rotations": 0, "linker": 0, "progress": 0,
    "bodies": 1, "orbits": 1,
    "dynamics": 2, "integrators": 2, "theory": 2, "moon": 2, "earth": 2, "nonrigid": 2, "terms": 2,
    "simulate": 3, "analysis": 2,
}
EDGE = 9          # scenarios, scenes, references, results, reports, cli, bench, sweep, __init__
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
