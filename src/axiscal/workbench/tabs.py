"""Which of the browser's tabs may change the open visit: one holds it, the others follow it read-only.

The page sends its tab's id (kept over a reload of the tab, not shared with another tab) with every
call and opens its stream with it. The first tab that changes the visit holds it for as long as its
stream is open; another tab is refused (:class:`OpenElsewhere`) and shown the visit read-only. Once
the holding tab's stream has closed (the tab was closed), the next tab that acts takes it over. A
call without a tab id (a script, a test) is no tab's and is let through.
"""

from __future__ import annotations

import threading

from axiscal.errors import AxiscalError

__all__ = ["OpenElsewhere", "Tabs"]


class OpenElsewhere(AxiscalError):
    """The visit is held by another tab whose page is open: this one follows it read-only.

    Parameters
    ----------
    message : str
        One line, as :class:`~axiscal.errors.AxiscalError` takes it.
    """


class Tabs:
    """The tab that holds the visit and the tabs whose page is open.

    Attributes
    ----------
    owner : str or None
        The id of the tab that holds the visit (None: no tab has changed it yet).
    """

    def __init__(self) -> None:
        self.owner: str | None = None
        self._open: dict[str, int] = {}
        self._lock = threading.Lock()

    def may_act(self, tab: str | None) -> bool:
        """Whether ``tab`` may change the visit now (its holder, or any while the holder's page is closed).

        Parameters
        ----------
        tab : str or None
            A tab id; None (no tab's call) may.

        Returns
        -------
        bool
        """
        owner = self.owner
        return tab is None or owner is None or owner == tab or self._open.get(owner, 0) == 0

    def claim(self, tab: str | None) -> None:
        """Let ``tab`` change the visit, making it the holder.

        Parameters
        ----------
        tab : str or None

        Raises
        ------
        OpenElsewhere
            When another tab holds the visit and its page is still open.
        """
        if tab is None:
            return
        with self._lock:
            if not self.may_act(tab):
                raise OpenElsewhere("the visit is open in another tab: this one follows it read-only (close the other"
                                    " tab to work here)")
            self.owner = tab

    def attach(self, tab: str) -> None:
        """A tab's stream opened (its page is open).

        Parameters
        ----------
        tab : str
        """
        with self._lock:
            self._open[tab] = self._open.get(tab, 0) + 1

    def detach(self, tab: str) -> None:
        """A tab's stream closed (its page was closed or reloaded).

        Parameters
        ----------
        tab : str
        """
        with self._lock:
            left = self._open.get(tab, 0) - 1
            if left > 0:
                self._open[tab] = left
            else:
                self._open.pop(tab, None)
