"""Devices: the instruments and controllers people own, spoken to in their own protocols.

Each device is one module holding its reader (an instrument) or its driver (a controller). The room knows
protocols, not evaluations: it turns bytes into readings in SI units and moves into bytes, and is used by
``live`` and ``capture``.
"""
