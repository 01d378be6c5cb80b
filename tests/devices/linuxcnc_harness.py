"""A headless LinuxCNC simulator for the tests, with a simulated µMD laser reading its X joint.

LinuxCNC 2.9 (Debian's ``linuxcnc-uspace``) runs for real: POSIX non-realtime, ``DISPLAY = linuxcncrsh``
(TCP 5007), ``core_sim.hal`` (the commands loop back as feedback), trivkins, soft limits from the INI.
rtapi_app refuses root, so as root it runs as an ordinary user (``runuser -u axiscal-sim``, the user
``make`` creates). A HAL ``sampler`` streams ``joint.0.motor-pos-cmd`` (which carries the joint's
compensation, ``COMP_FILE``) at the servo rate (1 kHz) through ``halsampler -t``; each sample becomes a
µMD2 line (sequence = the sample's number: the instrument's clock) of the carriage's position, the
motor position plus a known mechanical error, written to a real pseudo-terminal that ``umd:/dev/pts/N``
reads. ``restart(comp)`` stops LinuxCNC, starts it with the compensation file and homes it again.
"""

from __future__ import annotations

import os
import pwd
import shutil
import signal
import socket
import subprocess
import threading
import time
from pathlib import Path

from axiscal.devices.simulators import UmdSimulator, close_pty_pair, open_pty_pair

USER = "axiscal-sim"
PORT = 5007
TRAVEL_MM = (-1.0, 201.0)

INI = """[EMC]
VERSION = 1.1
MACHINE = axiscal-test-sim
[DISPLAY]
DISPLAY = linuxcncrsh
[TASK]
TASK = milltask
CYCLE_TIME = 0.001
[RS274NGC]
PARAMETER_FILE = sim.var
[EMCMOT]
EMCMOT = motmod
COMM_TIMEOUT = 1.0
BASE_PERIOD = 0
SERVO_PERIOD = 1000000
[EMCIO]
EMCIO = io
CYCLE_TIME = 0.100
TOOL_TABLE = sim.tbl
[HAL]
HALFILE = LIB:core_sim.hal
HALFILE = sampler.hal
[TRAJ]
COORDINATES = X Y Z
LINEAR_UNITS = mm
ANGULAR_UNITS = degree
DEFAULT_LINEAR_VELOCITY = 50
MAX_LINEAR_VELOCITY = 200
NO_FORCE_HOMING = 1
[KINS]
KINEMATICS = trivkins
JOINTS = 3
{axes}
"""
AXIS = """[AXIS_{letter}]
MAX_VELOCITY = 200
MAX_ACCELERATION = 2000
MIN_LIMIT = {low}
MAX_LIMIT = {high}
[JOINT_{joint}]
TYPE = LINEAR
HOME = 0
MAX_VELOCITY = 200
MAX_ACCELERATION = 2000
MIN_LIMIT = {low}
MAX_LIMIT = {high}
FERROR = 1
MIN_FERROR = 1
HOME_SEARCH_VEL = 0
HOME_SEQUENCE = 0
{comp}"""
SAMPLER = """loadrt sampler depth=8192 cfg=f
addf sampler.0 servo-thread
net Xpos => sampler.0.pin.0
"""


def mechanical_error_mm(x_mm: float) -> float:
    """The simulated axis' positioning error, mm: a 40 um/200 mm scale error and a 3 um, 47 mm wave."""
    import math

    return 40e-3 * x_mm / 200.0 + 3e-3 * math.sin(2 * math.pi * x_mm / 47.0)


def _as_user() -> list[str]:
    return ["runuser", "-u", USER, "--"] if os.geteuid() == 0 else []


def _ensure_user() -> None:
    if os.geteuid() != 0:
        return
    try:
        pwd.getpwnam(USER)
    except KeyError:
        subprocess.run(["useradd", "--system", "--create-home", "--shell", "/usr/sbin/nologin", USER], check=True)


class LinuxcncSim:
    """LinuxCNC and the laser reading it.

    Parameters
    ----------
    folder : Path
        Where the configuration goes (made readable by the LinuxCNC user).
    """

    def __init__(self, folder: Path):
        _ensure_user()
        self.folder = folder
        folder.mkdir(parents=True, exist_ok=True)
        folder.chmod(0o777)
        self.master, self.pty = open_pty_pair()
        os.set_blocking(self.master, False)
        self.process: subprocess.Popen | None = None
        self.sampler: subprocess.Popen | None = None
        self._laser: threading.Thread | None = None
        self._stop = threading.Event()
        self.samples = 0
        self.comp: Path | None = None
        self.encoder = UmdSimulator(self.master, lambda t: 0.0, version=2, rate_hz=1000.0)

    @property
    def ini(self) -> Path:
        return self.folder / "sim.ini"

    def _write_config(self) -> None:
        comp = ""
        if self.comp is not None:
            comp = f"COMP_FILE = {self.comp}\nCOMP_FILE_TYPE = 1\n"
        axes = "".join(AXIS.format(letter=letter, joint=j, low=TRAVEL_MM[0], high=TRAVEL_MM[1], comp=comp if j == 0 else "")
                       for j, letter in enumerate("XYZ"))
        self.ini.write_text(INI.format(axes=axes), encoding="utf-8")
        (self.folder / "sampler.hal").write_text(SAMPLER, encoding="utf-8")
        for name in ("sim.var", "sim.tbl"):
            (self.folder / name).touch()
        for path in self.folder.iterdir():
            path.chmod(0o666)

    def _wait_port(self, timeout_s: float) -> None:
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            if self.process is not None and self.process.poll() is not None:
                raise RuntimeError(f"LinuxCNC ended at start: {self._log()}")
            try:
                socket.create_connection(("127.0.0.1", PORT), timeout=0.5).close()
                return
            except OSError:
                time.sleep(0.2)
        raise RuntimeError(f"linuxcncrsh did not listen within {timeout_s} s: {self._log()}")

    def _log(self) -> str:
        try:
            return (self.folder / "linuxcnc.log").read_text(errors="replace")[-2000:]
        except OSError:
            return ""

    def _rsh(self, commands: list[str]) -> list[str]:
        from axiscal.devices.linuxcnc import RshConnection

        rsh = RshConnection("127.0.0.1", PORT, name="test-harness", timeout_s=5.0)
        try:
            return [rsh.ask(c, timeout_s=10.0) for c in commands]
        finally:
            rsh.close()

    def home(self) -> None:
        """Out of e-stop, machine on, every joint homed (what an operator does before a run)."""
        self._rsh(["set estop off", "set machine on", "set mode manual", "set home -1"])
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline:
            if self._rsh(["get joint_homed"])[0].split()[1:4] == ["YES"] * 3:
                return
            time.sleep(0.2)
        raise RuntimeError("LinuxCNC did not home")

    def _laser_loop(self) -> None:
        assert self.sampler is not None and self.sampler.stdout is not None
        for raw in self.sampler.stdout:
            if self._stop.is_set():
                return
            fields = raw.split()
            if len(fields) < 2:
                continue
            try:
                n, x_mm = int(fields[0]), float(fields[1])
            except ValueError:
                continue
            true_mm = x_mm + mechanical_error_mm(x_mm)
            self.encoder.position = lambda t, v=true_mm * 1e-3: v
            line = self.encoder.line(n + 1, n / 1000.0)
            try:
                os.write(self.master, line)  # non-blocking: dropped when nobody reads, as the firmware drops it
            except BlockingIOError:
                continue
            except OSError:
                return
            self.samples += 1

    def start(self) -> "LinuxcncSim":
        if subprocess.run(["pgrep", "-x", "rtapi_app"], capture_output=True).returncode == 0:
            raise RuntimeError("another LinuxCNC runs on this machine (one at a time): stop it first")
        # a LinuxCNC that was killed leaves HAL's shared memory behind, which locks the next one out
        subprocess.run(_as_user() + ["halrun", "-U"], capture_output=True, timeout=60)
        self._write_config()
        log = open(self.folder / "linuxcnc.log", "w")
        self.process = subprocess.Popen(_as_user() + ["linuxcnc", "-r", str(self.ini)], cwd=self.folder, stdout=log,
                                        stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True)
        self._wait_port(90)
        self.home()
        self._stop.clear()
        self.sampler = subprocess.Popen(_as_user() + ["stdbuf", "-oL", "halsampler", "-t"], cwd=self.folder,
                                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, start_new_session=True)
        self._laser = threading.Thread(target=self._laser_loop, name="linuxcnc-laser", daemon=True)
        self._laser.start()
        time.sleep(0.3)
        return self

    def stop(self) -> None:
        self._stop.set()
        if self.sampler is not None:
            os.killpg(self.sampler.pid, signal.SIGTERM)
            self.sampler.wait(timeout=10)
            self.sampler = None
        if self.process is not None:
            os.killpg(self.process.pid, signal.SIGTERM)  # the linuxcnc script cleans up on SIGTERM
            try:
                self.process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(self.process.pid, signal.SIGKILL)
                self.process.wait(timeout=10)
                subprocess.run(_as_user() + ["halrun", "-U"], capture_output=True, timeout=60)
            self.process = None
        if self._laser is not None:
            self._laser.join(timeout=5)
            self._laser = None
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline:
            if subprocess.run(["pgrep", "-x", "rtapi_app"], capture_output=True).returncode != 0:
                break
            time.sleep(0.2)

    def restart(self, comp: Path | None) -> None:
        """Stop LinuxCNC, start it with ``comp`` as joint 0's COMP_FILE (copied here), home again."""
        self.stop()
        if comp is not None:
            target = self.folder / "X.comp"
            shutil.copyfile(comp, target)
            target.chmod(0o666)
            self.comp = target
        self.start()

    def close(self) -> None:
        self.stop()
        close_pty_pair(self.master)
