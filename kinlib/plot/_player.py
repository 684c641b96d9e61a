"""matplotlib's animation player without the network (private).

``Animation.to_jshtml()`` draws its buttons with Font Awesome, a stylesheet it links from a
CDN: on a machine that cannot reach it (a remote lab, a hub behind a firewall, a laptop
offline) the buttons are blank, and every page that shows a player asks the internet for
it. :func:`offline_player` drops the link and writes each button's icon as a Unicode
symbol instead.
"""

from __future__ import annotations

import re

__all__ = ["offline_player"]

_FONT_AWESOME = re.compile(r'<link\b[^>]*font-awesome[^>]*>')
_ICONS = {"fa-minus": "−", "fa-fast-backward": "⇤", "fa-step-backward": "◁",
          "fa-play fa-flip-horizontal": "◀", "fa-pause": "❚❚", "fa-play": "▶",
          "fa-step-forward": "▷", "fa-fast-forward": "⇥", "fa-plus": "+"}


def offline_player(html: str) -> str:
    """``html`` with matplotlib animation players that need no icon font: the Font Awesome
    stylesheet link is dropped and each button icon becomes a Unicode symbol.

    >>> offline_player('<button title="Play"><i class="fa fa-play"></i></button>')
    '<button title="Play"><span class="kl-icon">▶</span></button>'
    """
    html = _FONT_AWESOME.sub("", html)
    return re.sub(r'<i class="fa ((?:fa-[a-z-]+ ?)+)"></i>',
                  lambda m: f'<span class="kl-icon">{_ICONS.get(m.group(1).strip(), "?")}</span>',
                  html)
