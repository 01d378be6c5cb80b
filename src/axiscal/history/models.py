"""The tables of the calibration history: machines, their campaigns, and each campaign's figures.

No standard clause: ISO/IEC 17025 (7.5, technical records) asks a laboratory to keep the results of
every calibration with what identifies the item, the date and the software; these three tables keep
exactly what an axiscal results.json (schema ``axiscal-results/1``) holds of that. The schema is
made and changed only by the alembic migrations shipped beside this module
(``axiscal/history/migrations``); a test checks that the migrations build these models.
"""

from __future__ import annotations

import datetime as _dt

from sqlalchemy import (
    Date,
    DateTime,
    Float,
    ForeignKey,
    Integer,
    String,
    Text,
    UniqueConstraint,
)
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column, relationship

__all__ = ["Base", "MachineRow", "CampaignRow", "FigureRow"]


class Base(DeclarativeBase):
    """The declarative base of the history tables.

    Attributes
    ----------
    metadata : sqlalchemy.MetaData
        The three tables, as the migrations make them.
    """


class MachineRow(Base):
    """A machine, identified by the name and serial of the results file's ``[machine]`` table.

    Attributes
    ----------
    id : int
    name, serial : str
        Unique together; serial ``""`` when the results file has none.
    campaigns : list of CampaignRow
    """

    __tablename__ = "machines"
    __table_args__ = (UniqueConstraint("name", "serial", name="uq_machines_name_serial"),)

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    name: Mapped[str] = mapped_column(String(200), nullable=False)
    serial: Mapped[str] = mapped_column(String(200), nullable=False, default="")
    campaigns: Mapped[list[CampaignRow]] = relationship(back_populates="machine", passive_deletes=True)


class CampaignRow(Base):
    """One stored campaign: one results.json, known by the SHA-256 of its bytes.

    Attributes
    ----------
    id, machine_id : int
    results_sha256 : str
        Unique: the same file is stored once.
    title : str
    date : datetime.date
        The campaign's date.
    verdict, decision_rule, software_version, source : str
    added_at : datetime.datetime
        When it was stored (UTC).
    figure_count : int
        How many figures it has: an integrity check counts them.
    figures : list of FigureRow
    """

    __tablename__ = "campaigns"

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    machine_id: Mapped[int] = mapped_column(ForeignKey("machines.id", ondelete="CASCADE"), nullable=False, index=True)
    results_sha256: Mapped[str] = mapped_column(String(64), nullable=False, unique=True)
    title: Mapped[str] = mapped_column(String(500), nullable=False, default="")
    date: Mapped[_dt.date] = mapped_column(Date, nullable=False)
    verdict: Mapped[str] = mapped_column(String(20), nullable=False)
    decision_rule: Mapped[str] = mapped_column(String(20), nullable=False)
    software_version: Mapped[str] = mapped_column(String(40), nullable=False)
    source: Mapped[str] = mapped_column(Text, nullable=False, default="")
    added_at: Mapped[_dt.datetime] = mapped_column(DateTime(timezone=True), nullable=False)
    figure_count: Mapped[int] = mapped_column(Integer, nullable=False)
    machine: Mapped[MachineRow] = relationship(back_populates="campaigns")
    figures: Mapped[list[FigureRow]] = relationship(back_populates="campaign", passive_deletes=True,
                                                    order_by="FigureRow.position")


class FigureRow(Base):
    """One figure of one test of a campaign, with its tolerance, U (k = 2) and result.

    Attributes
    ----------
    id, campaign_id, position : int
        ``position`` is the figure's place in its results file.
    key : str
        ``KIND.AXIS.FIGURE``, unique within its campaign.
    test_id, kind, axis, name, unit, result : str
    value, tolerance, U : float or None
        In ``unit``; U (column ``expanded_uncertainty``) at k = 2.
    """

    __tablename__ = "figures"
    __table_args__ = (UniqueConstraint("campaign_id", "key", name="uq_figures_campaign_key"),)

    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    campaign_id: Mapped[int] = mapped_column(ForeignKey("campaigns.id", ondelete="CASCADE"), nullable=False, index=True)
    position: Mapped[int] = mapped_column(Integer, nullable=False)
    key: Mapped[str] = mapped_column(String(300), nullable=False, index=True)
    test_id: Mapped[str] = mapped_column(String(200), nullable=False)
    kind: Mapped[str] = mapped_column(String(40), nullable=False)
    axis: Mapped[str] = mapped_column(String(20), nullable=False, default="")
    name: Mapped[str] = mapped_column(String(100), nullable=False)
    value: Mapped[float | None] = mapped_column(Float, nullable=True)
    unit: Mapped[str] = mapped_column(String(20), nullable=False, default="")
    tolerance: Mapped[float | None] = mapped_column(Float, nullable=True)
    U: Mapped[float | None] = mapped_column("expanded_uncertainty", Float, nullable=True)
    result: Mapped[str] = mapped_column(String(20), nullable=False)
    campaign: Mapped[CampaignRow] = relationship(back_populates="figures")
