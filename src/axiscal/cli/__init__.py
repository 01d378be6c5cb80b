"""The ``axiscal`` command line: a thin layer over the SI API.

Each module in this package that defines ``register(group)`` adds its commands to the main group;
:mod:`axiscal.cli.main` finds them, so a new command needs no edit elsewhere.
"""

__all__: list[str] = []
