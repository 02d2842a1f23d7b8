"""Progress of long runs on stderr: simulated time, rate and time left (tqdm).

A bar appears only after ``DELAY_S`` seconds and only when stderr is a
terminal; ``spinorbit --quiet`` (or ``SPINORBIT_QUIET=1``) turns it off.
"""
import contextlib
import os

DELAY_S = 2.0


def enabled():
    return os.environ.get("SPINORBIT_QUIET", "") in ("", "0")


@contextlib.contextmanager
def progress(description, start, end, unit="d"):
    """A bar over [start, end] in ``unit``; yields ``advance_to(value)``.  No bar when description is None."""
    if description is None or not enabled():
        yield lambda value: None
        return
    from tqdm import tqdm

    total = abs(end - start)
    with tqdm(total=total, desc=description, unit=unit, delay=DELAY_S, disable=None, leave=False,
              dynamic_ncols=True, bar_format="{desc}: {percentage:3.0f}%|{bar}| {n:.6g}/{total:.6g} {unit} "
                                             "[{elapsed}<{remaining}, {rate_fmt}]") as bar:
        def advance_to(value):
            bar.update(min(abs(value - start), total) - bar.n)

        yield advance_to
