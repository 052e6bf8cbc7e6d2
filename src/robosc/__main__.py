"""``python -m robosc``: the same as the ``robosc`` command."""

from robosc.cli.main import run

run()
