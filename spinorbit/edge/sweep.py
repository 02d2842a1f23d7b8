"""Parameter sweeps and ensembles on Dask (a local cluster by default).

``spinorbit sweep SCENE.toml --vary integrator.rtol=1e-8,1e-10 --vary span.end="10 d","20 d"``
runs the Cartesian product of the values (at most ``MAX_MEMBERS``), one run directory
per member (``OUT/000/``, ``OUT/001/`` ...), and collects every member's comparison and
run metrics into ``OUT/sweep.json`` and ``OUT/sweep.csv``.  ``OUT`` is a run directory
(spinorbit.edge.rundir): a previous sweep is replaced whole, files spinorbit did not write are
refused (or kept, with ``force``).  Each member writes its own files as it finishes, so
nothing done is lost if the sweep stops (it is kept in ``OUT`` or ``OUT.failed``).

``scheduler``: "local" (dask.distributed LocalCluster, one process per core),
"synchronous" (in this process, for debugging), or a scheduler address
("tcp://host:8786") to use a cluster that outgrows one machine.
"""
import itertools
import json
import math
from pathlib import Path

from ..base.errors import ScenarioError

MAX_MEMBERS = 10_000            # a grid's members: each is a run and a directory
CONNECT_TIMEOUT_S = 10          # waiting for a scheduler at an address


def parse_vary(text):
    """``key=v1,v2`` -> (key, [v1, v2]) with each value kept as TOML text."""
    if "=" not in text:
        raise ScenarioError("--vary", text, "key=value1,value2,... e.g. span.end=10 d,20 d")
    key, values = (s.strip() for s in text.split("=", 1))
    if not key:
        raise ScenarioError("--vary", text, "key=value1,value2,... with a dotted key, e.g. "
                                            "span.end=10 d,20 d")
    items = [v.strip() for v in _split_top_level(values) if v.strip()]
    if not items:
        raise ScenarioError(f"--vary {key}", values, "at least one value")
    return key, items


def grid(varies):
    """{key: [values]} of ``--vary`` texts, in their order; a key given twice is refused (one list per key:
    give its values once, comma-separated)."""
    out = {}
    for text in varies:
        key, values = parse_vary(text)
        if key in out:
            raise ScenarioError(f"--vary {key}", text, f"each key once, its values in one list (e.g. {key}="
                                f"{','.join(out[key] + values)})")
        out[key] = values
    return out


def members(grid):
    """Cartesian product of {key: [values]} as lists of ``key=value`` overrides (at most MAX_MEMBERS)."""
    count = math.prod(len(values) for values in grid.values())
    if count > MAX_MEMBERS:
        raise ScenarioError("--vary", " ".join(f"{k}=({len(v)} values)" for k, v in grid.items()),
                            f"a grid of at most {MAX_MEMBERS:,} members (this one has {count:,}); "
                            "split the sweep into several")
    keys = list(grid)
    return [[f"{k}={v}" for k, v in zip(keys, combo)] for combo in itertools.product(*grid.values())]


def run_member(scenario_path, overrides, staged, out_dir):
    """Run one member and write its run directory whole into ``staged`` (it will be ``out_dir``); return a
    flat record (never raises on bad input or a failed write)."""
    from ..base.errors import SpinorbitError
    from .reports import write_run
    from .rundir import write_whole
    from .runner import run_scenario

    record = {"overrides": overrides, "out": str(out_dir)}
    try:
        result = run_scenario(scenario_path, overrides)
        write_whole(staged, lambda d: write_run(result, d))
        record.update(status="ok", verdict=result.summary["verdict"]["result"],
                      **_flat_metrics(result.summary))
    except SpinorbitError as exc:
        record.update(status="failed", error=str(exc))
    except OSError as exc:
        record.update(status="failed", error=f"could not write {staged}: {exc.strerror or exc}")
    return record


def run_sweep(scenario_path, grid, out_dir, scheduler="local", base_overrides=(), force=False):
    """Run every member of ``grid`` on Dask into the run directory ``out_dir`` (spinorbit.edge.rundir: each member
    in ``NNN/`` as it finishes, the tables at the end, swapped in whole; a stopped sweep keeps what
    finished); return the list of records."""
    import dask

    from .rundir import RunDirectory
    from .scenarios import load_scenario

    load_scenario(scenario_path, base_overrides)          # fail fast on a bad base scene, a grid too big,
    runs = members(grid)                                  # or a key the scene lacks
    load_scenario(scenario_path, [*base_overrides, *(f"{key}={values[0]}" for key, values in grid.items())])
    out = Path(out_dir)
    with RunDirectory(out, force=force) as run_dir:
        staged = run_dir.stage()
        jobs = [dask.delayed(run_member)(str(scenario_path), [*base_overrides, *m], staged / f"{i:03d}",
                                         run_dir.out / f"{i:03d}")
                for i, m in enumerate(runs)]
        with _scheduler(scheduler) as compute:
            records = list(compute(*jobs))
        (staged / "sweep.json").write_text(json.dumps(records, indent=2) + "\n")
        _write_csv(records, staged / "sweep.csv")
        _sweep_figures(scenario_path, base_overrides, records, staged)
        run_dir.commit()
    return records


def _sweep_figures(scenario_path, overrides, records, staged):
    """The scene's figures over its members, when its Scene has ``sweep_figures(tables) -> {name: draw}``
    (e.g. a band over the members' curves), drawn into the sweep directory from the members' tables."""
    from astropy.table import QTable

    from .reports import write_plots
    from .runner import span_label
    from .scenarios import load_scenario

    scenario = load_scenario(scenario_path, overrides)
    make = scenario.scene.sweep_figures
    tables = [QTable.read(staged / Path(r["out"]).name / "timeseries.ecsv", format="ascii.ecsv")
              for r in records if r.get("status") == "ok"]
    if make is None or len(tables) < 2:
        return
    write_plots(make(tables), {"scene": f"{scenario.name} (sweep of {len(tables)})",
                               "span": {"years": span_label(scenario)}}, staged)


class _scheduler:
    """Context manager yielding a ``compute(*delayed)`` function for the chosen scheduler."""

    def __init__(self, name):
        self.name, self.client, self.cluster = name, None, None

    def __enter__(self):
        import dask

        if self.name == "synchronous":
            return lambda *jobs: dask.compute(*jobs, scheduler="synchronous")
        from dask.distributed import Client, LocalCluster

        if self.name == "local":
            self.cluster = LocalCluster(threads_per_worker=1, processes=True, dashboard_address=None)
            self.client = Client(self.cluster)
        elif self.name.startswith(("tcp://", "tls://", "ucx://")):
            try:
                self.client = Client(self.name, timeout=CONNECT_TIMEOUT_S)
            except (OSError, ValueError, TypeError) as exc:
                reason = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
                raise ScenarioError("--scheduler", self.name, f"a Dask scheduler that answers within "
                                    f"{CONNECT_TIMEOUT_S} s ({reason})") from None
        else:
            raise ScenarioError("--scheduler", self.name,
                                "'local', 'synchronous' or a scheduler address tcp://host:port")
        return self._gather

    def _gather(self, *jobs):
        """The members' records from the cluster; a member that took its workers down with it each time
        (dask's allowed-failures) ends the sweep in one line, what finished kept (rundir)."""
        from dask.distributed import KilledWorker

        try:
            return self.client.gather(self.client.compute(list(jobs)))
        except KilledWorker as exc:
            raise ScenarioError("--scheduler", self.name, "workers that outlive the members: one member's worker "
                                f"died each time it ran ({_first_line(exc)}); the members that finished are "
                                "kept") from None

    def __exit__(self, *exc):
        if self.client is not None:
            self.client.close()
        if self.cluster is not None:
            self.cluster.close()


def _first_line(exc):
    return str(exc).splitlines()[0][:120] if str(exc) else type(exc).__name__


def _flat_metrics(summary):
    flat = {}
    for table in ("comparison", "run"):
        for key, value in summary.get(table, {}).items():
            if isinstance(value, (int, float, str, bool)):
                flat[key] = value
    return flat


def _write_csv(records, path):
    import csv

    columns = list(dict.fromkeys(k for r in records for k in r))
    with path.open("w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=columns)
        writer.writeheader()
        for record in records:
            writer.writerow({k: (";".join(v) if isinstance(v, list) else v) for k, v in record.items()})


def _split_top_level(text):
    """Split on commas outside quotes and brackets (so lists and quantities survive)."""
    parts, depth, quote, current = [], 0, None, ""
    for char in text:
        if quote:
            quote = None if char == quote else quote
        elif char in "\"'":
            quote = char
        elif char in "[(":
            depth += 1
        elif char in "])":
            depth -= 1
        elif char == "," and depth == 0:
            parts.append(current)
            current = ""
            continue
        current += char
    parts.append(current)
    return parts
