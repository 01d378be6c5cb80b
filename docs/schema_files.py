"""Write what docs/ shows of the declared file formats: docs/schemas/NAME.json and the key tables of
docs/formats.md (between the ``<!-- keys: NAME -->`` and ``<!-- end of keys -->`` lines).

Run ``python docs/schema_files.py`` after changing a format (src/axiscal/io/formats/);
tests/io/test_formats.py fails while the committed files differ from what the models give.
"""

from __future__ import annotations

import re
from pathlib import Path

from axiscal.io.formats.catalogue import FORMATS, json_schema_text, key_tables

DOCS = Path(__file__).resolve().parent
BLOCK = re.compile(r"(<!-- keys: (?P<name>[\w-]+) -->\n)(.*?)(<!-- end of keys -->)", re.S)


def formats_page(text: str) -> str:
    """``text`` (docs/formats.md) with every key block regenerated."""
    return BLOCK.sub(lambda m: m.group(1) + "\n" + key_tables(m.group("name")) + "\n" + m.group(4), text)


def main() -> None:
    for name in FORMATS:
        (DOCS / "schemas" / f"{name}.json").write_text(json_schema_text(name), encoding="utf-8")
    page = DOCS / "formats.md"
    page.write_text(formats_page(page.read_text(encoding="utf-8")), encoding="utf-8")


if __name__ == "__main__":
    main()
