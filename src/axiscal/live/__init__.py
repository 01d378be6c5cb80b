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
  starlette/uvicorn; the other modules do not, so its names are imported from it, not from here).
"""

from __future__ import annotations

from axiscal.live.pipeline import (
    Pipeline,
    RunSummary,
)
from axiscal.live.protocol import (
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
)
from axiscal.live.sources import (
    Backoff,
    ReplaySource,
    SerialSource,
    SimSource,
    SourceStatus,
    TcpSource,
    open_source,
    parse_source,
)
from axiscal.live.state import (
    CORRECTED,
    SPATIAL,
    LiveState,
    axis_error_columns,
    result_columns,
)

__all__ = [
    "RunSummary",
    "Pipeline",
    "FrameBatch",
    "LineDecoder",
    "encode_lines",
    "header_line",
    "FORMAT_LINE",
    "RECORD_KIND",
    "Recorder",
    "Record",
    "read_record",
    "build_system",
    "LiveSession",
    "SourceStatus",
    "Backoff",
    "SimSource",
    "ReplaySource",
    "TcpSource",
    "SerialSource",
    "parse_source",
    "open_source",
    "SPATIAL",
    "CORRECTED",
    "axis_error_columns",
    "result_columns",
    "LiveState",
]
