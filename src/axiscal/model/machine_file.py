"""The machine description (TOML, docs/formats.md) read into a :class:`~axiscal.model.chain.Machine`:
validated once against the declared format (:class:`axiscal.io.formats.MachineFile`), then what
only the file's meaning can refuse (an axis not in the chain, an error table outside the folder, a
squareness term without its axes) is refused naming the key's line."""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from axiscal.conventions import ROTARY_LETTERS, SQUARENESS_TERMS, location_names
from axiscal.errors import AxiscalError
from axiscal.io.arguments import check_instance, check_path
from axiscal.io.formats.base import read_format, validate_data
from axiscal.io.formats.machine import MachineFile
from axiscal.io.schema import TomlLines
from axiscal.model.kinematics import AXIS_INDEX
from axiscal.model.axes import _SQUARENESS_PLACE, SQUARENESS_PLACEMENTS, Axis, parse_chain
from axiscal.model.chain import Machine
from axiscal.model.tables import INTERPOLATIONS, MAX_ANGLE_ERROR_RAD, MAX_TRANSLATION_ERROR_M, read_error_table
from axiscal.units import MM, angle_factor, length_factor, split_unit

__all__ = ["machine_from_dict", "load_machine", "as_machine"]


class _Where:
    """Locates keys of the machine file for the errors only its meaning can find."""

    def __init__(self, source: str, lines: TomlLines | None):
        self.source = source
        self.lines = lines

    def error(self, message: str, section: str = "", key: str | None = None) -> AxiscalError:
        line = self.lines.of(section, key=key) if self.lines is not None else None
        return AxiscalError(message, path=self.source, line=line)


def _vector_m(value: list[float] | None) -> tuple[float, float, float]:
    return (0.0, 0.0, 0.0) if value is None else tuple(float(v) * MM for v in value)  # type: ignore[return-value]


def _confined(base_dir: Path, name: str, tables_dir: Path | None) -> Path | None:
    """``name`` resolved inside ``base_dir`` (or else ``tables_dir``), or None if it points elsewhere."""
    found = []
    for folder in (base_dir,) if tables_dir is None else (base_dir, tables_dir):
        root = folder.resolve()
        candidate = (root / name).resolve()
        if candidate.is_relative_to(root):
            found.append(candidate)
    return next((c for c in found if c.is_file()), found[0] if found else None)


def machine_from_dict(
    data: Mapping,
    *,
    base_dir: Path = Path("."),
    source: str = "<machine>",
    text: str | None = None,
    tables_dir: str | Path | None = None,
) -> Machine:
    """Build a :class:`Machine` from the parsed TOML description (docs/formats.md).

    Every key is validated against the declared format (:class:`axiscal.io.formats.MachineFile`);
    the error names the key and, given ``text``, its line.

    Parameters
    ----------
    data : mapping
        The parsed TOML (lengths in mm, angles with their unit in the key).
    base_dir : Path
        Folder the error table paths are relative to; they must stay inside it.
    source : str
        Name of the description in error messages (its file).
    text : str, optional
        The TOML text ``data`` was parsed from, to name the line of a bad key.
    tables_dir : str or Path, optional
        A second folder error table paths may point into.

    Returns
    -------
    Machine

    Raises
    ------
    AxiscalError
        Unknown keys, a value of the wrong kind, a missing chain or axis section, an error table
        path outside ``base_dir`` (and ``tables_dir``), a bad error table or squareness entry;
        the message names ``source`` (or the table file) and the line.

    Examples
    --------
    >>> machine_from_dict({"chain": "FX", "hold_ends": "false"})
    Traceback (most recent call last):
    ...
    axiscal.errors.AxiscalError: <machine>: hold_ends must be true or false, not 'false'
    """
    check_instance("source", source, str)
    base_dir = check_path("base_dir", base_dir)
    if text is not None:
        check_instance("text", text, str)
    if tables_dir is not None:
        tables_dir = check_path("tables_dir", tables_dir)
    lines = TomlLines(text) if text is not None else None
    if not isinstance(data, Mapping):
        raise AxiscalError("a machine description must be a table of keys", path=source)
    checked = validate_data(MachineFile, dict(data), path=source, lines=lines)
    return _machine(checked, base_dir=base_dir, where=_Where(source, lines), tables_dir=tables_dir)


def _machine(checked: MachineFile, *, base_dir: Path, where: _Where, tables_dir: Path | None) -> Machine:
    """The machine of a validated description: what only the file's meaning can refuse is refused here."""
    chain = checked.chain
    try:
        workpiece_side, tool_side = parse_chain(chain)
    except AxiscalError as exc:
        raise where.error(exc.message, "", "chain") from None
    interpolation = checked.interpolation or INTERPOLATIONS[0]
    hold_ends = bool(checked.hold_ends)
    axes_data = checked.axes or {}
    for letter in workpiece_side + tool_side:
        if letter not in axes_data:
            raise where.error(f"axis {letter} is in chain '{chain}' but has no [axes.{letter}] section", "", "chain")
    axes: dict[str, Axis] = {}
    for letter, section in axes_data.items():
        label = f"axes.{letter}"
        if letter not in workpiece_side + tool_side:
            raise where.error(f"[{label}] is not an axis of chain '{chain}'", label)
        table_path = _confined(base_dir, section.errors, tables_dir)
        if table_path is None:
            raise where.error(
                f"[{label}] errors: the error table must be inside the machine file's folder", label, "errors"
            )
        if not table_path.is_file():
            raise where.error(f"[{label}] errors: no file '{section.errors}' in the machine file's folder", label, "errors")
        if section.periodic is not None and letter not in ROTARY_LETTERS:
            raise where.error(f"[{label}] periodic: only a rotary axis (A, B, C) is periodic", label, "periodic")
        table = read_error_table(
            table_path,
            letter,
            interpolation=section.interpolation or interpolation,
            hold_ends=hold_ends if section.hold_ends is None else section.hold_ends,
            periodic=section.periodic,
        )
        axes[letter] = Axis(letter, table, _vector_m(section.origin_mm))
    squareness: dict[str, float] = {}
    for key, value in (checked.squareness or {}).items():
        stem, unit = split_unit(key) if "_" in key else (key, "")
        if stem not in SQUARENESS_TERMS:
            raise where.error(
                f"[squareness] unknown term '{key}'; use EC0Y, EB0Z, EA0Z with a unit, e.g. EB0Z_arcsec", "squareness", key
            )
        try:
            squareness[stem] = float(value) * angle_factor(unit, what=key)
        except AxiscalError as exc:
            raise where.error(exc.message, "squareness", key) from None
        if abs(squareness[stem]) > MAX_ANGLE_ERROR_RAD:
            raise where.error(f"[squareness] {key} = {value} is not a squareness error (over {MAX_ANGLE_ERROR_RAD} rad)", "squareness", key)
        letter, reference, _ = _SQUARENESS_PLACE[stem]
        if letter not in workpiece_side + tool_side or reference not in workpiece_side + tool_side:
            raise where.error(f"[squareness] {key}: chain '{chain}' has no axes {reference} and {letter} to be square", "squareness", key)
    location: dict[str, float] = {}
    for key, value in (checked.location or {}).items():
        stem, unit = split_unit(key) if "_" in key else (key, "")
        letter = stem[-1:]
        if letter not in ROTARY_LETTERS or stem not in location_names(letter):
            raise where.error(
                f"[location] unknown term '{key}'; e.g. {', '.join(n + '_um' for n in location_names('C')[:2])}, "
                f"{', '.join(n + '_urad' for n in location_names('C')[2:])}",
                "location",
                key,
            )
        if letter not in workpiece_side + tool_side:
            raise where.error(f"[location] {key}: chain '{chain}' has no axis {letter}", "location", key)
        try:
            if stem[1] in AXIS_INDEX:
                factor, limit = length_factor(unit, what=key), MAX_TRANSLATION_ERROR_M
            else:
                factor, limit = angle_factor(unit, what=key), MAX_ANGLE_ERROR_RAD
        except AxiscalError as exc:
            raise where.error(exc.message, "location", key) from None
        if abs(value * factor) > limit:
            raise where.error(f"[location] {key} = {value} has no physical meaning (limits: 10 mm, 0.01 rad)", "location", key)
        location[stem] = float(value) * factor
    try:
        return Machine(
            chain=chain,
            axes=axes,
            squareness_rad=squareness,
            tool_m=_vector_m(checked.tool_mm),
            workpiece_m=_vector_m(checked.workpiece_mm),
            name=checked.name or "",
            squareness_placement=checked.squareness_placement or SQUARENESS_PLACEMENTS[0],
            location=location,
        )
    except AxiscalError as exc:
        raise exc.located(path=where.source) from None


def load_machine(path: str | Path, *, tables_dir: str | Path | None = None) -> Machine:
    """Read a machine description (TOML, docs/formats.md) and its error tables.

    Parameters
    ----------
    path : str or Path
        The TOML file; the error table paths in it are relative to its folder and must stay inside it.
    tables_dir : str or Path, optional
        A second folder the error table paths may point into.

    Returns
    -------
    Machine
        SI units throughout; the squareness placement is ``"relative"`` unless the file says otherwise.

    Raises
    ------
    AxiscalError
        A missing or malformed file, naming the file and, where known, the line.

    Examples
    --------
    >>> machine = load_machine("examples/xz_module/machine.toml")  # doctest: +SKIP
    >>> machine.chain  # doctest: +SKIP
    'FXZ'
    """
    path = check_path("path", path)
    if tables_dir is not None:
        tables_dir = check_path("tables_dir", tables_dir)
    checked, lines = read_format(MachineFile, path)  # the file read once: parsed, validated, its lines kept
    return _machine(checked, base_dir=path.parent, where=_Where(str(path), lines), tables_dir=tables_dir)


def as_machine(machine: Machine | str | Path) -> Machine:
    """``machine`` itself, or the machine its description file describes.

    Parameters
    ----------
    machine : Machine, str or Path
        A machine, or the path of its TOML description.

    Returns
    -------
    Machine

    Raises
    ------
    AxiscalError
        Neither a Machine nor a path, or a missing or malformed file (see :func:`load_machine`).
    """
    if isinstance(machine, Machine):
        return machine
    if not isinstance(machine, (str, Path)):
        raise AxiscalError(f"a machine is a Machine or the path of its TOML file, not {machine!r:.40}")
    return load_machine(machine)


