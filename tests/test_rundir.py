"""The run directory is one whole run, old or new: swapped in at the end, locked, never mixed,
foreign files refused, a failed run kept beside a good one, a killed run leaving the old one intact."""
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from spinorbit.cli import main
from spinorbit.errors import ScenarioError
from spinorbit.rundir import MANIFEST, RunDirectory, read_manifest

ROOT = Path(__file__).parents[1]
P93 = ROOT / "scenarios" / "p93_bounded.toml"
FREE_BODY = ROOT / "scenarios" / "free_body.toml"


def writer(**contents):
    """A write(path) function standing in for reports.write_run: one file per keyword."""
    def write(directory):
        for name, text in contents.items():
            (directory / name.replace("_", ".")).write_text(text)
    return write


def good_run(out, **contents):
    with RunDirectory(out) as run:
        run.commit(writer(**(contents or {"summary_json": '{"run": "old"}\n', "zeta_png": "old plot"})))


def snapshot(directory):
    return {p.name: p.read_bytes() for p in Path(directory).iterdir()}


def test_a_new_run_replaces_the_old_one_whole(tmp_path):
    """The second run writes no plot: the first run's zeta.png must not linger beside it."""
    out = tmp_path / "run"
    good_run(out)
    good_run(out, summary_json='{"run": "new"}\n')
    assert sorted(snapshot(out)) == [MANIFEST, "summary.json"]
    assert read_manifest(out)["status"] == "ok"
    assert sorted(p.name for p in tmp_path.iterdir()) == [".run.lock", "run"]     # nothing temporary left


def test_failed_run_keeps_the_previous_good_run(tmp_path, capsys):
    """Through the command line: rk8 stopped by max_steps after 10.1 d, exit 3, partial output beside."""
    out = tmp_path / "run"
    good_run(out)
    before = snapshot(out)
    stopped = tmp_path / "stopped.toml"
    stopped.write_text(re.sub(r'method = "dop853"\nrtol = .*\natol = .*\n',
                              'method = "rk8"\nstep = "0.1 d"\nmax_steps = 100\n', FREE_BODY.read_text()))
    assert main(["run", str(stopped), "--out", str(out), "--set", "output.plots=false"]) == 3
    assert snapshot(out) == before
    failed = tmp_path / "run.failed"
    summary = json.loads((failed / "summary.json").read_text())
    assert summary["status"] == "failed" and summary["run"]["outputs_written"] == 21    # t = 0, 0.5, ..., 10 d
    assert read_manifest(failed)["status"] == "failed"
    assert f"partial output written to {failed}/; the previous run in {out}/ is kept" in capsys.readouterr().err


@pytest.mark.parametrize("name", ["report.md", "omega.png"])
def test_files_spinorbit_did_not_write_are_refused_up_front(tmp_path, capsys, name):
    out = tmp_path / "run"
    out.mkdir()
    (out / name).write_text("the user's own file\n")
    assert main(["run", str(P93), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("error: --out: got ") and name in err and "--force" in err
    assert snapshot(out) == {name: b"the user's own file\n"}


def test_force_overwrites_foreign_files_the_run_writes_and_keeps_the_others(tmp_path):
    out = tmp_path / "run"
    out.mkdir()
    (out / "summary.json").write_text("mine\n")
    (out / "notes.txt").write_text("mine\n")
    with pytest.raises(ScenarioError, match="--force"):
        good_run(out)
    with RunDirectory(out, force=True) as run:
        run.commit(writer(summary_json="{}\n"))
    assert snapshot(out)["summary.json"] == b"{}\n" and snapshot(out)["notes.txt"] == b"mine\n"
    assert list(read_manifest(out)["files"]) == ["summary.json"]     # notes.txt is still not ours


def test_an_edited_output_counts_as_foreign(tmp_path):
    out = tmp_path / "run"
    good_run(out)
    (out / "summary.json").write_text("my notes on this run\n")
    with pytest.raises(ScenarioError, match="summary.json"):
        good_run(out)
    assert (out / "summary.json").read_text() == "my notes on this run\n"


def test_a_swap_interrupted_between_its_renames_is_finished_by_the_next_run(tmp_path):
    """Killed after out -> .run.old-N and before .run.new-N -> out: the complete new run is moved into place."""
    out = tmp_path / "run"
    good_run(out)
    new = tmp_path / ".run.new-999999"
    shutil.copytree(out, new)
    (new / "summary.json").write_text('{"run": "new"}\n')
    manifest = json.loads((new / MANIFEST).read_text())       # keep the manifest true to the edit
    manifest["files"]["summary.json"] = hashlib.sha256((new / "summary.json").read_bytes()).hexdigest()
    (new / MANIFEST).write_text(json.dumps(manifest))
    os.replace(out, tmp_path / ".run.old-999999")
    with RunDirectory(out):
        pass
    assert json.loads((out / "summary.json").read_text()) == {"run": "new"}
    assert sorted(p.name for p in tmp_path.iterdir()) == [".run.lock", "run"]


def test_kill_9_mid_run_and_a_concurrent_run(tmp_path):
    """A run holding the lock refuses a second run into the same --out; kill -9 leaves the old run
    intact and the kernel releases the lock for the next run."""
    out = tmp_path / "run"
    good_run(out)
    before = snapshot(out)
    slow = tmp_path / "slow.toml"       # 4e7 rk4 steps: far longer than the test waits
    slow.write_text(re.sub(r'method = "dop853"\nrtol = .*\natol = .*\n', 'method = "rk4"\nstep = "1e-4 d"\n',
                           P93.read_text()))
    command = [sys.executable, "-m", "spinorbit.cli", "run", str(slow), "--out", str(out), "--force",
               "--set", 'span.end="4000 d"', "--set", 'span.step="10 d"']
    child = subprocess.Popen(command, cwd=tmp_path, env={**os.environ, "PYTHONPATH": str(ROOT)},
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        lock = tmp_path / ".run.lock"
        deadline = time.monotonic() + 120
        while not (lock.exists() and lock.read_text().strip() == str(child.pid)):
            assert child.poll() is None, child.communicate()[1]
            assert time.monotonic() < deadline
            time.sleep(0.05)
        with pytest.raises(ScenarioError, match=f"no other run is writing \\(process {child.pid} holds"):
            good_run(out)
    finally:
        child.send_signal(signal.SIGKILL)
        child.wait()
    assert snapshot(out) == before
    good_run(out, summary_json='{"run": "after"}\n')
    assert snapshot(out)["summary.json"] == b'{"run": "after"}\n'
