"""The harness the bad-argument tables share (tests/boundaries/test_api_arguments*.py).

A table holds (room, public name, call, words) cases; :meth:`CaseTable.tests` makes the two tests
every table runs: each call raises AxiscalError whose message holds the words (no other exception,
no RuntimeWarning), and every public callable of the table's rooms has a case or an exemption.
"""

from __future__ import annotations

import inspect
import warnings
from collections.abc import Callable, Iterable, Mapping
from importlib import import_module
from pathlib import Path

import pytest

from axiscal.errors import AxiscalError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
NAN, INF = float("nan"), float("inf")


def api(room: str):
    """The room's package, ``axiscal.<room>``."""
    return import_module(f"axiscal.{room}")


def public_callables(room: str) -> set[str]:
    """The callables of the room's ``__all__`` (int and str enumerations left out)."""
    module = api(room)
    names = set()
    for name in module.__all__:
        value = getattr(module, name)
        if callable(value) and not (inspect.isclass(value) and issubclass(value, (int, str))):
            names.add(name)
    return names


def finite_or_refused(call: Callable[[], object]) -> object | None:
    """The call's result, or None when it raised AxiscalError; no other exception, no RuntimeWarning."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            return call()
        except AxiscalError:
            return None


class CaseTable:
    """Bad-argument cases of some rooms, and the tests over them."""

    def __init__(self, rooms: Iterable[str]):
        self.rooms = tuple(rooms)
        self.cases: list[tuple[str, str, Callable[[], object], str]] = []

    def bad(self, room: str, name: str, words: str, *calls: Callable[[], object]) -> None:
        """Add one case per call: each must raise AxiscalError whose message holds ``words``."""
        assert room in self.rooms, room
        self.cases.extend((room, name, call, words) for call in calls)

    def _ids(self) -> list[str]:
        counts: dict[str, int] = {}
        ids = []
        for room, name, _, _ in self.cases:
            key = f"{room}.{name}"
            counts[key] = counts.get(key, 0) + 1
            ids.append(f"{key}-{counts[key]}")
        return ids

    def tests(self, exempt: Mapping[str, set[str]]):
        """The two tests of the table, to bind to module-level ``test_`` names."""

        @pytest.mark.parametrize(("room", "name", "call", "words"), self.cases, ids=self._ids())
        def bad_arguments(room, name, call, words):
            with warnings.catch_warnings():
                warnings.simplefilter("error")
                with pytest.raises(AxiscalError) as caught:
                    call()
            assert words.lower() in caught.value.message.lower(), caught.value.message

        @pytest.mark.parametrize("room", self.rooms)
        def coverage(room):
            covered = {name for r, name, _, _ in self.cases if r == room}
            missing = sorted(public_callables(room) - covered - set(exempt.get(room, set())))
            assert not missing, f"public callables of axiscal.{room} without a bad-argument case: {missing}"

        return bad_arguments, coverage
