"""Kernels that cannot be trusted are refused in one line naming orbit.source: missing, empty, text,
truncated, non-finite coefficients, and a body that jumps between the interpolant's samples."""
import importlib.resources
import shutil

import numpy as np
import pytest
from jplephem.daf import DAF
from jplephem.spk import SPK

from spinorbit.base.errors import InputError
from spinorbit.edge.cli import main
from spinorbit.orbits.sources import sample_orbits

DE421 = importlib.resources.files("skyfield_data") / "data" / "de421.bsp"
J2000_JD = 2451545.0


def edited_de421(path, t_tdb_d, edit):
    """A copy of DE421 with ``edit(x0)`` applied to the constant Chebyshev term of the Moon's x
    (301 relative to the Earth-Moon barycentre, km) in the record covering ``t_tdb_d``."""
    shutil.copy(DE421, path)
    spk = SPK.open(str(DE421))
    segment = next(s for s in spk.segments if s.target == 301)
    init, length, record_words, _ = spk.daf.read_array(segment.end_i - 3, segment.end_i)
    spk.close()
    record = int((t_tdb_d * 86400.0 - init) // length)
    words = np.memmap(path, dtype="<f8", mode="r+")
    at = segment.start_i - 1 + record * int(record_words) + 2       # [mid, radius, x0, ...]
    words[at] = edit(words[at])
    words.flush()
    return path, (init + record * length) / 86400.0                  # record start, TDB days


def refusal(path):
    with pytest.raises(InputError) as info:
        sample_orbits(str(path), "moon", ("earth", "sun"), -3.0, 8.0)
    message = str(info.value)
    assert message.startswith(f"source: got '{path}'") and "\n" not in message
    return message


@pytest.mark.parametrize("kind, content, says", [
    ("missing", None, "no such file"),
    ("empty", b"", "cannot be read"),
    ("text", b"hello, I am not a kernel\n", "cannot be read"),
    ("truncated", 3_000_000, "truncated"),
])
def test_unreadable_kernels(tmp_path, kind, content, says):
    path = tmp_path / f"{kind}.bsp"
    if isinstance(content, bytes):
        path.write_bytes(content)
    elif isinstance(content, int):
        path.write_bytes(DE421.read_bytes()[:content])
    assert says in refusal(path)


def test_non_finite_coefficients(tmp_path):
    path, _ = edited_de421(tmp_path / "nan.bsp", 1.0, lambda x: np.nan)
    assert "finite coefficients" in refusal(path)


def test_a_moon_that_jumps_by_1_km_is_flagged_by_the_interpolant_check(tmp_path):
    """One 4-day Moon record moved 1 km: the quintic Hermite's mid-point check (1e-7 km on DE421 at 0.25 d)
    sees half the jump (0.5 km) in the interval holding it, at the record boundary."""
    path, boundary = edited_de421(tmp_path / "jump.bsp", 1.0, lambda x: x + 1.0)
    message = refusal(path)
    assert "move smoothly" in message
    error_km = float(message.split("interpolation error ")[1].split(" km")[0])
    assert error_km == pytest.approx(0.5, rel=0.05)
    t_jump = float(message.split("near t = ")[1].split(" d")[0])
    assert abs(t_jump - boundary) <= 0.125 or abs(t_jump - (boundary + 4.0)) <= 0.125


def test_a_bad_kernel_through_the_command_line(tmp_path, capsys):
    path = tmp_path / "empty.bsp"
    path.write_bytes(b"")
    code = main(["run", "scenarios/moon_libration.toml", "--out", str(tmp_path / "out"),
                 "--set", f'orbit.source="{path}"', "--set", 'span.start="2000-01-01T12:00:00"',
                 "--set", 'span.end="4 d"', "--set", "model.level=1"])
    err = capsys.readouterr().err
    assert code == 2 and len(err.splitlines()) == 1 and err.startswith("error: orbit.source: got "), err


def without_the_moon(path):
    """A copy of DE421 whose Moon segment (301) is relabelled as body 3010, so the kernel holds no Moon."""
    shutil.copy(DE421, path)
    with open(path, "r+b") as f:
        daf = DAF(f)
        for record_number, n_summaries, data in list(daf.summary_records()):
            data = bytearray(data)
            for i in range(int(n_summaries)):
                at = daf.summary_control_struct.size + i * daf.summary_step
                values = list(daf.summary_struct.unpack(data[at:at + daf.summary_length]))
                if values[2] == 301:                     # (start, end, target, center, frame, type, ...)
                    values[2] = 3010
                    data[at:at + daf.summary_length] = daf.summary_struct.pack(*values)
            daf.write_record(record_number, bytes(data))
    return path




def test_a_kernel_without_the_moon_is_refused_on_orbit_source(tmp_path, capsys):
    path = without_the_moon(tmp_path / "no_moon.bsp")
    code = main(["run", "scenarios/moon_libration.toml", "--out", str(tmp_path / "out"),
                 "--set", f'orbit.source="{path}"', "--set", 'span.start="2000-01-01T12:00:00"',
                 "--set", 'span.end="4 d"', "--set", "model.level=1"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1, err
    assert err.startswith(f"error: orbit.source: got '{path}'") and "a kernel holding moon" in err


@pytest.mark.parametrize("start, end, says", [
    ("1899-07-29T00:00:00", "10 d", "a span from 1899-07-30T00:00 to "),
    ("2200-01-20T00:00:00", "2200-02-02T00:00:00", "to 2200-01-31T00:00 TDB fits"),
    ("1899-08-29T00:00:00", "2100-01-01T00:00:00", "one of them must hold the whole span"),
])
def test_spans_at_the_edges_of_de421_say_what_fits(tmp_path, capsys, start, end, says):
    """DE421 is the .bsp (1899-07-29 to 2053-10-09) or the de421 package's arrays (1899-12-04 to 2200-02-03):
    the refusal quotes both and the span that fits once the orbit's 1-d margin is taken."""
    code = main(["--quiet", "run", "scenarios/moon_libration.toml", "--out", str(tmp_path / "out"),
                 "--set", f'span.start="{start}"', "--set", f'span.end="{end}"', "--set", "model.level=1",
                 "--set", "output.plots=false"])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1 and says in err, err
    assert "its .bsp to 2053-10-09, the de421 package's arrays from 1899-12-04" in err


def test_a_naif_module_in_the_working_directory_is_never_run(tmp_path):
    """An installed naif-<name> kernel is found from its distribution's file list, not by importing naif_<name>:
    a module of that name planted in the working directory does not run, and the name is refused in one line."""
    import subprocess
    import sys

    marker = tmp_path / "ran"
    (tmp_path / "naif_planted.py").write_text(f"open({str(marker)!r}, 'w').close()\nplanted = 'x.bsp'\n")
    code = ("from spinorbit.orbits.kernel import kernel_path\n"
            "try:\n    kernel_path('planted')\nexcept Exception as exc:\n    print(exc)\n")
    proc = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert not marker.exists()
    assert proc.stdout.startswith("source: got 'planted'") and proc.stdout.count("\n") == 1
