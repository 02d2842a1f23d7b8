"""``python -m spinorbit``: the ``spinorbit`` command, for a checkout that is not installed."""
import sys

from spinorbit.edge.cli import console

if __name__ == "__main__":
    sys.exit(console())
