"""Parameter sweeps on Dask: every member runs, writes its own directory, and is collected."""
import json
import os
import re
import signal
import threading
import time
from pathlib import Path

import pytest

from spinorbit.edge.sweep import members, parse_vary, run_sweep

FREE_BODY = Path(__file__).parents[2] / "scenarios" / "free_body.toml"


def test_vary_parsing_keeps_lists_and_quantities():
    assert parse_vary('span.end="10 d","20 d"') == ("span.end", ['"10 d"', '"20 d"'])
    key, values = parse_vary('body.omega0=["1 rad/d","0 rad/d","1 rad/d"],["2 rad/d","0 rad/d","1 rad/d"]')
    assert key == "body.omega0" and len(values) == 2 and values[0].startswith("[")
    assert len(members({"a": [1, 2, 3], "b": [4, 5]})) == 6


@pytest.mark.parametrize("scheduler", ["synchronous", "local"])
def test_sweep_over_tolerance_converges_to_the_closed_form(tmp_path, scheduler):
    grid = {"integrator.rtol": ["1e-7", "1e-12"]}
    records = run_sweep(FREE_BODY, grid, tmp_path, scheduler, ["span.end=50 d", "output.plots=false"])
    assert [r["status"] for r in records] == ["ok", "ok"]
    loose, tight = (r["omega_max_rel_error_vs_closed_form"] for r in records)
    assert tight < 1e-10 < loose < 1e-4
    assert json.loads((tmp_path / "sweep.json").read_text()) == records
    assert all((Path(r["out"]) / "summary.json").is_file() for r in records)


def test_a_key_given_twice_to_vary_is_refused_in_one_line(capsys):
    from spinorbit.base.errors import ScenarioError
    from spinorbit.edge import cli
    from spinorbit.edge.sweep import grid

    with pytest.raises(ScenarioError, match="--vary integrator.rtol") as info:
        grid(["integrator.rtol=1e-8", "span.end=5 d", "integrator.rtol=1e-10,1e-12"])
    assert "\n" not in str(info.value) and "once" in str(info.value)
    assert grid(["integrator.rtol=1e-8,1e-10", "span.end=5 d"]) == {"integrator.rtol": ["1e-8", "1e-10"],
                                                                      "span.end": ["5 d"]}
    assert cli.main(["sweep", "scenarios/free_body.toml", "--vary", "integrator.rtol=1e-8", "--vary",
                     "integrator.rtol=1e-10", "--scheduler", "synchronous", "--out", "/nonexistent/x"]) == 2
    assert capsys.readouterr().err.count("\n") == 1


# Sweeps on a real dask.distributed cluster: a scheduler and worker processes on 127.0.0.1 reached by its
# tcp:// address, as `spinorbit sweep --scheduler tcp://host:port` reaches one on other machines; the members'
# numbers are the local sweep's, bit for bit; a worker killed mid-sweep costs its member a rerun, not the sweep;
# and the README's sweep example is one whose members pass.


ROOT = Path(__file__).parents[2]
SHORT = ["span.end=20 d", "output.plots=false"]
GRID = {"integrator.rtol": ["1e-10", "1e-13"], "body.moments": ["[0.5, 1.0, 2.0]", "[0.6666666666666666, 1.0, 2.0]"]}
NOT_NUMBERS = {"out", "wall_s"}        # where each member ran, and how long it took


@pytest.fixture(scope="module")
def cluster():
    """A scheduler and two single-threaded worker processes (each under a nanny that restarts it) on
    127.0.0.1."""
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", scheduler_port=0,
                      dashboard_address=None) as local:
        yield local


def numbers(records):
    return [{key: value for key, value in record.items() if key not in NOT_NUMBERS} for record in records]


def test_a_sweep_through_a_schedulers_tcp_address_gives_the_local_sweeps_numbers(cluster, tmp_path):
    address = cluster.scheduler_address
    assert re.fullmatch(r"tcp://127\.0\.0\.1:\d+", address)
    remote = run_sweep(FREE_BODY, GRID, tmp_path / "remote", address, SHORT)
    local = run_sweep(FREE_BODY, GRID, tmp_path / "local", "synchronous", SHORT)
    assert [r["status"] for r in remote] == ["ok"] * 4
    assert numbers(remote) == numbers(local)                    # every metric, to the last bit
    for a, b in zip(remote, local):                              # and every member's table, byte for byte
        body = lambda run: [line for line in (Path(run["out"]) / "timeseries.ecsv").read_text().splitlines()
                            if not line.startswith("#")]
        assert body(a) == body(b)
    # the closed form (Euler §808) judges each member as the local run does: the tight tolerance passes
    assert [r["verdict"] for r in remote][2:] == ["pass", "pass"]         # rtol 1e-13, both bodies


@pytest.mark.slow
def test_a_worker_killed_mid_sweep_costs_a_rerun_of_its_member_not_the_sweep(cluster, tmp_path):
    """The scheduler hands the dead worker's member to another (dask's allowed-failures: 3); the nanny
    restarts the worker.  The killed member's files are written whole or not at all (rundir.write_whole)."""
    from dask.distributed import Client

    client = Client(cluster.scheduler_address)
    pids = client.run(os.getpid)
    killed = []

    def kill_a_busy_worker():                  # once a member runs on a worker, SIGKILL that worker
        while not killed:
            busy = [address for address, keys in client.processing().items() if keys]
            if busy:
                time.sleep(1.0)
                os.kill(pids[busy[0]], signal.SIGKILL)
                killed.append(pids[busy[0]])
            time.sleep(0.05)

    killer = threading.Thread(target=kill_a_busy_worker, daemon=True)
    killer.start()
    records = run_sweep(FREE_BODY, {"integrator.rtol": ["1e-13", "3e-14"]}, tmp_path / "sweep",
                        cluster.scheduler_address, ["output.plots=false"])
    killer.join(timeout=5)
    assert killed and killed[0] not in client.run(os.getpid).values()     # a worker died mid-sweep, replaced
    client.close()
    assert [r["status"] for r in records] == ["ok", "ok"]
    # Euler's closed form over 100 periods: each member within the scene's 1e-10 rad
    assert all(r["attitude_max_error_vs_closed_form_rad"] <= 1e-10 for r in records)


@pytest.mark.slow
def test_a_member_whose_worker_dies_each_time_stops_the_sweep_in_one_line(tmp_path):
    """With dask's allowed-failures at 0, one dead worker is the member's last: the sweep ends in a
    ScenarioError on --scheduler (the command line's one line, exit 2), not dask's traceback."""
    import dask
    from dask.distributed import Client, LocalCluster

    from spinorbit.base.errors import ScenarioError

    with dask.config.set({"distributed.scheduler.allowed-failures": 0}), \
            LocalCluster(n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1", scheduler_port=0,
                         dashboard_address=None) as local, Client(local.scheduler_address) as client:
        (pid,) = client.run(os.getpid).values()

        def kill_when_busy():
            while not any(client.processing().values()):
                time.sleep(0.05)
            time.sleep(1.0)
            os.kill(pid, signal.SIGKILL)

        threading.Thread(target=kill_when_busy, daemon=True).start()
        with pytest.raises(ScenarioError) as err:
            run_sweep(FREE_BODY, {"integrator.rtol": ["1e-13"]}, tmp_path / "sweep", local.scheduler_address,
                      ["output.plots=false"])
    text = str(err.value)
    assert err.value.key == "--scheduler" and "\n" not in text and "workers that outlive the members" in text


def test_the_readmes_sweep_example_has_members_that_pass(tmp_path):
    line = next(line for line in (ROOT / "README.md").read_text().splitlines()
                if line.startswith("spinorbit sweep "))
    key, values = parse_vary(re.search(r"--vary (\S+)", line).group(1))
    records = run_sweep(ROOT / line.split()[2], {key: values}, tmp_path, "synchronous", ["output.plots=false"])
    assert [r["verdict"] for r in records] == ["pass"] * len(values)
    # the figure each is judged by, against Euler's closed form (§808): the scene's 1e-10 rad
    assert all(r["attitude_max_error_vs_closed_form_rad"] <= 1e-10 for r in records)
