"""``axiscal capture`` interrupted (Ctrl-C): one line naming the partial file and --resume."""

from __future__ import annotations

import axiscal.capture.files


def _interrupted(after_partial: bool):
    def capture_to_file(plan_csv, source, output, **_):
        if after_partial:
            axiscal.capture.files.partial_path(output).write_text("step,reading_m\n1,0.0\n")
        raise KeyboardInterrupt

    return capture_to_file


def test_ctrl_c_names_the_partial_file_and_resume(run_cli, examples, tmp_path, monkeypatch):
    monkeypatch.setattr(axiscal.capture.files, "capture_to_file", _interrupted(after_partial=True))
    out = tmp_path / "run.csv"
    status, _, err = run_cli("capture", examples / "capture" / "plan_x.csv", "--from", examples / "capture" / "recording_x.csv",
                             "-o", out)
    assert status == 1
    assert err == (f"axiscal: error: capture interrupted: the stops taken so far are in {out}.partial; run the same "
                   "command with --resume to continue it\n")


def test_ctrl_c_before_the_first_stop_says_nothing_was_written(run_cli, examples, tmp_path, monkeypatch):
    monkeypatch.setattr(axiscal.capture.files, "capture_to_file", _interrupted(after_partial=False))
    status, _, err = run_cli("capture", examples / "capture" / "plan_x.csv", "--from", examples / "capture" / "recording_x.csv",
                             "-o", tmp_path / "run.csv")
    assert status == 1 and err == "axiscal: error: capture interrupted before its first stop: nothing was written\n"
