"""The visit's machine and its tests, as the workbench keeps them: every axis, every test, each with its state.

:class:`VisitTests` is a part of :class:`~axiscal.workbench.visit.Workbench`. It sets the visit's
machine up (:mod:`axiscal.workbench.machines`), keeps the list of its tests
(:mod:`axiscal.workbench.suite`) with their states, adds tests taken from files
(:mod:`axiscal.workbench.added`) and checks each at once through the campaign room, and writes
``campaign.toml`` with every test whose data is in the visit's folder, so that the campaign
room evaluates them and the report room reports them. It uses the workbench's ``data``,
``saved``, ``run``, ``_lock``, ``_plot_lock``, ``_save``, ``_rel``, ``_visit_folder``,
``_phase_folder`` and ``_render_campaign``.
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

from axiscal.errors import AxiscalError
from axiscal.io.atomic import write_text
from axiscal.workbench.added import FILES_FOLDER, checked_file_form, data_files, file_test, store_upload
from axiscal.workbench.forms import FormErrors
from axiscal.workbench.machines import (EXAMPLE, MACHINE_FILE, copy_machine, example_machine, machine_axes,
                                        write_new_machine)
from axiscal.workbench.suite import campaign_with_tests, state_of, wanted_tests

__all__ = ["VisitTests"]

#: the New visit form's fields that choose the machine and its tests (the rest is the campaign's)
MACHINE_KEYS = ("machine_choice", "machine_chain", "machine_travels", "tests")


class VisitTests:
    """The visit's machine, its tests and their states, the tests added from files, campaign.toml written.

    Attributes
    ----------
    (none of its own)
        It works on the :class:`~axiscal.workbench.visit.Workbench` it is a part of: the visit's
        tests are ``saved.tests``, its machine ``saved.machine``.
    """

    # -- the machine -------------------------------------------------------------------------------
    def machine_choices(self) -> list[dict[str, Any]]:
        """The machine descriptions the New visit form offers (the example, the data folder's)."""
        from axiscal.workbench.machines import machine_choices

        return machine_choices(self.data)

    def machine_file(self) -> Path:
        """The visit's machine description (the example machine's while no visit names one)."""
        path = None if self.folder is None else self.folder / MACHINE_FILE
        return path if path is not None and path.is_file() else example_machine()

    def _axes(self) -> list[dict[str, Any]]:
        if self.saved is not None and self.saved.machine:
            return self.saved.machine["axes"]
        return machine_axes(self.machine_file())["axes"]

    def _chosen_machine(self, chosen: dict[str, Any], name: str) -> tuple[Any, dict[str, Any]]:
        """What the form chose (a path, or the new machine's fields) and its description; FormErrors naming the field."""
        choice = chosen.get("machine_choice") or EXAMPLE
        if not isinstance(choice, str):
            raise FormErrors({"machine_choice": "choose a machine"})
        if choice == "new":
            with tempfile.TemporaryDirectory(prefix="axiscal-machine-") as scratch:
                try:
                    described = write_new_machine(Path(scratch), name, chosen.get("machine_chain"),
                                                  chosen.get("machine_travels"))
                except AxiscalError as exc:
                    text = str(exc)
                    field = "machine_chain" if text.startswith("chain") else "machine" if text == "name the machine" else (
                        "machine_travels")
                    raise FormErrors({field: str(exc)}) from None
            return ("new", chosen.get("machine_chain"), chosen.get("machine_travels")), described
        path = example_machine() if choice == EXAMPLE else (self.data / choice).resolve()
        if choice != EXAMPLE and (self.data not in path.parents or not path.is_file()):
            raise FormErrors({"machine_choice": f"{choice}: no machine description there in the data folder"})
        try:
            return path, machine_axes(path)
        except AxiscalError as exc:
            raise FormErrors({"machine_choice": str(exc)}) from None

    def _checked_machine_and_tests(self, chosen: dict[str, Any], name: str) -> tuple[Any, dict[str, Any], list[dict[str, Any]]]:
        """The machine chosen and the tests wanted, every mistake named by its field."""
        source, described = self._chosen_machine(chosen, name)
        return source, described, wanted_tests(chosen.get("tests"), described["axes"])

    def _set_up_machine(self, folder: Path, source: Any, name: str) -> dict[str, Any]:
        if isinstance(source, tuple):
            return write_new_machine(folder, name, source[1], source[2])
        return copy_machine(source, folder)

    # -- the tests ---------------------------------------------------------------------------------
    def _tests(self) -> list[dict[str, Any]]:
        return list(self.saved.tests) if self.saved is not None else []

    def _test(self, test_id: Any, *, run: bool = False) -> dict[str, Any]:
        tests = self._tests()
        found = next((t for t in tests if t["id"] == test_id), None)
        if found is None:
            raise AxiscalError(f"the visit has no test {test_id!r} ({', '.join(t['id'] for t in tests) or 'none yet'})")
        if run and found["source"] != "run":
            raise AxiscalError(f"{found['label']} is taken from a file, not run here (add its file on New visit)")
        return found

    def tests(self) -> list[dict[str, Any]]:
        """The visit's tests, each with its state (planned, running, done, failed); campaign.toml brought up to date.

        Returns
        -------
        list of dict
            As :func:`axiscal.workbench.suite.state_of` gives them.
        """
        if self.folder is None or self.saved is None:
            return []
        self.write_campaign()
        run = self.run if self.phase == "as-found" else None
        return [state_of(t, self.folder, run) for t in self._tests()]

    def write_campaign(self) -> Path:
        """Write the visit's campaign.toml with the machine's model and every test whose data is in its folder.

        Returns
        -------
        Path
        """
        folder = self._visit_folder()
        model = MACHINE_FILE if (folder / MACHINE_FILE).is_file() else None
        path = folder / "campaign.toml"
        text = campaign_with_tests(self._render_campaign(), self._tests(), folder, model=model)
        if not path.is_file() or path.read_text(encoding="utf-8") != text:
            write_text(path, text)
        return path

    # -- tests from files --------------------------------------------------------------------------
    def data_files(self) -> list[str]:
        """The data folder's files a test may be taken from (relative paths), the visit's own first."""
        return data_files(self.data, self.folder)

    def upload(self, name: Any, content: bytes) -> dict[str, Any]:
        """Keep an uploaded file in the visit's ``files/``; its path relative to the data folder."""
        folder = self._visit_folder()
        return {"file": self._rel(store_upload(folder, name, content))}

    def add_file_test(self, data: Any) -> dict[str, Any]:
        """Add a test taken from a file and evaluate it at once through the campaign; the visit's tests.

        A positioning run of an axis whose test waits for its file (a rotary axis) is that test's data.

        Raises
        ------
        FormErrors
            For a field missing or wrong (the file not in the data folder).
        AxiscalError
            The one line the command's reader gives for a bad file (the file, the line, the problem);
            the test is not added.
        """
        from axiscal.campaign import load_campaign, run_test

        form = checked_file_form(data)
        folder = self._visit_folder()
        tests = self._tests()
        try:
            test = file_test(self.data, folder, form, {t["id"] for t in tests})
        except FormErrors:
            raise
        except AxiscalError as exc:  # an importer refused the export
            raise AxiscalError(self._as_named(exc, form, folder)) from None
        waiting = next((t for t in tests if t["source"] == "file" and not t["entry"] and test["kind"] == "positioning"
                        and t["axis"] == test["axis"]), None)
        if waiting is not None:
            test = waiting | {"entry": test["entry"]}
            tests = [test if t is waiting else t for t in tests]
        else:
            tests = tests + [test]
        model = MACHINE_FILE if (folder / MACHINE_FILE).is_file() else None
        path = folder / "campaign.toml"
        write_text(path, campaign_with_tests(self._render_campaign(), tests, folder, model=model))
        try:
            campaign = load_campaign(folder)
            spec = next(s for s in campaign.tests if s.id == test["id"])
            with self._plot_lock:
                run_test(campaign, spec)
        except AxiscalError as exc:
            self.write_campaign()  # as it was, without the test
            raise AxiscalError(self._as_named(exc, form, folder)) from None
        with self._lock:
            self.saved.tests = tests
            self._save()
        return {"added": test["id"], "tests": self.tests()}

    def _as_named(self, exc: AxiscalError, form: Any, folder: Path) -> str:
        """The reader's line with each file named as the form named it (not its copy in ``files/``, not absolute)."""
        message = str(exc)
        for name in (form.file, form.second):
            if name:
                message = message.replace(str(folder / FILES_FOLDER / Path(name).name), name)
        return message.replace(f"{self.data}/", "")

    def remove_test(self, test_id: Any) -> dict[str, Any]:
        """Take a test added from a file off the visit (its file stays in ``files/``); the visit's tests."""
        test = self._test(test_id)
        if test["source"] != "file":
            raise AxiscalError(f"{test['label']} is one the visit was written with: it stays")
        with self._lock:
            self.saved.tests = [t for t in self._tests() if t["id"] != test["id"]]
            self._save()
        return {"tests": self.tests()}
