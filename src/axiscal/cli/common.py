"""Helpers shared by the command modules: JSON output, lazy matplotlib, output paths."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import click
import numpy as np

__all__ = ["echo_json", "pyplot", "ensure_parent", "write_output"]


def _plain(value: Any) -> Any:
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, (np.floating, float)):
        value = float(value)
        return value if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    return value


def echo_json(payload: dict[str, Any]) -> None:
    """Print one JSON object; NaN and infinities become null (JSON has no NaN)."""
    click.echo(json.dumps(_plain(payload), indent=2))


def pyplot():
    """matplotlib.pyplot on the non-interactive Agg backend, imported only when a plot is asked for."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def ensure_parent(path: str | Path) -> Path:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    return path


def write_output(path: str | Path, write: Callable[[Path], Any]) -> Path:
    """Run ``write`` on ``path`` with its parent folders made; a file that cannot be written (no
    permission, no such device, disk full) is an AxiscalError naming it, so one error line."""
    from axiscal.errors import AxiscalError

    try:
        target = ensure_parent(path)
        write(target)
    except OSError as exc:
        raise AxiscalError(f"cannot write this file: {exc.strerror or exc}", path=path) from None
    return target
