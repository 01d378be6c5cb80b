"""Connect, for the visit's machine: every axis the visit runs a test on, its soft limits, LinuxCNC's INI file.

:class:`VisitConnection` is a part of :class:`~axiscal.workbench.visit.Workbench`. It connects the
instrument and the controller (:func:`axiscal.workbench.connection.connect`) for the linear axes the
visit's tests run on, keeps what they told (the soft limits of each axis: the controller's, the INI
file's for LinuxCNC, the machine's travels for the virtual machine) and holds a plan against those
limits. It uses the workbench's ``saved``, ``visit``, ``folder``, ``connection``, ``_lock``,
``_save``, ``_tests``, ``_axes`` and ``machine_file``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from axiscal.units import MM
from axiscal.workbench.connection import SIM_RATE_HZ, connect, is_virtual, serial_ports
from axiscal.workbench.forms import FormErrors, checked
from axiscal.workbench.machines import machine_axes

__all__ = ["VisitConnection"]


class VisitConnection:
    """The visit's connection: the devices' lights and what they told, each axis's soft limits.

    Attributes
    ----------
    (none of its own)
        It works on the :class:`~axiscal.workbench.visit.Workbench` it is a part of: what was told
        is ``connection`` (a :class:`~axiscal.workbench.connection.Connection`).
    """

    # -- 4. connect --------------------------------------------------------------------------------
    def ports(self) -> list[dict[str, Any]]:
        """The computer's serial ports (device, description, USB ids), listed now."""
        return serial_ports()

    def _moved_axes(self) -> tuple[str, ...]:
        """The linear axes the visit runs a test on (the machine's linear axes while no visit is open)."""
        if self.saved is not None:
            run = [t["axis"] for t in self._tests() if t["source"] == "run"]
            if run:
                return tuple(dict.fromkeys(run))
        return tuple(a["axis"] for a in self._axes() if not a["rotary"]) or ("X",)

    def connect(self, data: Any) -> dict[str, Any]:
        """Check the Connect form, open the instrument and the controller, and say what they told.

        Both specs and LinuxCNC's INI file are checked first; the answer has the lights, the reading,
        the position and what each device told, with the soft limits of each axis the visit runs a test on.
        """
        form = checked("connect", data)
        axes = self._moved_axes()
        c = connect(form.instrument, form.controller, axes=axes, ini=form.ini or None, machine=self.machine_file())
        if is_virtual(c.instrument, c.controller):  # the virtual machine is the visit's machine, every axis of it
            described = machine_axes(self.machine_file()) if self.folder is None else {"name": self.visit.machine} | {
                "axes": self._axes()}
            travels = ", ".join(f"{a['axis']} {a['start']:g} to {a['end']:g} {a['unit']}" for a in described["axes"])
            c = replace(c, description=f"virtual laser ({SIM_RATE_HZ:g} Hz) on the virtual {described['name']}: {travels}",
                        controller_told=c.controller_told + (("machine", described["name"]), ("axes", travels), (
                            "soft limits", "none: the virtual machine runs a plan's overrun beyond the travels too")))
        elif c.controller.lower() == "sim" and not c.refused:  # each run's virtual controller: its axis's travel
            moved = [a for a in self._axes() if a["axis"] in axes]
            c = replace(c, controller_told=tuple(t for t in c.controller_told if not t[0].startswith("soft limits")) + tuple(
                (f"soft limits {a['axis']}", f"{a['start']:g} to {a['end']:g} mm") for a in moved),
                limits=tuple((a["axis"], a["start"] * MM, a["end"] * MM) for a in moved))
        self.connection = c
        if self.saved is not None:
            with self._lock:
                self.saved.connection = {"instrument": form.instrument, "controller": form.controller, "ini": form.ini}
                self._save()
        return {"instrument": c.instrument, "controller": c.controller,
                "lights": {"instrument": c.instrument_state, "controller": c.controller_state},
                "description": c.description, "reading_mm": c.reading_m / MM, "position_mm": c.position_m / MM,
                "told": {"instrument": [list(t) for t in c.instrument_told], "controller": [list(t) for t in c.controller_told]},
                "refused": c.refused}

    def _within_told_limits(self, form: Any, moves: np.ndarray) -> None:
        """FormErrors naming the field that takes a plan's moves beyond the soft limits the controller told at Connect."""
        limits = None if self.connection is None else self.connection.limits_of(form.axis)
        if limits is None:
            return
        low, high = limits
        first, last = float(np.min(moves)), float(np.max(moves))
        if low - 1e-9 <= first and last <= high + 1e-9:
            return
        where = (f"the moves reach {first / MM:g} to {last / MM:g} mm, beyond the controller's soft limits of {form.axis}"
                 f" ({low / MM:g} to {high / MM:g} mm, told at Connect)")
        if form.start_mm * MM < low - 1e-9 or form.end_mm * MM > high + 1e-9:
            raise FormErrors({name: where for name in ("start_mm", "end_mm")
                              if not low - 1e-9 <= getattr(form, name) * MM <= high + 1e-9})
        raise FormErrors({"overrun_mm": where})
