"""``python -m spinorbit``: the ``spinorbit`` command, for a checkout that is not installed."""
import sys

from spinorbit.cli import console

sys.exit(console())
