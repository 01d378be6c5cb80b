"""Where a test's key stands in campaign.toml: a refused option is named at its own line, not at its ``[[tests]]`` header."""

from __future__ import annotations

from axiscal.campaign.config import Campaign, TestSpec

__all__ = ["key_line"]


def key_line(campaign: Campaign, spec: TestSpec, key: str) -> int:
    """The line of ``key`` in the test's ``[[tests]]`` entry of campaign.toml, else the entry's own line.

    Parameters
    ----------
    campaign : Campaign
        The checked campaign (its folder holds campaign.toml).
    spec : TestSpec
        The test (its ``line`` is its ``[[tests]]`` header's).
    key : str
        The key as the file writes it (``window_ms``).

    Returns
    -------
    int
        1-based line number.
    """
    from axiscal.io.arguments import check_instance
    from axiscal.io.schema import TomlLines
    from axiscal.io.tabular import read_text

    check_instance("campaign", campaign, Campaign)
    check_instance("spec", spec, TestSpec)
    check_instance("key", key, str)

    lines = TomlLines(read_text(campaign.folder / "campaign.toml"))
    index = next((i for (table, i), line in lines.tables.items() if table == "tests" and line == spec.line), None)
    found = None if index is None else lines.of("tests", index, key)
    return spec.line if found is None or found < spec.line else found
