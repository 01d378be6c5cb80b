"""Artefact files declared (docs/identification.md): one model per kind of artefact, told apart by
``kind``; each names the CSV files beside it."""

from __future__ import annotations

from typing import Annotated, Literal, Union

from annotated_types import Ge, Len
from pydantic import Discriminator, Field, Strict, StringConstraints, Tag, TypeAdapter

from axiscal.io.formats.base import FileName, FormatModel, Number, Positive, Vector3

__all__ = [
    "ArtefactCommon",
    "PlatePose",
    "GaugeLine",
    "BallPlateFile",
    "StepGaugeFile",
    "BallbarNetworkFile",
    "MultilaterationFile",
    "RTestFile",
    "ARTEFACT_MODELS",
    "ArtefactFile",
]


#: an artefact's name: it titles its figures and names their files, so it stays short
ArtefactName = Annotated[str, Strict(), StringConstraints(pattern=r"\S", max_length=100)]


class ArtefactCommon(FormatModel):
    """What every artefact file has.

    Attributes
    ----------
    name : str or None
        The artefact's name (default: the file's stem).
    tool_mm : list of 3 float or None
        The probe or ball in the tool frame, mm.
    measured : str
        The readings (CSV) beside the file.
    """

    name: ArtefactName | None = Field(None, description="the artefact's name (default: the file name), at most 100 characters")
    tool_mm: Vector3 | None = Field(None, description="probe or ball in the tool frame, mm (default 0)")
    measured: FileName = Field(description="the readings (CSV) beside this file")


class PlatePose(FormatModel):
    """``[pose]`` of a ball plate stated rather than fitted.

    Attributes
    ----------
    origin_mm, x_direction, y_direction : list of 3 float
    """

    origin_mm: Vector3 = Field(description="the plate's origin in the machine frame, mm")
    x_direction: Vector3 = Field(description="unit vector of the plate's x axis")
    y_direction: Vector3 = Field(description="unit vector of the plate's y axis (orthogonal to x)")


class GaugeLine(FormatModel):
    """``[line]`` of a step gauge.

    Attributes
    ----------
    start_mm, direction : list of 3 float
    """

    start_mm: Vector3 = Field(description="the gauge's zero in the machine frame, mm")
    direction: Vector3 = Field(description="unit vector along the gauge")


class BallPlateFile(ArtefactCommon):
    """A ball plate.

    Attributes
    ----------
    kind : str
    balls : str
    pose : str or PlatePose
    """

    kind: Literal["ball_plate"] = Field(description="the kind of artefact")
    balls: FileName = Field(description="certificate (CSV): ball, x_mm, y_mm[, z_mm][, U_um]")
    pose: Annotated[
        Union[Annotated[Literal["fit"], Tag("=fit")], Annotated[PlatePose, Tag("=table")]],
        Discriminator(lambda v: "=table" if isinstance(v, (dict, PlatePose)) else "=fit"),  # a model, once validated
    ] = Field("fit", description='"fit" (default) or a [pose] table')


class StepGaugeFile(ArtefactCommon):
    """A step gauge.

    Attributes
    ----------
    kind : str
    faces : str
    line : GaugeLine
    """

    kind: Literal["step_gauge"] = Field(description="the kind of artefact")
    faces: FileName = Field(description="certificate (CSV): face, position_mm[, U_um]")
    line: GaugeLine = Field(description="where the gauge lies, [line]")


class BallbarNetworkFile(ArtefactCommon):
    """A network of ballbar lengths.

    Attributes
    ----------
    kind : str
    length_mm : float
    length_U_um : float or None
    """

    kind: Literal["ballbar_network"] = Field(description="the kind of artefact")
    length_mm: Positive = Field(description="the bar's calibrated length, mm")
    length_U_um: Annotated[Number, Ge(0)] | None = Field(None, description="its expanded uncertainty (k = 2), um")


class MultilaterationFile(ArtefactCommon):
    """Tracker or tracer ranges to targets.

    Attributes
    ----------
    kind : str
    stations : dict of str to list of 3 float, or None
    """

    kind: Literal["multilateration"] = Field(description="the kind of artefact")
    stations: dict[str, Vector3] | None = Field(None, description="approximate position_mm of every station, [stations]")


class RTestFile(ArtefactCommon):
    """An R-test (ball on the table, sensors on the spindle).

    Attributes
    ----------
    kind : str
    sensors : list of list of 3 float
    ball_on_table_mm : list of 3 float or None
    """

    kind: Literal["r_test"] = Field(description="the kind of artefact")
    sensors: Annotated[list[Vector3], Len(1)] = Field(description="unit sensing directions, e.g. [[1, 0, 0], [0, 1, 0], [0, 0, 1]]")
    ball_on_table_mm: Vector3 | None = Field(None, description="the ball in the table frame, mm")


#: kind -> the model of an artefact file of that kind
ARTEFACT_MODELS: dict[str, type[ArtefactCommon]] = {
    "ball_plate": BallPlateFile, "step_gauge": StepGaugeFile, "ballbar_network": BallbarNetworkFile,
    "multilateration": MultilaterationFile, "r_test": RTestFile,
}
#: an artefact file of any kind (for its JSON Schema)
ArtefactFile = TypeAdapter(Annotated[Union[tuple(ARTEFACT_MODELS.values())], Field(discriminator="kind")])  # type: ignore[valid-type]
