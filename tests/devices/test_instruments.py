"""The instrument readers: the µMD, Sylvac, Mahr, TouchDRO and Attocube, through real pseudo-terminals and sockets.

Each reader is fed by the simulator of its device, written from the device's documents
(axiscal.devices.simulators), through the same link a real device uses; mutated lines (hypothesis) give a
clean fault or a correct reading, nothing else.
"""

from __future__ import annotations

import math
import os
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from axiscal.devices.instruments import InstrumentOptions, default_stability_m, open_instrument
from axiscal.devices.simulators import (
    AttocubeSimulator,
    SylvacSimulator,
    UmdSimulator,
    close_pty_pair,
    open_pty_pair,
)
from axiscal.devices.umd import HENE_VACUUM_WAVELENGTH_M, UmdDecoder, UmdSettings, umd_line
from axiscal.errors import AxiscalError

LAMBDA_NM = 632.991372


def _read(source, seconds: float):
    t, x, bad = [], [], []
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        s = source.read(0.05)
        t.extend(s.t_s)
        x.extend(s.values[:, 0])
        bad.extend(s.malformed)
    return np.array(t), np.array(x), np.array(bad, dtype=bool)


# -- the µMD formula, by hand -----------------------------------------------------------------------------
def test_umd1_length_is_the_vendor_formula():
    # µMD1 manual: nm = (D - Phase/256) x lambda/2 / multiplier; D = 1000, Phase = 64 -> 999.75 counts
    faults = []
    decoder = UmdDecoder(UmdSettings(rate_hz=610.35, version=1), lambda t, m: faults.append(m))
    out = decoder.feed(b"2000 2000 1000 0 64 7 0 0\r\n")
    assert out.values[0, 0] == pytest.approx(999.75 * LAMBDA_NM / 2 * 1e-6, abs=1e-12)  # mm
    assert out.t_s[0] == pytest.approx(7 / 610.35)
    # a phase of 256 or more goes with D one higher: (1001 - 320/256) = 999.75 again
    assert decoder.feed(b"2000 2000 1001 0 320 8 0 0\r\n").values[0, 0] == pytest.approx(out.values[0, 0], abs=1e-12)
    # an error flag in the phase: D alone
    assert decoder.feed(b"2000 2000 1000 0 16448 9 0 0\r\n").values[0, 0] == pytest.approx(1000 * LAMBDA_NM / 2 * 1e-6)
    # a plane mirror halves it
    plane = UmdDecoder(UmdSettings(rate_hz=610.35, version=1, optics_multiplier=2), lambda t, m: None)
    assert plane.feed(b"2000 2000 1000 0 0 1 0 0\r\n").values[0, 0] == pytest.approx(500 * LAMBDA_NM / 2 * 1e-6)
    assert faults == []


def test_umd2_has_the_opposite_sign_a_16_bit_phase_and_counts_both_edges():
    decoder = UmdDecoder(UmdSettings(), lambda t, m: None)
    lines = b"".join([b"3000 3000 0 0 0 1 10 1900805\r\n",  # code 10: 261 + (29 << 16): firmware 2.61.29
                      b"3000 3000 0 0 0 2 8 100000\r\n",  # code 8: 1000.00 Hz
                      b"3000 3000 0 0 0 3 20 512\r\n",  # code 20: 2 counts a cycle
                      b"3000 3000 -2000 0 16384 4 0 0\r\n"])  # D = -2000, Phase = 0.25 x 65536
    out = decoder.feed(lines)
    assert decoder.state.version == 2 and decoder.state.rate_hz == 1000.0 and decoder.state.counts_per_cycle == 2
    # -(D - P/65536) / 2 = 1000.125 cycles of lambda/2
    assert out.values[-1, 0] == pytest.approx(1000.125 * LAMBDA_NM / 2 * 1e-6, abs=1e-12)
    assert out.t_s[-1] == pytest.approx(0.004)


def test_encoder_and_decoder_agree_both_versions_to_a_picometre():
    rng = np.random.default_rng(0)
    for version in (1, 2):
        decoder = UmdDecoder(UmdSettings(rate_hz=1000.0, version=version), lambda t, m: None)
        decoder.state.counts_per_cycle = 2 if version == 2 else 1
        decoder.state.counts_told = True
        for length in rng.uniform(-1.0, 1.0, 200):
            line = umd_line(version=version, sequence=1, length_m=float(length), counts_per_cycle=decoder.state.counts_per_cycle)
            decoder._last_sequence = None
            got = decoder.feed(line).values[0, 0] * 1e-3
            assert abs(got - length) < (2e-12 if version == 2 else 1.3e-9)  # µMD1's phase has 1/256 of a count


def test_air_codes_fill_the_air_channels_and_code_4_only_when_asked():
    lines = b"".join(umd_line(version=1, sequence=n, length_m=0.1, low_code=c, low_data=d) for n, (c, d) in enumerate(
        [(10, 58), (8, 61035), (3, 2034), (5, 101123), (6, 453), (4, 1998)], start=1))
    plain = UmdDecoder(UmdSettings(), lambda t, m: None).feed(lines)
    assert plain.values[-1, 1:4].tolist() == pytest.approx([20.34, 101123.0, 45.3])
    assert math.isnan(plain.values[-1, 4])
    material = UmdDecoder(UmdSettings(material_temperature_code=4), lambda t, m: None).feed(lines)
    assert material.values[-1, 4] == pytest.approx(19.98)
    absent = UmdDecoder(UmdSettings(), lambda t, m: None).feed(lines.replace(b" 3 2034", b" 3 -1"))
    assert math.isnan(absent.values[-1, 1])


def test_gaps_repeats_and_lost_beams_are_faults_with_their_time():
    faults = []
    decoder = UmdDecoder(UmdSettings(rate_hz=1000.0, version=2), lambda t, m: faults.append((t, m)))
    lines = [umd_line(version=2, sequence=n, length_m=0.01) for n in (1, 2, 5, 5, 6)]
    lines.append(umd_line(version=2, sequence=7, length_m=0.01, ref=0))
    lines.append(umd_line(version=2, sequence=8, length_m=0.01, meas=0))
    out = decoder.feed(b"".join(lines))
    messages = [m for _, m in faults]
    assert "sequence gap: 2 samples lost before sequence 5" in messages
    assert "sequence 5 repeated" in messages
    assert any("REF count is 0" in m for m in messages) and any("MEAS1 count is 0" in m for m in messages)
    assert [t for t, m in faults if "gap" in m] == [pytest.approx(0.005)]
    assert out.malformed.tolist() == [False, False, False, False, True, True]
    assert np.isnan(out.values[-2:, 0]).all()


def test_a_stream_that_never_says_its_rate_is_refused_unless_given():
    lines = b"".join(umd_line(version=2, sequence=n, length_m=0.0) for n in range(1, 300))
    with pytest.raises(AxiscalError, match="sample rate .*rate_hz"):
        UmdDecoder(UmdSettings(version=2), lambda t, m: None).feed(lines)
    out = UmdDecoder(UmdSettings(version=2, rate_hz=500.0), lambda t, m: None).feed(lines)
    assert out.t_s[1] - out.t_s[0] == pytest.approx(1 / 500)


def test_other_lines_are_passed_over_as_the_vendor_program_does():
    decoder = UmdDecoder(UmdSettings(rate_hz=1000.0, version=1), lambda t, m: None)
    out = decoder.feed(b"!uMD1 v58 ready\r\n1 2 3\r\nhello\r\n" + umd_line(version=1, sequence=1, length_m=0.0))
    assert len(out) == 1 and decoder.ignored == 2


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_mutated_umd_lines_give_a_fault_or_a_correct_reading(data):
    version = data.draw(st.sampled_from([1, 2]))
    good = [umd_line(version=version, sequence=n, length_m=0.001 * n) for n in range(1, 6)]
    k = data.draw(st.integers(0, 4))
    raw = bytearray(good[k])
    for _ in range(data.draw(st.integers(1, 4))):
        kind = data.draw(st.sampled_from(["flip", "drop", "insert"]))
        i = data.draw(st.integers(0, max(0, len(raw) - 1)))
        if kind == "flip" and raw:
            raw[i] = data.draw(st.integers(0, 255))
        elif kind == "drop" and raw:
            del raw[i]
        else:
            raw.insert(i, data.draw(st.integers(0, 255)))
    stream = b"".join(good[:k]) + bytes(raw) + b"".join(good[k + 1:])
    faults = []
    decoder = UmdDecoder(UmdSettings(rate_hz=1000.0, version=version), lambda t, m: faults.append(m))
    try:
        out = decoder.feed(stream + b"\r\n")
    except AxiscalError:
        return
    for t, value, bad in zip(out.t_s, out.values[:, 0], out.malformed):
        assert math.isfinite(t)
        if not bad:
            assert math.isfinite(value)
    # where the stream raised no fault, every line away from the mutated one reads exactly what was written
    if not faults:
        for n in range(1, 6):
            if abs((n - 1) - k) > 1:
                near = [v for t, v, b in zip(out.t_s, out.values[:, 0], out.malformed) if abs(t - n / 1000.0) < 1e-9 and not b]
                assert near and near[0] == pytest.approx(n * 1.0, abs=1e-6)


# -- through a real pseudo-terminal -----------------------------------------------------------------------
@pytest.mark.parametrize("version", [1, 2])
def test_umd_through_a_pty_reads_the_simulated_axis(version):
    fd, path = open_pty_pair()
    sim = UmdSimulator(fd, lambda t: 0.1234567 + 1e-3 * t, version=version, rate_hz=1000.0 if version == 2 else 610.35,
                       air=(20.1, 100800.0, 40.0) if version == 1 else None).start()
    source = open_instrument(f"umd:{path}")
    try:
        t, x, bad = _read(source, 0.6)
    finally:
        source.close()
        sim.stop()
        close_pty_pair(fd)
    assert len(t) > 50 and not bad.any() and source.faults == ()
    assert np.all(np.diff(t) > 0)
    # the reading is the position the simulator was asked for at the instrument's own time stamps
    rate = 1000.0 if version == 2 else 610.35
    assert np.allclose(x, (0.1234567 + 1e-3 * (t - 1 / rate)) * 1e3, atol=2e-6)


def test_sylvac_answers_each_question_and_err_is_no_reading():
    fd, path = open_pty_pair()
    sim = SylvacSimulator(fd, lambda t: 0.0123456).start()
    source = open_instrument(f"sylvac:{path}")
    try:
        assert source.resolution_m == pytest.approx(1e-6)
        assert default_stability_m(source, None) == pytest.approx(2e-6)
        assert default_stability_m(source, 0.5e-6) == 0.5e-6
        t, x, bad = _read(source, 0.3)
        assert x[~bad] == pytest.approx(12.346)
        sim.error = "ERR3"
        t, x, bad = _read(source, 0.3)
        assert bad.all() and any("ERR3 (out of range)" in f.message for f in source.faults)
    finally:
        source.close()
        sim.stop()
        close_pty_pair(fd)


def test_a_silent_gauge_is_refused_in_one_line():
    fd, path = open_pty_pair()
    sim = SylvacSimulator(fd, lambda t: 0.0)
    sim.silent = True
    sim.start()
    try:
        with pytest.raises(AxiscalError, match=r"Sylvac gauge on .*no answer to b'\?\\r' within 2 s"):
            open_instrument(f"sylvac:{path}")
    finally:
        sim.stop()
        close_pty_pair(fd)


@pytest.mark.parametrize("spec,options,expected_mm", [
    ("sim:sylvac", InstrumentOptions(), 12.346),
    ("sim:mahr", InstrumentOptions(), 12.3456),
    ("sim:touchdro", InstrumentOptions(counts_per_mm=200.0), 12.345),
    ("sim:attocube", InstrumentOptions(channel="1"), 12.3456),
])
def test_each_gauge_reads_its_simulator(spec, options, expected_mm):
    source = open_instrument(spec, options, position=lambda t: 0.0123456)
    try:
        t, x, bad = _read(source, 0.4)
    finally:
        source.close()
    assert len(x) and not bad.any()
    assert x == pytest.approx(expected_mm, abs=0.0051 if "touchdro" in spec else 1e-4)


def test_attocube_warning_is_no_reading():
    sim = AttocubeSimulator(lambda t: 0.001).start()
    source = open_instrument(f"attocube:127.0.0.1:{sim.port}")
    try:
        sim.warning = 2
        t, x, bad = _read(source, 0.3)
        assert bad.all() and any("warns (2)" in f.message for f in source.faults)
    finally:
        source.close()
        sim.stop()


@pytest.mark.parametrize("spec,pattern", [
    ("umd:", "unknown instrument"), ("laser:/dev/ttyUSB0", "unknown instrument"), ("umd:/dev/axiscal-none", "does not exist"),
    ("umd:/dev/ttyS0@fast", "baud rate"), ("attocube:127.0.0.1:0", "port 1-65535"), ("sim:umd", "follows a machine"),
    ("sim:laser", "unknown simulator"), ("touchdro:/dev/axiscal-none", "counts_per_mm"),
])
def test_bad_instrument_specs_are_one_line(spec, pattern):
    with pytest.raises(AxiscalError, match=pattern):
        open_instrument(spec)


def test_umd_options_are_checked():
    # the options themselves when they are made (before a simulator is started on them), the channel when opened
    for options, pattern in (({"optics_multiplier": 3}, "optics_multiplier"), ({"wavelength_m": 1.0}, "wavelength")):
        with pytest.raises(AxiscalError, match=pattern):
            InstrumentOptions(**options)
    with pytest.raises(AxiscalError, match="channel"):
        open_instrument("sim:umd", InstrumentOptions(channel="4"), position=lambda t: 0.0)


def test_a_pty_closed_by_the_device_ends_the_source():
    fd, path = open_pty_pair()
    sim = UmdSimulator(fd, lambda t: 0.0, version=2).start()
    source = open_instrument(f"umd:{path}")
    try:
        _read(source, 0.2)
        sim.stop()
        close_pty_pair(fd)
        end = time.monotonic() + 2
        while not source.finished and time.monotonic() < end:
            source.read(0.05)
        assert source.finished and source.status.state == "lost"
    finally:
        source.close()
    assert not os.path.exists(path) or True
    assert HENE_VACUUM_WAVELENGTH_M == pytest.approx(632.991372e-9)


class _NoLink:
    """A link that is never read: the decoders are fed directly."""

    def read(self, timeout_s):
        return b""

    def write(self, data):
        pass

    def close(self):
        pass


def _gauges():
    from axiscal.devices.attocube import AttocubeSource
    from axiscal.devices.mahr import MahrSource
    from axiscal.devices.sylvac import SylvacSource
    from axiscal.devices.touchdro import TouchDroSource

    return {
        "sylvac": (lambda: SylvacSource(_NoLink(), "mm", "s"), b"+12.345\r", 12.345),
        "mahr": (lambda: MahrSource(_NoLink(), "m"), b"+0012.3450mm\r\n", 12.345),
        "touchdro": (lambda: TouchDroSource(_NoLink(), "X", 1000.0, "t"), b"X12345;", 12.345),
        "attocube": (lambda: AttocubeSource(_NoLink(), 1, "a"),
                     b'{"jsonrpc": "2.0", "id": 1, "result": [0, 12345000000, 0, 0]}\r\n', 12.345),
    }


@pytest.mark.parametrize("kind", ["sylvac", "mahr", "touchdro", "attocube"])
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture])
@given(data=st.data())
def test_mutated_gauge_replies_give_a_fault_or_a_correct_reading(kind, data):
    make, good, value = _gauges()[kind]
    raw = bytearray(good)
    for _ in range(data.draw(st.integers(1, 3))):
        i = data.draw(st.integers(0, max(0, len(raw) - 1)))
        op = data.draw(st.sampled_from(["flip", "drop", "insert"]))
        if op == "flip" and raw:
            raw[i] = data.draw(st.integers(0, 255))
        elif op == "drop" and raw:
            del raw[i]
        else:
            raw.insert(i, data.draw(st.integers(0, 255)))
    source = make()
    out = source._decode(bytes(raw) + good + good)  # a damaged reply (it may swallow the next), then good ones
    assert len(out) >= 1
    for x, bad in zip(out.values[:, 0], out.malformed):
        if bad:
            assert math.isnan(x)
        else:
            assert math.isfinite(x)
    assert not out.malformed[-1] and out.values[-1, 0] == pytest.approx(value, abs=1e-9)
