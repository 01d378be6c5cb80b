"""Every public callable of the pre-compensation room refuses bad arguments with AxiscalError naming them.

The same table harness as the other rooms (api_cases.CaseTable): NaN and infinity, wrong shapes,
strings, None and unknown options, each refused at the public entry with the argument named.
"""

from __future__ import annotations

import numpy as np

from api_cases import EXAMPLES, CaseTable, api

ROOMS = ("precompensation",)
NAN, INF = float("nan"), float("inf")
TABLE = CaseTable(ROOMS)
bad = TABLE.bad
pc = api("precompensation")
R = "precompensation"
MACHINE = str(EXAMPLES / "xfyz_machine" / "machine.toml")
PROGRAM = "G21 G90\nG0 X100 Y100 Z100\nG1 X200 F500\nM2\n"
NEVER = EXAMPLES / "no such folder"

bad(R, "precompensate_points", "points_m",
    lambda: pc.precompensate_points(MACHINE, [[NAN, 0.1, 0.1]]), lambda: pc.precompensate_points(MACHINE, [[0.1, 0.1]]),
    lambda: pc.precompensate_points(MACHINE, "points"), lambda: pc.precompensate_points(MACHINE, np.zeros((0, 3))))
bad(R, "precompensate_points", "rotary_rad",
    lambda: pc.precompensate_points(MACHINE, [[0.1, 0.1, 0.1]], rotary_rad={"C": 0.1}))
bad(R, "precompensate_points", "tool_m",
    lambda: pc.precompensate_points(MACHINE, [[0.1, 0.1, 0.1]], tool_m=(0.0, INF, 0.0)),
    lambda: pc.precompensate_points(MACHINE, [[0.1, 0.1, 0.1]], tool_m=(0.0, 0.0)))
bad(R, "precompensate_points", "machine", lambda: pc.precompensate_points(None, [[0.1, 0.1, 0.1]]))
for name in ("precompensate_program", "rewrite_program"):
    function = getattr(pc, name)
    bad(R, name, "text must be a str", lambda f=function: f(None, MACHINE, dialect="linuxcnc"),
        lambda f=function: f(b"G1", MACHINE, dialect="linuxcnc"))
    bad(R, name, "unknown dialect", lambda f=function: f(PROGRAM, MACHINE, dialect="haas"))
    bad(R, name, "dialect must be a str", lambda f=function: f(PROGRAM, MACHINE, dialect=None))
    bad(R, name, "tolerance_m", lambda f=function: f(PROGRAM, MACHINE, dialect="linuxcnc", tolerance_m=NAN),
        lambda f=function: f(PROGRAM, MACHINE, dialect="linuxcnc", tolerance_m=-1.0),
        lambda f=function: f(PROGRAM, MACHINE, dialect="linuxcnc", tolerance_m="0.5"))
    bad(R, name, "max_segment_m", lambda f=function: f(PROGRAM, MACHINE, dialect="linuxcnc", max_segment_m=0.0),
        lambda f=function: f(PROGRAM, MACHINE, dialect="linuxcnc", max_segment_m=INF))
    bad(R, name, "work_offset_m", lambda f=function: f(PROGRAM, MACHINE, dialect="linuxcnc", work_offset_m=3),
        lambda f=function: f(PROGRAM, MACHINE, dialect="linuxcnc", work_offset_m={"X": NAN}))
    bad(R, name, "machine", lambda f=function: f(PROGRAM, 5, dialect="linuxcnc"))
    bad(R, name, "source", lambda f=function: f(PROGRAM, MACHINE, dialect="linuxcnc", source=5))
bad(R, "precompensate_file", "program_path", lambda: pc.precompensate_file(5, MACHINE, NEVER / "o.ngc", dialect="linuxcnc"))
bad(R, "precompensate_file", "not found", lambda: pc.precompensate_file(NEVER / "p.ngc", MACHINE, NEVER / "o.ngc", dialect="linuxcnc"))
bad(R, "precompensate_file", "output_path", lambda: pc.precompensate_file(EXAMPLES / "x.ngc", MACHINE, None, dialect="linuxcnc"))
bad(R, "precompensate_file", "machine", lambda: pc.precompensate_file(EXAMPLES / "x.ngc", None, NEVER / "o.ngc", dialect="linuxcnc"))
bad(R, "correction_grid", "grid", lambda: pc.correction_grid(MACHINE, None), lambda: pc.correction_grid(MACHINE, "X=a"),
    lambda: pc.correction_grid(MACHINE, "X=100,Y=100"))
bad(R, "correction_grid", "machine", lambda: pc.correction_grid(3.0, "X=100,Y=100,Z=100"))
bad(R, "export_correction_grid", "path", lambda: pc.export_correction_grid(MACHINE, "X=100,Y=100,Z=100", None))
bad(R, "export_correction_grid", "grid", lambda: pc.export_correction_grid(MACHINE, "", NEVER / "g.csv"))
bad(R, "write_correction_grid", "result must be a CorrectionGrid", lambda: pc.write_correction_grid(None, NEVER / "g.csv"))

bad(R, "isg_volumetric_table", "grid", lambda: pc.isg_volumetric_table(MACHINE, None), lambda: pc.isg_volumetric_table(MACHINE, "X=100,Y=100"),
    lambda: pc.isg_volumetric_table(MACHINE, "X=100,Y=100,Z=100,A=0"))
bad(R, "isg_volumetric_table", "machine", lambda: pc.isg_volumetric_table(3.0, "X=100,Y=100,Z=100"))
bad(R, "isg_volumetric_table", "outside the error table", lambda: pc.isg_volumetric_table(MACHINE, "X=-100,Y=100,Z=100"))
bad(R, "isg_axis_tables", "one position", lambda: pc.isg_axis_tables(MACHINE, "X=100,Y=100:200:50,Z=100:200:50"))
bad(R, "isg_axis_tables", "axis_numbers", lambda: pc.isg_axis_tables(MACHINE, "X=100:200:50,Y=100:200:50,Z=100:200:50", axis_numbers={"X": 1}))
bad(R, "isg_axis_tables", "grid", lambda: pc.isg_axis_tables(MACHINE, 5))
bad(R, "parse_axis_numbers", "axis_numbers", lambda: pc.parse_axis_numbers("X=0"), lambda: pc.parse_axis_numbers("X1"),
    lambda: pc.parse_axis_numbers(5), lambda: pc.parse_axis_numbers("Q=1"))
bad(R, "export_isg", "path", lambda: pc.export_isg(MACHINE, "X=100,Y=100,Z=100", None))
bad(R, "export_isg", "kind", lambda: pc.export_isg(MACHINE, "X=100,Y=100,Z=100", NEVER / "v.csv", kind="grid"))
bad(R, "export_isg", "another suffix than .lis", lambda: pc.export_isg(MACHINE, "X=100,Y=100,Z=100", NEVER / "v.lis"))
bad(R, "export_isg", "tool_m applies", lambda: pc.export_isg(MACHINE, "X=100:200:50,Y=100:200:50,Z=100:200:50", NEVER / "v",
                                                            kind="axis", tool_m=(0.0, 0.0, 0.0)))
bad(R, "export_isg", "axis_numbers", lambda: pc.export_isg(MACHINE, "X=100,Y=100,Z=100", NEVER / "v.csv", axis_numbers={"X": 1}))

#: result containers, made by the functions above rather than by users
EXEMPT = {R: {"CorrectionGrid", "PrecompensatedPoints", "Precompensation", "IsgExport"}}

test_bad_arguments_raise_axiscal_error_naming_them, test_every_public_callable_has_a_bad_argument_case = TABLE.tests(EXEMPT)
