"""Progress of long runs on stderr: simulated time, rate and time left.

On a terminal, a tqdm bar; elsewhere (a notebook's stderr, a log file, CI) one line at each tenth of the run
or every ``LINE_EVERY_S`` seconds, whichever comes first.  Either appears only after ``DELAY_S`` seconds;
A step with no simulated time to count (compiling, fitting) says when it starts and ends if it lasts longer
(:func:`stage`).  ``spinorbit --quiet`` (or ``SPINORBIT_QUIET=1``) turns them off.
"""
import contextlib
import os
import sys
import threading
import time

DELAY_S = 2.0
LINE_EVERY_S = 30.0           # a line at least this often when stderr is not a terminal
LINE_EVERY_FRACTION = 0.1     # and at each tenth of the run


def enabled():
    return os.environ.get("SPINORBIT_QUIET", "") in ("", "0")


@contextlib.contextmanager
def progress(description, start, end, unit="d"):
    """Progress over [start, end] in ``unit``; yields ``advance_to(value)``.  Nothing when description is None."""
    if description is None or not enabled():
        yield lambda value: None
        return
    if not _is_terminal(sys.stderr):
        yield Lines(description, start, end, unit).advance_to
        return
    from tqdm import tqdm

    total = abs(end - start)
    with tqdm(total=total, desc=description, unit=unit, delay=DELAY_S, disable=None, leave=False,
              dynamic_ncols=True, bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.6g}/{total:.6g} {unit} "
                                             "[{elapsed}<{remaining}, {rate_fmt}]") as bar:
        def advance_to(value):
            bar.update(min(abs(value - start), total) - bar.n)

        yield advance_to


@contextlib.contextmanager
def stage(description, stream=None):
    """A step with no simulated time to count (compiling, fitting, averaging, writing): when it is still running
    after ``DELAY_S``, one line ``description ...`` on stderr, and ``description: done in 12 s`` at its end; nothing
    for a shorter step, when quiet, or when description is None."""
    if description is None or not enabled():
        yield
        return
    began, said = time.monotonic(), threading.Event()

    def announce():
        said.set()
        print(f"{description} ...", file=stream or sys.stderr, flush=True)

    timer = threading.Timer(DELAY_S, announce)
    timer.daemon = True
    timer.start()
    try:
        yield
    finally:
        timer.cancel()
        if said.is_set():
            print(f"{description}: done in {time.monotonic() - began:.0f} s", file=stream or sys.stderr, flush=True)


def _is_terminal(stream):
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


class Lines:
    """Line-wise progress for a stderr that is not a terminal: ``label: 30% (300/1000 d), 12 s, ~28 s left``."""

    def __init__(self, description, start, end, unit, clock=time.monotonic, stream=None):
        self.description, self.start, self.unit = description, start, unit
        self.total = abs(end - start)
        self.clock, self.stream = clock, stream
        self.began = self.last_time = clock()
        self.last_fraction = 0.0

    def advance_to(self, value):
        now = self.clock()
        fraction = min(abs(value - self.start) / self.total, 1.0) if self.total > 0 else 1.0
        if now - self.began < DELAY_S:             # the first line at the first tenth after the delay
            self.last_fraction = fraction
            return
        tenth = int(fraction / LINE_EVERY_FRACTION + 1e-9)
        if tenth <= int(self.last_fraction / LINE_EVERY_FRACTION + 1e-9) and now - self.last_time < LINE_EVERY_S:
            return
        self.last_fraction, self.last_time = fraction, now
        elapsed = now - self.began
        left = f", ~{elapsed * (1 - fraction) / fraction:.0f} s left" if 0 < fraction < 1 else ""
        print(f"{self.description}: {100 * fraction:.0f}% ({fraction * self.total:.6g}/{self.total:.6g} "
              f"{self.unit}), {elapsed:.0f} s{left}", file=self.stream or sys.stderr, flush=True)
