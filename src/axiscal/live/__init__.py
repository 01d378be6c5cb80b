"""Live monitoring: raw sensor frames in, spatial error of the functional point out, in real time (paper 000 §5).

The pieces (docs/live.md has the architecture):

- :mod:`axiscal.live.sources` -- where frames come from: the virtual instrument, a recorded file,
  the TCP line protocol of :mod:`axiscal.live.protocol`, a serial port;
- :mod:`axiscal.live.pipeline` -- the loop: frames through ``MeasurementSystem.process`` in small
  batches, faults flagged and kept, every frame and result handed to the recorder and the state;
- :mod:`axiscal.live.recorder` -- the crash-safe CSV record and its reader;
- :mod:`axiscal.live.state` -- the latest state a dashboard shows (bounded, independent of clients);
- :mod:`axiscal.live.session` -- one run set up from a machine, a source, a record and a dashboard;
- :mod:`axiscal.live.server` -- the Starlette app pushing that state over a WebSocket (imports
  starlette/uvicorn; the other modules do not, so this package loads it only when one of its
  names is first used);
- :mod:`axiscal.live.dashboard` -- that app served by a process of its own, fed the batches through
  a pipe, so that it never holds the loop's interpreter lock (what a session serves; it imports
  the server only in its own process).
"""

from __future__ import annotations

from axiscal.live.dashboard import (
    BACKLOG_BYTES,
    DashboardProcess,
)
from axiscal.live.pipeline import (
    Pipeline,
    RunSummary,
)
from axiscal.live.protocol import (
    MAX_LINE_BYTES,
    FrameBatch,
    LineDecoder,
    encode_lines,
    header_line,
)
from axiscal.live.recorder import (
    FORMAT_LINE,
    RECORD_KIND,
    Record,
    Recorder,
    read_record,
)
from axiscal.live.session import (
    LiveSession,
    build_system,
    check_record_target,
)
from axiscal.live.sources import (
    MAX_RATE_HZ,
    Backoff,
    ReplaySource,
    RtxSource,
    SerialSource,
    SimSource,
    SourceStatus,
    TcpSource,
    open_source,
    parse_source,
    rtx_parts,
)
from axiscal.live.state import (
    CORRECTED,
    SPATIAL,
    UPDATE_HZ_RANGE,
    LiveState,
    axis_error_columns,
    result_columns,
)

#: the dashboard server's names, imported from :mod:`axiscal.live.server` only when first used
#: (it imports starlette and uvicorn, which the rest of the live room and the CLI do without)
_SERVER_NAMES = ("WEB", "HOST", "LOOPBACK_HOSTS", "ClientStats", "Broadcaster", "request_allowed", "create_app",
                 "create_board_app", "LiveServer")


def __getattr__(name: str):
    if name in _SERVER_NAMES:
        from axiscal.live import server

        return getattr(server, name)
    raise AttributeError(f"module 'axiscal.live' has no attribute {name!r}")
from axiscal.live.playback import (
    AHEAD_S,
)
from axiscal.live.priority import (
    Priority,
    below_the_loop,
    raise_priority,
    restore_priority,
)
from axiscal.live.record_text import (
    FIXED,
    GENERAL,
    INTEGER,
    format_rows,
    python_format,
)
from axiscal.live.state import (
    FOLD_S,
    FOLD_FRAMES,
)

__all__ = [
    "RunSummary",
    "Pipeline",
    "FrameBatch",
    "MAX_LINE_BYTES",
    "LineDecoder",
    "encode_lines",
    "header_line",
    "FORMAT_LINE",
    "RECORD_KIND",
    "Recorder",
    "Record",
    "read_record",
    "build_system",
    "check_record_target",
    "LiveSession",
    "MAX_RATE_HZ",
    "SourceStatus",
    "Backoff",
    "SimSource",
    "ReplaySource",
    "RtxSource",
    "TcpSource",
    "SerialSource",
    "parse_source",
    "rtx_parts",
    "open_source",
    "UPDATE_HZ_RANGE",
    "SPATIAL",
    "CORRECTED",
    "axis_error_columns",
    "result_columns",
    "LiveState",
    "WEB",
    "HOST",
    "LOOPBACK_HOSTS",
    "ClientStats",
    "Broadcaster",
    "request_allowed",
    "create_app",
    "create_board_app",
    "LiveServer",
    "BACKLOG_BYTES",
    "DashboardProcess",
    "AHEAD_S",
    "Priority",
    "below_the_loop",
    "raise_priority",
    "restore_priority",
    "FIXED",
    "GENERAL",
    "INTEGER",
    "format_rows",
    "python_format",
    "FOLD_S",
    "FOLD_FRAMES",
]
