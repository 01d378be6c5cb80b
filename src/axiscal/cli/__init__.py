"""The ``axiscal`` command line: a thin layer over the SI API.

The commands are listed in one table, :data:`axiscal.cli.main.COMMANDS` (a new command is one line
there); each command's module is imported only when that command runs or shows its help, and
imports the library inside its functions.
"""

__all__: list[str] = []
