"""Progress where stderr is not a terminal (a notebook, a log, CI): a line at each tenth of the run or every
30 s, after the first 2 s; none with --quiet."""
import io

from spinorbit.base import progress


class Clock:
    def __init__(self):
        self.now = 0.0

    def __call__(self):
        return self.now


def test_lines_come_at_each_tenth_and_say_the_fraction_and_time_left():
    clock, out = Clock(), io.StringIO()
    lines = progress.Lines("moon", 0.0, 1000.0, "d", clock=clock, stream=out)
    for step in range(1, 101):                     # 100 chunks of 10 d, 0.1 s each: 10 s in all
        clock.now = 0.1 * step
        lines.advance_to(10.0 * step)
    said = out.getvalue().splitlines()
    # nothing in the first 2 s (20 %), then one line per tenth: 20 %, 30 %, ... 100 %
    assert [line.split(": ")[1].split("%")[0] for line in said] == [str(p) for p in range(20, 101, 10)]
    assert said[0] == "moon: 20% (200/1000 d), 2 s, ~8 s left"      # 2 s for 20 %: 8 s for the other 80 %
    assert said[-1] == "moon: 100% (1000/1000 d), 10 s"


def test_a_slow_run_says_a_line_every_30_s_between_tenths():
    clock, out = Clock(), io.StringIO()
    lines = progress.Lines("deep time", 0.0, -1000.0, "kyr", clock=clock, stream=out)
    for second in range(1, 121):                   # 1 kyr a second: 4 % in 40 s
        clock.now = float(second)
        lines.advance_to(-0.1 * second)
    assert len(out.getvalue().splitlines()) == 4    # at 30, 60, 90 and 120 s
    assert out.getvalue().splitlines()[0].startswith("deep time: 0% (3/1000 kyr), 30 s")


def test_not_a_terminal_gives_lines_and_quiet_gives_nothing(monkeypatch, capsys):
    monkeypatch.setattr(progress, "DELAY_S", 0.0)
    monkeypatch.delenv("SPINORBIT_QUIET", raising=False)
    with progress.progress("run", 0.0, 10.0) as advance_to:        # pytest's stderr is not a terminal
        advance_to(5.0)
    assert "run: 50% (5/10 d)" in capsys.readouterr().err
    monkeypatch.setenv("SPINORBIT_QUIET", "1")
    with progress.progress("run", 0.0, 10.0) as advance_to:
        advance_to(5.0)
    assert capsys.readouterr().err == ""


def test_a_long_stage_says_when_it_starts_and_ends_and_a_short_one_nothing(monkeypatch):
    import io
    import time

    monkeypatch.delenv("SPINORBIT_QUIET", raising=False)
    monkeypatch.setattr(progress, "DELAY_S", 0.05)
    said = io.StringIO()
    with progress.stage("fitting", stream=said):
        time.sleep(0.3)
    with progress.stage("quick", stream=said):
        pass
    lines = said.getvalue().splitlines()
    assert lines[0] == "fitting ..." and lines[1].startswith("fitting: done in ") and len(lines) == 2
