"""Devices: the instruments and controllers people own, spoken to in their own protocols.

Each device is one module holding its reader (an instrument) or its driver (a controller), written from
the device's public documents (named in each module). The room knows protocols, not evaluations: it turns
bytes into readings in SI units and moves into bytes, and is used by ``live`` and ``capture`` (``axiscal
capture --source``, ``axiscal run``). The simulators of the instruments, which ``--source sim:KIND``
serves and the tests read through real pseudo-terminals, are in :mod:`axiscal.devices.simulators`.
"""

from importlib import import_module as _import_module

__all__: list[str] = []
for _name in ("attocube", "base", "controller", "controllers", "grbl", "instruments", "klipper", "lines", "links", "linuxcnc", "mahr", "marlin", "sim", "simulators", "sylvac", "touchdro", "umd"):
    _module = _import_module(f"axiscal.devices.{_name}")
    for _public in _module.__all__:
        globals()[_public] = getattr(_module, _public)
        __all__.append(_public)
del _name, _module, _public, _import_module
