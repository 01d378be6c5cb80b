"""Reports that tie the rooms together: the demo job on the built-in example (paper 000's XZ module)."""

from __future__ import annotations

from axiscal.report.demo import DEMO_FILES, DemoResult, builtin_example, run_demo

__all__ = ["DEMO_FILES", "DemoResult", "builtin_example", "run_demo"]
