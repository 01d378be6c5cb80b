"""The certificate's languages: gettext catalogs (Babel), and numbers and dates as each language writes them.

The texts of the certificate (its templates and the sentences :mod:`axiscal.report.certificate`
builds) are English message ids; each other language has a catalog
``templates/locale/LANG/LC_MESSAGES/axiscal.po``, read with Babel and compiled in memory on first
use. English needs no catalog. A language without a complete catalog is refused, never shown with
English in between (the suite checks that every message has its translation).
"""

from __future__ import annotations

import datetime as _dt
import functools
import gettext
import io
import math
import re
from importlib import resources
from typing import Any

from axiscal.errors import AxiscalError

__all__ = ["DOMAIN", "catalog_path", "translations", "format_decimal_for", "format_date_for"]

#: the gettext domain of axiscal's catalogs
DOMAIN = "axiscal"


def catalog_path(language: str):
    """The ``.po`` catalog of ``language`` among the package's templates.

    Parameters
    ----------
    language : str
        ISO 639-1 code.

    Returns
    -------
    importlib.resources.abc.Traversable
    """
    if not isinstance(language, str) or not re.fullmatch(r"[a-z]{2}", language):
        raise AxiscalError(f"language must be an ISO 639-1 code such as 'de', not {language!r}"[:200])
    return resources.files("axiscal") / "templates" / "locale" / language / "LC_MESSAGES" / f"{DOMAIN}.po"


@functools.cache
def translations(language: str) -> gettext.NullTranslations:
    """The translations into ``language`` (``"en"``: the message ids themselves).

    Parameters
    ----------
    language : str
        ISO 639-1 code.

    Returns
    -------
    gettext.NullTranslations
        With ``gettext`` and ``ngettext``; Jinja2's i18n extension takes it as it is.

    Raises
    ------
    AxiscalError
        For a language without a catalog.
    """
    if language == "en":
        return gettext.NullTranslations()
    if not isinstance(language, str) or not re.fullmatch(r"[a-z]{2}", language):
        raise AxiscalError(f"language must be an ISO 639-1 code such as 'de', not {language!r}"[:200])
    path = catalog_path(language)
    if not path.is_file():
        raise AxiscalError(f"no translation of the certificate into '{language}' (languages: en, de)")
    from babel.messages.mofile import write_mo
    from babel.messages.pofile import read_po

    with path.open("rb") as handle:
        catalog = read_po(handle, locale=language, domain=DOMAIN)
    compiled = io.BytesIO()
    write_mo(compiled, catalog)
    compiled.seek(0)
    return gettext.GNUTranslations(compiled)


def format_decimal_for(value: Any, digits: int, language: str) -> str:
    """A number with ``digits`` decimals as ``language`` writes it (``1.234`` in English, ``1,234`` in German).

    Parameters
    ----------
    value : float, int, str or None
        A text is returned as it is; None or a non-finite value is ``n/a``.
    digits : int
        Decimals (whole numbers are printed whole).
    language : str

    Returns
    -------
    str
    """
    from babel.numbers import format_decimal

    translations(language)  # a language with a catalog
    if not isinstance(digits, int) or isinstance(digits, bool) or not 0 <= digits <= 15:
        raise AxiscalError(f"digits must be a whole number of decimals from 0 to 15, not {digits!r}"[:200])
    if value is None or isinstance(value, str):
        return "n/a" if value is None else value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise AxiscalError(f"value must be a number, a text or None, not {type(value).__name__}")
    if isinstance(value, int):
        return format_decimal(value, locale=language, group_separator=False)
    value = float(value)
    if not math.isfinite(value):
        return "n/a"
    pattern = "0." + "0" * digits if digits > 0 else "0"
    return format_decimal(round(value, digits) + 0.0, format=pattern, locale=language, group_separator=False)


def format_date_for(value: str | _dt.date, language: str) -> str:
    """A date as ``language`` writes it in full (``28 November 2026``, ``28. November 2026``).

    Parameters
    ----------
    value : str or datetime.date
        An ISO date (``2026-11-28``).
    language : str

    Returns
    -------
    str
    """
    from babel.dates import format_date

    translations(language)  # a language with a catalog
    try:
        day = value if isinstance(value, _dt.date) else _dt.date.fromisoformat(value[:10])
    except (TypeError, ValueError):
        raise AxiscalError(f"value must be a date or an ISO date (2026-11-28), not {value!r}"[:200]) from None
    return format_date(day, format="long", locale=language)
