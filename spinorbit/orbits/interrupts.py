"""Ctrl-C around REBOUND: its ``integrate()`` and ``steps()`` install a C handler for SIGINT (to stop its own
loop and raise KeyboardInterrupt when they return) and leave it installed, so that afterwards Ctrl-C would only
set REBOUND's flag and the run would go on.  :func:`python_sigint` puts Python's handler back after each call."""
import contextlib
import signal
import threading


@contextlib.contextmanager
def python_sigint():
    """Run a REBOUND call, then reinstall the SIGINT handler Python had (main thread only: the others cannot
    set handlers, and REBOUND's C handler is process-wide, so the main thread's next call restores it)."""
    try:
        yield
    finally:
        handler = signal.getsignal(signal.SIGINT)
        if handler is not None and threading.current_thread() is threading.main_thread():
            signal.signal(signal.SIGINT, handler)
