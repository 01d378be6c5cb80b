"""Every machine's history read at once is each machine's history read alone."""

from __future__ import annotations

from axiscal.history import Drift, add_results, drifting_results, machine_histories, machine_history, write_results


def test_all_histories_at_once_are_those_read_one_by_one(tmp_path):
    url = str(tmp_path / "h.sqlite")
    assert machine_histories(url=url) == []
    for k, (name, serial) in enumerate((("Lathe", "L1"), ("Lathe", "L2"), ("Mill", ""))):
        payloads = drifting_results({"positioning.X.E": Drift(10.0 + k, 2.0, 0.5, 40.0)}, machine=name, serial=serial,
                                    campaigns=2 + k, seed=k)
        add_results(write_results(tmp_path / f"m{k}", payloads), url=url)
    every = machine_histories(url=url)
    assert [h.label for h in every] == ["Lathe (L1)", "Lathe (L2)", "Mill"]
    assert every == [machine_history(h.label, url=url) for h in every]
    assert [len(h.campaigns) for h in every] == [2, 3, 4]
