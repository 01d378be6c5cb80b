"""axiscal: measure, model and compensate the geometric errors of machine axes.

The Python API works in SI units (metres, radians, kelvin, pascals). Files and the command line
use the units people use, spelled out in names (``position_mm``, ``EXX_um``, ``--pressure-pa``).
"""

from axiscal.errors import AxiscalError
from axiscal.version import __version__ as __version__

__all__ = ["AxiscalError", "load_machine", "Machine"]


def __getattr__(name: str):
    # Lazy so that `import axiscal` stays cheap and the submodules import in any order.
    if name in ("load_machine", "Machine"):
        from axiscal.model import machine

        return getattr(machine, name)
    raise AttributeError(name)
