"""Devices: the instruments and controllers people own, spoken to in their own protocols.

Each device is one module holding its reader (an instrument) or its driver (a controller), written from
the device's public documents (named in each module). The room knows protocols, not evaluations: it turns
bytes into readings in SI units and moves into bytes, and is used by ``live`` and ``capture`` (``axiscal
capture --source``, ``axiscal run``). The simulators of the instruments, which ``--source sim:KIND``
serves and the tests read through real pseudo-terminals, are in :mod:`axiscal.devices.simulators`.
"""

from axiscal.devices.attocube import *  # noqa: F401,F403
from axiscal.devices.base import *  # noqa: F401,F403
from axiscal.devices.controller import *  # noqa: F401,F403
from axiscal.devices.controllers import *  # noqa: F401,F403
from axiscal.devices.grbl import *  # noqa: F401,F403
from axiscal.devices.instruments import *  # noqa: F401,F403
from axiscal.devices.klipper import *  # noqa: F401,F403
from axiscal.devices.lines import *  # noqa: F401,F403
from axiscal.devices.links import *  # noqa: F401,F403
from axiscal.devices.linuxcnc import *  # noqa: F401,F403
from axiscal.devices.mahr import *  # noqa: F401,F403
from axiscal.devices.marlin import *  # noqa: F401,F403
from axiscal.devices.sim import *  # noqa: F401,F403
from axiscal.devices.simulators import *  # noqa: F401,F403
from axiscal.devices.sylvac import *  # noqa: F401,F403
from axiscal.devices.touchdro import *  # noqa: F401,F403
from axiscal.devices.umd import *  # noqa: F401,F403
