"""The run directory is one whole run, old or new: swapped in at the end, locked, never mixed,
foreign files refused, a failed run kept beside a good one, a killed run leaving the old one intact."""
import errno
import functools
import hashlib
import json
import os
import re
import shutil
import signal
import socket
import stat
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from spinorbit.base.errors import ScenarioError
from spinorbit.edge.cli import main
from spinorbit.edge.rundir import MANIFEST, RunDirectory, read_manifest
from tests.second_user import IS_ROOT, OTHER, as_user, chown_other, needs_root, shared_dir

ROOT = Path(__file__).parents[2]
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
    assert summary["status"] == "failed" and summary["run"]["outputs_written"] == 21   # t = 0, 0.5, ... 10 d
    assert read_manifest(failed)["status"] == "failed"
    err = capsys.readouterr().err
    assert f"partial output written to {failed}/; the previous run in {out}/ is kept" in err


@pytest.mark.parametrize("name", ["report.md", "omega.png"])
def test_files_spinorbit_did_not_write_are_refused_up_front(tmp_path, capsys, name):
    out = tmp_path / "run"
    out.mkdir()
    (out / name).write_text("the user's own file\n")
    assert main(["run", str(P93), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("error: --out: got ")
    assert name in err and "--force" in err
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
    """Killed after out -> .run.old-N and before .run.new-N -> out: the complete new run is moved in."""
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
    command = [sys.executable, "-m", "spinorbit.edge.cli", "run", str(slow), "--out", str(out), "--force",
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


# --- issue 27: the output directory owns only what it wrote --------------------------------------

@pytest.fixture
def alarm():
    """Fail, rather than hang, a test that would block (e.g. on opening a FIFO)."""
    def expire(signum, frame):
        raise TimeoutError("blocked for 20 s")
    previous = signal.signal(signal.SIGALRM, expire)
    signal.alarm(20)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, previous)


@pytest.fixture
def shared():
    path = shared_dir()
    yield path
    shutil.rmtree(path, ignore_errors=True)


def one_line(info):
    message = str(info.value)
    assert "\n" not in message and message.startswith("--out: got "), message
    return message


def test_entries_added_while_the_run_computes_are_kept(tmp_path):
    out = tmp_path / "run"
    good_run(out)
    with RunDirectory(out) as run:
        (out / "notes.txt").write_text("mine\n")
        (out / "data").mkdir()
        (out / "data" / "x.csv").write_text("1\n")
        (out / "empty").mkdir()
        os.symlink("/etc", out / "etc-link")
        run.commit(writer(summary_json="{}\n"))
    assert (out / "notes.txt").read_text() == "mine\n" and (out / "data" / "x.csv").read_text() == "1\n"
    assert (out / "empty").is_dir() and os.readlink(out / "etc-link") == "/etc"
    assert (out / "summary.json").read_text() == "{}\n" and not (out / "zeta.png").exists()
    assert list(read_manifest(out)["files"]) == ["summary.json"]
    assert sorted(p.name for p in tmp_path.iterdir()) == [".run.lock", "run"]


def test_an_entry_taking_a_name_the_run_writes_is_kept_and_the_run_goes_beside(tmp_path):
    out = tmp_path / "run"
    good_run(out)
    with pytest.raises(ScenarioError) as info, RunDirectory(out) as run:
        (out / "summary.json").write_text("my own summary\n")
        run.commit(writer(summary_json="{}\n"))
    (elsewhere,) = tmp_path.glob(f"run.new-{os.getpid()}-*")
    assert f"this run was written to {elsewhere}/" in one_line(info)
    assert "summary.json (file)" in str(info.value)
    assert (out / "summary.json").read_text() == "my own summary\n"
    assert (elsewhere / "summary.json").read_text() == "{}\n" and read_manifest(elsewhere)["status"] == "ok"


def test_user_names_are_never_patterns(tmp_path):
    """A run into run[1] leaves run1's checkpoint and its recovery folder alone (a glob would match them)."""
    good_run(tmp_path / "run1")
    (tmp_path / "run1.checkpoint.npz").write_bytes(b"run1's checkpoint")
    shutil.copytree(tmp_path / "run1", tmp_path / ".run1.new-999999")
    before = {p.name: snapshot(p) if p.is_dir() else p.read_bytes() for p in tmp_path.iterdir()}
    for name in ("run[1]", "run?", "run*"):
        good_run(tmp_path / name)
        with RunDirectory(tmp_path / name) as run:
            run.fail(writer(summary_json="{}\n"))
    after = {p.name: snapshot(p) if p.is_dir() else p.read_bytes() for p in tmp_path.iterdir()}
    assert {k: after[k] for k in before} == before


def test_a_killed_checkpoint_save_leaves_nothing_after_the_next_run(tmp_path):
    """What a save killed before its rename left beside run (verified.write's names, the main checkpoint's and a
    part's) goes when the next run into run takes the lock; run1's stays."""
    left = [".run.checkpoint.npz.tmp-999999-k1ll3d_x", ".run.checkpoint-tides_off.npz.tmp-999999-abcdefgh"]
    others = [".run1.checkpoint.npz.tmp-999999-abcdefgh", "run.checkpoint.npz"]
    for name in left + others:
        (tmp_path / name).write_bytes(b"half a save")
    good_run(tmp_path / "run")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["run", ".run.lock", *others])


def test_a_link_planted_as_the_lock_is_refused_and_its_target_kept(tmp_path, shared):
    """In a shared (sticky) folder another user plants .run.lock -> a file of the victim's."""
    precious = tmp_path / "precious.txt"
    precious.write_text("precious\n")
    plant = functools.partial(os.symlink, precious, shared / ".run.lock")
    as_user(plant) if IS_ROOT else plant()
    with pytest.raises(ScenarioError) as info:
        good_run(shared / "run")
    assert "lock file" in one_line(info) and "symbolic link" in str(info.value)
    assert precious.read_text() == "precious\n" and not (shared / "run").exists()


@needs_root
def test_a_lock_file_of_another_user_is_refused_untouched(shared):
    as_user(lambda: (shared / ".run.lock").write_text("theirs\n"))
    with pytest.raises(ScenarioError) as info:
        good_run(shared / "run")
    assert f"belongs to uid {OTHER}" in one_line(info)
    assert (shared / ".run.lock").read_text() == "theirs\n"


def make_entry(path, kind):
    if kind == "empty folder":
        path.mkdir()
    elif kind == "link to a folder":
        os.symlink("/etc", path)
    elif kind == "dangling link":
        os.symlink(path.parent / "nowhere", path)
    elif kind == "link to /dev/zero":
        os.symlink("/dev/zero", path)
    elif kind == "FIFO":
        os.mkfifo(path)
    elif kind == "socket":
        server = socket.socket(socket.AF_UNIX)
        server.bind(str(path))
        server.close()


ENTRIES = ["empty folder", "link to a folder", "dangling link", "link to /dev/zero", "FIFO", "socket"]


@pytest.mark.parametrize("kind", ENTRIES)
@pytest.mark.parametrize("name", ["notes", "summary.json"])      # a name of the run's own files too
def test_foreign_entries_are_refused_from_metadata_and_kept_with_force(tmp_path, alarm, kind, name):
    out = tmp_path / "run"
    good_run(out)
    (out / name).unlink(missing_ok=True)                 # summary.json: the user replaced the run's file
    make_entry(out / name, kind)
    kind_before = stat.S_IFMT(os.lstat(out / name).st_mode)
    described = {"empty folder": "folder", "FIFO": "FIFO", "socket": "socket"}.get(kind, "symbolic link")
    with pytest.raises(ScenarioError) as info:
        good_run(out)
    assert f"{name} ({described})" in one_line(info) and "--force" in str(info.value)
    with RunDirectory(out, force=True) as run:
        run.commit(writer(other_txt="new\n"))
    assert os.path.lexists(out / name) and (out / "other.txt").read_text() == "new\n"
    assert stat.S_IFMT(os.lstat(out / name).st_mode) == kind_before
    with pytest.raises(ScenarioError):                  # still not spinorbit's: the next run is told again
        good_run(out)


def test_force_keeps_the_folder_mode_and_owner(tmp_path):
    out = tmp_path / "run"
    out.mkdir()
    (out / "notes").mkdir()
    os.chmod(out, 0o750)
    owner = (OTHER, OTHER) if IS_ROOT else (os.getuid(), os.getgid())
    if IS_ROOT:
        chown_other(out)
    with RunDirectory(out, force=True) as run:
        run.commit(writer(summary_json="{}\n"))
    info = os.stat(out)
    assert stat.S_IMODE(info.st_mode) == 0o750 and (info.st_uid, info.st_gid) == owner
    assert (out / "notes").is_dir() and (out / "summary.json").is_file()


@needs_root
def test_as_another_user_unreadable_files_are_foreign_and_a_read_only_subfolder_never_sticks(shared):
    """The victim (uid 65534) runs into its own --out; a file it cannot read is refused as foreign without
    --force and kept with it; a read-only folder of its own run does not make later runs fail."""
    out = shared / "run"

    def first_run():
        with RunDirectory(out) as run:
            run.commit(lambda d: ((d / "000").mkdir(), (d / "000" / "summary.json").write_text("{}\n")))
        os.chmod(out / "000", 0o555)
    as_user(first_run)
    (out / "secret").write_text("root's\n")
    os.chmod(out / "secret", 0o600)

    def refused():
        with pytest.raises(ScenarioError) as info:
            good_run(out)
        return str(info.value)
    assert "secret (file)" in as_user(refused)

    def forced_then_again():
        for _ in range(2):
            with RunDirectory(out, force=True) as run:
                run.commit(writer(summary_json="{}\n"))
        return sorted(os.listdir(out)), sorted(os.listdir(shared))
    inside, beside = as_user(forced_then_again)
    assert inside == [MANIFEST, "secret", "summary.json"]
    assert (out / "secret").read_text() == "root's\n"
    leftovers = [name for name in beside if ".leftover-" in name]     # the read-only folder it kept
    assert len(leftovers) <= 1
    assert all((shared / name / "000" / "summary.json").is_file() for name in leftovers)


def test_a_writer_failing_half_way_keeps_what_it_wrote_beside_the_good_run(tmp_path, capsys):
    out = tmp_path / "run"
    good_run(out)
    before = snapshot(out)

    def write(directory):
        (directory / "summary.json").write_text('{"finished": true}\n')
        raise OSError(errno.ENOSPC, "No space left on device", str(directory / "timeseries.ecsv"))
    with pytest.raises(ScenarioError) as info, RunDirectory(out) as run:
        run.commit(write)
    assert "No space left on device" in one_line(info)
    assert snapshot(out) == before
    kept = tmp_path / "run.failed"
    assert (kept / "summary.json").read_text() == '{"finished": true}\n'
    assert f"is in {kept}/" in capsys.readouterr().err


@pytest.mark.parametrize("what", ["file", "FIFO", "link to a file"])
def test_out_that_is_not_a_directory_is_refused_in_one_line(tmp_path, alarm, what):
    out = tmp_path / "run"
    {"file": lambda: out.write_text("x"), "FIFO": lambda: os.mkfifo(out),
     "link to a file": lambda: os.symlink("/etc/hostname", out)}[what]()
    with pytest.raises(ScenarioError) as info:
        good_run(out)
    assert "expected a directory (this is a" in one_line(info)


def test_out_under_a_file_is_refused_in_one_line(tmp_path):
    (tmp_path / "file").write_text("x")
    with pytest.raises(ScenarioError) as info:
        good_run(tmp_path / "file" / "run")
    assert f"a path through folders ({tmp_path / 'file'} is not a folder)" in one_line(info)


def test_a_failed_run_beside_a_good_one_when_out_failed_is_a_file(tmp_path, capsys):
    """<out>.failed taken by a file: the partial output goes to <out>.failed-<pid>, the error is printed."""
    out = tmp_path / "run"
    good_run(out)
    (tmp_path / "run.failed").write_text("a file of the user's\n")
    stopped = tmp_path / "stopped.toml"
    stopped.write_text(re.sub(r'method = "dop853"\nrtol = .*\natol = .*\n',
                              'method = "rk8"\nstep = "0.1 d"\nmax_steps = 100\n', FREE_BODY.read_text()))
    assert main(["run", str(stopped), "--out", str(out), "--set", "output.plots=false"]) == 3
    err = capsys.readouterr().err
    (failed,) = tmp_path.glob(f"run.failed-{os.getpid()}-*")
    assert json.loads((failed / "summary.json").read_text())["run"]["outputs_written"] == 21
    assert (tmp_path / "run.failed").read_text() == "a file of the user's\n"
    assert f"partial output written to {failed}/" in err and "error: rk8" in err


def test_names_a_run_writes_beside_out_cannot_be_planted(tmp_path, shared):
    """Links planted (by another user, in a shared folder) where a run used to stage, retire and checkpoint
    (names from its pid alone) lead nowhere: those names now carry a random part and are made afresh."""
    from spinorbit.edge.checkpoint import Checkpoint

    victim = tmp_path / "victim"
    victim.mkdir()
    (victim / "summary.json").write_text("the victim's\n")
    (tmp_path / "precious.npz").write_text("the victim's\n")
    pid = os.getpid()
    links = {f".run.new-{pid}": victim, f".run.old-{pid}": victim,
             f".run.checkpoint.npz.tmp-{pid}": tmp_path / "precious.npz"}

    def plant():
        for name, target in links.items():
            os.symlink(target, shared / name)
    as_user(plant) if IS_ROOT else plant()
    good_run(shared / "run")
    good_run(shared / "run", summary_json="{}\n")
    Checkpoint(shared / "run.checkpoint.npz").save({"a": "b"}, np.zeros((1, 3)))
    assert sorted(os.listdir(victim)) == ["summary.json"]
    assert (victim / "summary.json").read_text() == "the victim's\n"
    assert (tmp_path / "precious.npz").read_text() == "the victim's\n"
    assert (shared / "run" / "summary.json").read_text() == "{}\n"


def test_a_finished_run_its_out_cannot_take_is_kept_elsewhere(tmp_path, capsys, monkeypatch):
    """The output directory fails before anything is staged (here: no space for the staging folder): the
    finished run goes to a new private temporary directory, said in one line beside the error."""
    import tempfile

    def full(self):
        self._io(lambda: (_ for _ in ()).throw(OSError(errno.ENOSPC, "No space left on device")))
    monkeypatch.setattr(RunDirectory, "stage", full)
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    code = main(["--quiet", "run", str(FREE_BODY), "--out", str(tmp_path / "run"), "--set", "span.end=5 d",
                 "--set", "output.plots=false"])
    err = capsys.readouterr().err.strip().splitlines()
    (rescued,) = tmp_path.glob("spinorbit-free_body-*")
    refusal = (f"error: --out: got '{tmp_path / 'run'}'; expected a directory spinorbit can write: "
               "No space left on device")
    assert code == 2 and err == [f"the finished run is written to {rescued}/ instead", refusal]
    assert json.loads((rescued / "summary.json").read_text())["verdict"]["result"] == "pass"


def test_a_name_too_long_for_its_siblings_is_refused_in_one_line(tmp_path):
    with pytest.raises(ScenarioError) as info:
        good_run(tmp_path / ("x" * 250))
    assert "a name of at most" in one_line(info) and not list(tmp_path.iterdir())
