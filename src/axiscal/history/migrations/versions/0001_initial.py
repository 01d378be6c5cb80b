"""The first schema of the calibration history: machines, campaigns, figures.

Revision ID: 0001
Revises:
Create Date: 2026-11-25
"""

from __future__ import annotations

import sqlalchemy as sa
from alembic import op

revision = "0001"
down_revision = None
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "machines",
        sa.Column("id", sa.Integer(), primary_key=True),
        sa.Column("name", sa.String(200), nullable=False),
        sa.Column("serial", sa.String(200), nullable=False),
        sa.UniqueConstraint("name", "serial", name="uq_machines_name_serial"),
    )
    op.create_table(
        "campaigns",
        sa.Column("id", sa.Integer(), primary_key=True),
        sa.Column("machine_id", sa.Integer(), sa.ForeignKey("machines.id", ondelete="CASCADE"), nullable=False),
        sa.Column("results_sha256", sa.String(64), nullable=False, unique=True),
        sa.Column("title", sa.String(500), nullable=False),
        sa.Column("date", sa.Date(), nullable=False),
        sa.Column("verdict", sa.String(20), nullable=False),
        sa.Column("decision_rule", sa.String(20), nullable=False),
        sa.Column("software_version", sa.String(40), nullable=False),
        sa.Column("source", sa.Text(), nullable=False),
        sa.Column("added_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("figure_count", sa.Integer(), nullable=False),
    )
    op.create_index("ix_campaigns_machine_id", "campaigns", ["machine_id"])
    op.create_table(
        "figures",
        sa.Column("id", sa.Integer(), primary_key=True),
        sa.Column("campaign_id", sa.Integer(), sa.ForeignKey("campaigns.id", ondelete="CASCADE"), nullable=False),
        sa.Column("position", sa.Integer(), nullable=False),
        sa.Column("key", sa.String(300), nullable=False),
        sa.Column("test_id", sa.String(200), nullable=False),
        sa.Column("kind", sa.String(40), nullable=False),
        sa.Column("axis", sa.String(20), nullable=False),
        sa.Column("name", sa.String(100), nullable=False),
        sa.Column("value", sa.Float(), nullable=True),
        sa.Column("unit", sa.String(20), nullable=False),
        sa.Column("tolerance", sa.Float(), nullable=True),
        sa.Column("expanded_uncertainty", sa.Float(), nullable=True),
        sa.Column("result", sa.String(20), nullable=False),
        sa.UniqueConstraint("campaign_id", "key", name="uq_figures_campaign_key"),
    )
    op.create_index("ix_figures_campaign_id", "figures", ["campaign_id"])
    op.create_index("ix_figures_key", "figures", ["key"])


def downgrade() -> None:
    op.drop_table("figures")
    op.drop_table("campaigns")
    op.drop_table("machines")
