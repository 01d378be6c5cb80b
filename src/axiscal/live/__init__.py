"""Live monitoring: raw sensor frames in, spatial error of the functional point out, in real time (paper 000 §5).

The pieces (docs/live.md has the architecture):

- :mod:`axiscal.live.sources` -- where frames come from: the virtual instrument, a recorded file,
  the TCP line protocol of :mod:`axiscal.live.protocol`, a serial port;
- :mod:`axiscal.live.pipeline` -- the loop: frames through ``MeasurementSystem.process`` in small
  batches, faults flagged and kept, every frame and result handed to the recorder and the state;
- :mod:`axiscal.live.recorder` -- the crash-safe CSV record and its reader;
- :mod:`axiscal.live.state` -- the latest state a dashboard shows (bounded, independent of clients);
- :mod:`axiscal.live.server` -- the Starlette app pushing that state over a WebSocket (imports
  starlette/uvicorn; the other modules do not).
"""

__all__: list[str] = []
