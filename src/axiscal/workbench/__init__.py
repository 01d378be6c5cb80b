"""The workbench: one local web page that runs a whole visit at the machine.

It calls the library as the command line does and computes nothing itself.
"""
__all__: list[str] = []
