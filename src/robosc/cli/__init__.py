"""The ``robosc`` command line: a thin layer over :mod:`robosc.api`."""
