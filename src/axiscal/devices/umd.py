"""The open µMD readout of HP/Agilent heterodyne lasers (µMD1 firmware up to v60, µMD2 firmware 2.x).

Sources: the µMD1 and µMD2 manuals (repairfaq.org/sam/uMD1, /uMD2) and the open firmware
(lasersam594/Micro-Measurement-Display-*). The readout streams over USB CDC serial (115200 8N1, the µMD2
ignores the rate), one sample a line ending ``\\r\\n``, space-separated decimal integers: 8 fields (one
axis) or 16 (three axes); any other line, and lines starting ``!``, are not samples (the vendor's program
ignores them too).

====  ==========================================================================
field meaning
====  ==========================================================================
0     REF count: REF cycles in the sample period
1     MEAS1 count
2     D1: cumulative displacement count
3     V1 = D1(n) - D1(n-1)
4     Phase1: the sub-count fraction
5     sequence number, +1 a sample
6, 7  LowSpeedCode, LowSpeedData: one slow value a sample
8-11  MEAS2, D2, V2, Phase2
12-15 MEAS3, D3, V3, Phase3
====  ==========================================================================

Length as the vendor's program computes it, nanometres::

    µMD1:  nm = (D - Phase/256) x lambda/2 / multiplier           D = REF total - MEAS total
    µMD2:  nm = -(D - Phase/65536) / c x lambda/2 / multiplier    D = MEAS - REF (the opposite sign)

with lambda the vacuum wavelength (632.991372 nm by default), the multiplier 1 for a linear
retroreflector, 2 for a plane mirror, 4 for a high-resolution plane mirror, and c the counts per cycle
(code 20 >> 8: 2 when both edges are counted). A µMD1 phase is 0..511 and valid when
``(P & 0x7E00) == 0`` (a value of 256 or more goes with D one higher, which the formula takes as it
is); with an error flag set (0x4000, 0x2000/0x1000, 0x800, 0x400/0x200) D alone is used. A µMD2 sends
a 16-bit phase unless code 112 has its 8-bit flag (0x2) set (then -128..127 over 256).

A line with a zero REF or MEAS count is not a reading (the beam or the head was lost: a lost MEAS alone
makes D run away); a jump in the sequence number is a gap (samples lost), a repeat is a repeat. Both are
faults with their time; the sample time is ``sequence / fs`` with fs from code 8 (the instrument's
clock), never the host's clock.

LowSpeed codes: 3 / 4 temperature 1 / 2 (degC x 100), 5 pressure (Pa), 6 relative humidity (% x 10),
8 sample frequency (Hz x 100), 10 firmware version (µMD1 up to 60; µMD2 2xx, with the sub-version in
the upper 16 bits), 20 counts per cycle << 8 + homodyne axes, 112 firmware flags; -1 = sensor absent.
Code 3 is the air temperature; code 4 is a material temperature only when the user says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from axiscal.devices.base import AIR_CHANNELS, READING_CHANNEL, InstrumentSource, Samples
from axiscal.errors import AxiscalError

__all__ = ["HENE_VACUUM_WAVELENGTH_M", "UmdSettings", "UmdDecoder", "UmdSource", "umd_line", "UmdState"]

#: vacuum wavelength of the HP/Agilent 5501/5517/5519 HeNe lasers, metres (the µMD programs' default)
HENE_VACUUM_WAVELENGTH_M = 632.991372e-9

_PHASE_FLAGS_UMD1 = 0x7E00
#: fields of each measurement axis: (MEAS, D, Phase)
_AXIS_FIELDS = {1: (1, 2, 4), 2: (8, 9, 11), 3: (12, 13, 15)}
#: lines held while the stream has not yet said its rate and firmware (µMD codes cycle every 32 samples)
_HOLD_LINES = 256


@dataclass(frozen=True)
class UmdSettings:
    """How a µMD stream is read.

    Attributes
    ----------
    wavelength_m : float, metres
        Vacuum wavelength of the laser (default 632.991372 nm).
    optics_multiplier : int
        1 linear retroreflector, 2 plane mirror, 4 high-resolution plane mirror.
    channel : int
        The measurement axis read: 1, 2 or 3.
    rate_hz : float or None, Hz
        Sample rate when the stream does not say it (code 8 wins when it does).
    version : int or None
        1 or 2; None: told by the firmware code (10) the stream sends.
    material_temperature_code : int or None
        The LowSpeed code that carries a material temperature (4), if one does.
    """

    wavelength_m: float = HENE_VACUUM_WAVELENGTH_M
    optics_multiplier: int = 1
    channel: int = 1
    rate_hz: float | None = None
    version: int | None = None
    material_temperature_code: int | None = None

    def __post_init__(self) -> None:
        if not (isinstance(self.wavelength_m, float) and 100e-9 < self.wavelength_m < 20e-6):
            raise AxiscalError(f"wavelength must be a vacuum wavelength between 100 and 20000 nm, not {self.wavelength_m!r} m")
        if self.optics_multiplier not in (1, 2, 4):
            raise AxiscalError(f"optics multiplier must be 1, 2 or 4, not {self.optics_multiplier!r}")
        if self.channel not in (1, 2, 3):
            raise AxiscalError(f"channel must be 1, 2 or 3, not {self.channel!r}")
        if self.rate_hz is not None and not (math.isfinite(self.rate_hz) and 0 < self.rate_hz <= 1e6):
            raise AxiscalError(f"rate must be a sample rate between 0 and 1e6 Hz, not {self.rate_hz!r}")
        if self.version not in (None, 1, 2):
            raise AxiscalError(f"µMD version must be 1 or 2, not {self.version!r}")
        if self.material_temperature_code not in (None, 3, 4):
            raise AxiscalError(f"material temperature code must be 4 (or 3), not {self.material_temperature_code!r}")


@dataclass
class UmdState:
    """What the stream has said of itself so far (filled from the LowSpeed codes).

    Attributes
    ----------
    rate_hz : float or None
        Sample rate (code 8).
    version, firmware : int or None
        1 or 2, and the firmware number (code 10).
    counts_per_cycle, homodyne_axes : int
        Code 20.
    counts_told : bool
        Whether code 20 has come.
    phase_8bit : bool
        Code 112's flag.
    air_temperature_c, material_temperature_c, pressure_pa, humidity_pct : float
        The last sensor values (NaN when absent).
    """

    rate_hz: float | None = None
    version: int | None = None
    firmware: int | None = None
    counts_per_cycle: int = 1
    counts_told: bool = False
    homodyne_axes: int = 0
    phase_8bit: bool = False
    air_temperature_c: float = math.nan
    material_temperature_c: float = math.nan
    pressure_pa: float = math.nan
    humidity_pct: float = math.nan


def _integers(line: bytes) -> list[int] | None:
    fields = line.split()
    if len(fields) not in (8, 16):
        return None
    try:
        return [int(f) for f in fields]
    except ValueError:
        return None


class UmdDecoder:
    """Turns µMD bytes into samples of ``reading_mm`` and the air channels, with faults.

    Parameters
    ----------
    settings : UmdSettings
    fault : callable
        Called with (time_s, message) for every fault (a gap, a repeat, a line that is not a reading).

    Notes
    -----
    Until the stream has said its sample rate (code 8) and firmware (code 10), or ``rate_hz`` and
    ``version`` were given, lines are held (at most 256; then the settings given are used, or the
    stream is refused in one line).
    """

    channels = (READING_CHANNEL,) + AIR_CHANNELS

    def __init__(self, settings: UmdSettings, fault):
        self.settings = settings
        self.state = UmdState(version=settings.version)
        self._fault = fault
        self._tail = b""
        self._held: list[list[int]] = []
        self._last_sequence: int | None = None
        self.lines = 0
        self.ignored = 0

    # ------------------------------------------------------------------------------------------
    def _low_speed(self, code: int, data: int) -> None:
        s = self.state
        if data == -1 and code in (3, 4, 5, 6):
            value = math.nan
        else:
            value = float(data)
        if code == 3:
            s.air_temperature_c = value / 100.0
        elif code == 4:
            s.material_temperature_c = value / 100.0
        elif code == 5:
            s.pressure_pa = value
        elif code == 6:
            s.humidity_pct = value / 10.0
        elif code == 8 and data > 0:
            s.rate_hz = data / 100.0
        elif code == 10 and data > 0:
            s.firmware = data & 0xFFFF
            if self.settings.version is None:
                s.version = 2 if s.firmware >= 100 else 1
        elif code == 20 and data > 0:
            s.counts_per_cycle = max(1, data >> 8)
            s.counts_told = True
            s.homodyne_axes = data & 0xFF
        elif code == 112:
            s.phase_8bit = bool(data & 0x2)

    def _ready(self) -> bool:
        s = self.state
        # a µMD2 says how many edges it counts a cycle (code 20) right after its rate: wait for it too
        return ((s.rate_hz is not None or self.settings.rate_hz is not None) and s.version is not None
                and (s.version == 1 or s.counts_told or self.settings.version is not None))

    def _settle(self) -> None:
        """After too many held lines: use the settings given, or refuse."""
        s = self.state
        if s.rate_hz is None and self.settings.rate_hz is None:
            raise AxiscalError(f"the µMD stream has not said its sample rate (code 8) in {_HOLD_LINES} samples: give rate_hz")
        if s.version is None:
            raise AxiscalError(f"the µMD stream has not said its firmware (code 10) in {_HOLD_LINES} samples: give umd_version 1 or 2")
        if s.version == 2 and not s.counts_told:
            s.counts_per_cycle = 2  # the µMD2 firmware's own default (both edges counted)
            s.counts_told = True

    def _length_m(self, f: list[int]) -> tuple[float, str | None]:
        """The length of one sample, metres, or NaN and why it is not a reading."""
        st, se = self.state, self.settings
        meas_i, d_i, p_i = _AXIS_FIELDS[se.channel]
        if se.channel > 1 and len(f) < 16:
            return math.nan, f"an 8-field line holds no channel {se.channel}"
        if st.homodyne_axes == 0 and (f[0] == 0 or f[meas_i] == 0):
            lost = "REF" if f[0] == 0 else f"MEAS{se.channel}"
            return math.nan, f"not a reading: {lost} count is 0 (beam or head lost)"
        d, p = f[d_i], f[p_i]
        if st.version == 1:
            counts = float(d) if (p & _PHASE_FLAGS_UMD1) or p < 0 else d - p / 256.0
            per_cycle = 1
        else:
            scale = 256.0 if st.phase_8bit else 65536.0
            counts = -(d - p / scale)
            per_cycle = st.counts_per_cycle if st.counts_told else 2  # the µMD2 firmware counts both edges by default
        return counts / per_cycle * se.wavelength_m / 2.0 / se.optics_multiplier, None

    def _sample(self, f: list[int], out_t: list, out_rows: list, out_bad: list) -> None:
        st = self.state
        rate = st.rate_hz or self.settings.rate_hz
        sequence = f[5]
        t = sequence / rate
        if self._last_sequence is not None:
            step = sequence - self._last_sequence
            if step == 0:
                self._fault(t, f"sequence {sequence} repeated")
                return
            if step != 1:
                if step > 1:
                    self._fault(t, f"sequence gap: {step - 1} samples lost before sequence {sequence}")
                else:
                    self._fault(t, f"sequence went back from {self._last_sequence} to {sequence}")
        self._last_sequence = sequence
        length, problem = self._length_m(f)
        if problem is not None:
            self._fault(t, problem)
        material = st.material_temperature_c if self.settings.material_temperature_code == 4 else (
            st.air_temperature_c if self.settings.material_temperature_code == 3 else math.nan)
        out_t.append(t)
        out_rows.append((length * 1e3, st.air_temperature_c, st.pressure_pa, st.humidity_pct, material))
        out_bad.append(problem is not None)

    def feed(self, data: bytes) -> Samples:
        """Decode the bytes that arrived; a partial last line is kept for the next call.

        Parameters
        ----------
        data : bytes

        Returns
        -------
        Samples
            ``reading_mm`` (NaN where the line is not a reading, marked malformed) and the air channels.

        Raises
        ------
        AxiscalError
            When the stream never says its rate or firmware and the settings do not give them.
        """
        lines = (self._tail + data).split(b"\n")
        self._tail = lines.pop()
        if len(self._tail) > 4096:
            self._tail = b""
            self.ignored += 1
        out_t: list[float] = []
        out_rows: list[tuple] = []
        out_bad: list[bool] = []
        for raw in lines:
            line = raw.strip(b"\r\n \t")
            if not line or line.startswith(b"!"):
                continue
            fields = _integers(line)
            if fields is None:
                self.ignored += 1
                continue
            self.lines += 1
            self._low_speed(fields[6], fields[7])
            self._held.append(fields)
            if not self._ready():
                if len(self._held) < _HOLD_LINES:
                    continue
                self._settle()
            for held in self._held:
                self._sample(held, out_t, out_rows, out_bad)
            self._held = []
        return Samples.of(out_t, out_rows, out_bad, len(self.channels))


class UmdSource(InstrumentSource):
    """A µMD readout on a serial port (or any link), as a capture's source.

    Parameters
    ----------
    link : a link of :mod:`axiscal.devices.links`
    settings : UmdSettings
    description : str

    Attributes
    ----------
    channels : tuple of str
        ``reading_mm`` then the air channels.
    """

    def __init__(self, link, settings: UmdSettings, description: str):
        super().__init__(link, description)
        self.decoder = UmdDecoder(settings, self._fault)
        self.channels = self.decoder.channels

    def _decode(self, data: bytes) -> Samples:
        return self.decoder.feed(data)


def umd_line(*, version: int, sequence: int, length_m: float, low_code: int = 0, low_data: int = 0,
             wavelength_m: float = HENE_VACUUM_WAVELENGTH_M, optics_multiplier: int = 1, counts_per_cycle: int = 2,
             ref: int = 2_000, meas: int | None = None, three_axes: bool = False, phase_flags: int = 0) -> bytes:
    """One µMD line for a length, as the firmware writes it (the simulators' encoder).

    Parameters
    ----------
    version : int, keyword-only
        1 or 2.
    sequence : int, keyword-only
    length_m : float, metres, keyword-only
        The optical length to encode on channel 1 (and 2, 3 when ``three_axes``).
    low_code, low_data : int, keyword-only
        The LowSpeed pair of this sample.
    wavelength_m, optics_multiplier, counts_per_cycle : keyword-only
        As the reader takes them (counts per cycle applies to a µMD2).
    ref, meas : int, keyword-only
        REF and MEAS counts of the sample (0 for a lost beam); MEAS defaults to REF.
    three_axes : bool, keyword-only
        A 16-field line.
    phase_flags : int, keyword-only
        µMD1 error flags OR-ed into the phase.

    Returns
    -------
    bytes
        The line with its ``\\r\\n``.
    """
    meas = ref if meas is None else meas
    counts = length_m * optics_multiplier * 2.0 / wavelength_m
    if version == 1:
        d = math.floor(counts)
        phase = int(round((d - counts) * 256.0))  # counts = D - Phase/256, Phase in 0..255 (or 256.. with D one higher)
        if phase < 0:
            d += 1
            phase = int(round((d - counts) * 256.0))
        phase |= phase_flags
    else:
        counts2 = -counts * counts_per_cycle  # D = MEAS - REF: the opposite sign
        d = math.floor(counts2)
        phase = int(round((d - counts2) * 65536.0))
        if phase < -32768:
            d += 1
            phase = int(round((d - counts2) * 65536.0))
    fields = [ref, meas, d, 0, phase, sequence, low_code, low_data]
    if three_axes:
        fields += [meas, d, 0, phase, meas, d, 0, phase]
    return (" ".join(str(int(v)) for v in fields) + "\r\n").encode()
