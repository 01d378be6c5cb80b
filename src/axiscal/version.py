"""The version of axiscal, written into every sidecar and results file."""

__all__ = ["__version__"]

__version__ = "0.1.0"
