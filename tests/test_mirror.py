"""tests/ mirrors spinorbit/ (docs/DEVELOPING.md, Tests): the tests of ``spinorbit/<path>/<module>.py`` are in
``tests/<path>/test_<module>.py``, or in the file of a package around it, ``tests/<path>/test_<package>.py``; every
test file is named for a module or a package at its place, never for a behaviour."""
from pathlib import Path

ROOT = Path(__file__).parents[1]
PACKAGE = ROOT / "spinorbit"
TESTS = ROOT / "tests"

# Modules (or whole packages) with no test file of their own, each with where it is tested and why.
UNMIRRORED = {
    "__main__.py": "two lines handing `python -m spinorbit` to cli.console (tests/edge/test_api.py runs it)",
    "base/version.py": "the version string, in the code version tests/solutions/test_code_version.py hashes",
    "base/constants.py": "numbers with their sources, read by every physics test",
    "base/errors.py": "the error classes: every refusal test matches one",
    "base/files.py": "regular files only: the FIFO refusals of tests/orbits/test_solution.py, edge/test_cli.py, "
                     "edge/test_rundir.py",
    "base/private.py": "a cache folder's rule: tests/base/linker/test_cache.py, solutions/test_store.py, "
                       "base/test_verified.py",
    "base/layout.py": "a System's named slices, tested with the System (tests/test_models.py)",
    "edge/caches.py": "what `spinorbit cache` lists and clears: tests/base/linker/test_cache.py fills and clears them",
    "edge/catalogue.py": "the built-in scenes by name: every test that loads a scene by its name",
    "edge/provenance.py": "a run's provenance: tests/scene/test_verdict.py (summary and ECSV), tests/test_plots.py",
    "scene/run_result.py": "what a scene's run returns: tests/edge/test_runner.py",
    "comparisons": "a scene's comparison, tested in its scene's file (tests/scenes/, test_scenes.py, models/)",
    "references": "what the tests compare against; the data tables' readers in tests/analysis/test_transfer.py",
    "starts": "a scene's start, tested through its scene (tests/starts/ for a start with tests of its own)",
}

# Test files named for no module, each with what it checks.
NOT_A_MODULE = {
    "test_layers.py": "the import rules across every module (docs/DEVELOPING.md, layers)",
    "test_mirror.py": "this rule",
    "test_notebooks.py": "the notebooks/ folder, which is not a module",
}


def modules():
    """Every module of spinorbit as its path below the package ('scenes/free_body.py'), packages' __init__ aside."""
    return sorted(str(path.relative_to(PACKAGE)) for path in PACKAGE.rglob("*.py") if path.name != "__init__.py")


def files_of_tests():
    return sorted(str(path.relative_to(TESTS)) for path in TESTS.rglob("test_*.py"))


def mirrors(module):
    """The test files that may hold a module's tests: its own, then each package's around it, innermost first."""
    parts = Path(module).with_suffix("").parts
    return [Path(*parts[:-1], f"test_{parts[-1]}.py")] + [
        Path(*parts[:depth - 1], f"test_{parts[depth - 1]}.py") for depth in range(len(parts) - 1, 0, -1)]


def exempt(module):
    parts = Path(module).parts
    return any("/".join(parts[:depth]) in UNMIRRORED for depth in range(1, len(parts) + 1))


def test_every_module_has_its_test_file():
    for module in modules():
        if exempt(module):
            continue
        candidates = mirrors(module)
        assert any((TESTS / path).is_file() for path in candidates), \
            f"spinorbit/{module} has no test file: add tests/{candidates[0]} (or list it in UNMIRRORED with its reason)"


def test_every_test_file_is_named_for_a_module_or_a_package():
    for name in files_of_tests():
        if name in NOT_A_MODULE:
            continue
        path = Path(name)
        stem = path.stem.removeprefix("test_")
        place = PACKAGE / path.parent / stem
        assert place.with_suffix(".py").is_file() or (place / "__init__.py").is_file(), \
            f"tests/{name} is named for no module or package: spinorbit/{path.parent / stem}(.py) does not exist"


def test_every_folder_of_tests_is_a_package():
    """Two test_earth.py in two folders would clash as top-level modules without it."""
    for folder in [TESTS, *(path for path in TESTS.rglob("*") if path.is_dir() and path.name != "__pycache__")]:
        assert (folder / "__init__.py").is_file(), f"tests/{folder.relative_to(TESTS)} has no __init__.py"


def test_the_exceptions_are_still_needed():
    """An exception whose module has gone, or has its test file now, is dropped from the lists."""
    for entry in UNMIRRORED:
        assert (PACKAGE / entry).exists(), f"UNMIRRORED names spinorbit/{entry}, which does not exist"
        if entry.endswith(".py"):
            assert not any((TESTS / path).is_file() for path in mirrors(entry)), \
                f"spinorbit/{entry} has a test file now: drop it from UNMIRRORED"
    for name in NOT_A_MODULE:
        assert (TESTS / name).is_file(), f"NOT_A_MODULE names tests/{name}, which does not exist"
