"""_live.py: molscope.live(), the live browser view of the session (doc/live.md) in a
notebook cell. It starts the live server of `display live on` (loopback only, its random
token in the URL) and returns a LiveView whose _repr_html_ is an iframe on that URL.

The server runs on Tcl's event loop, in the thread that imported molscope. Inside Jupyter
that thread runs an asyncio loop, so live() has it run molscope's pending events every
20 ms; a plain script lets the server answer by calling view.serve(seconds)."""
import asyncio
import html
import urllib.parse

import _molscope

from ._tcl import call, split

_TICK_S = 0.02
_ticker = None      # the asyncio handle running the events, while the server is on


def _status():
    """`display live status` as a dict, or None when the server is off."""
    words = split(call("display", "live", "status"))
    return None if words == ["off"] else dict(zip(words[::2], words[1::2]))


def _tick(loop):
    global _ticker
    if _status() is None:
        _ticker = None
        return
    _molscope.pump(0)
    _ticker = loop.call_later(_TICK_S, _tick, loop)


def _start_ticker():
    """Run the server's events from the thread's asyncio loop, when one runs (Jupyter)."""
    global _ticker
    try:
        loop = asyncio.get_running_loop()
    except RuntimeError:
        return False
    if _ticker is None:
        _ticker = loop.call_later(_TICK_S, _tick, loop)
    return True


class LiveView:
    """The live view: url (with its token), port, token; _repr_html_ (an iframe), serve,
    stop."""

    def __init__(self, url, width, height):
        self.url = url
        parts = urllib.parse.urlsplit(url)
        self.port = parts.port
        self.token = urllib.parse.parse_qs(parts.query).get("token", [""])[0]
        self.width, self.height = width, height

    @property
    def running(self):
        st = _status()
        return st is not None and st.get("url") == self.url

    def serve(self, seconds):
        """Answer the browser for that many seconds (a script outside Jupyter)."""
        _molscope.pump(float(seconds))

    def stop(self):
        """Stop the server (`display live off`); its port is closed."""
        if self.running:
            call("display", "live", "off")

    def _repr_html_(self):
        return ('<iframe src="%s" width="%d" height="%d" style="border:0" '
                'title="molscope live view"></iframe>'
                % (html.escape(self.url, quote=True), self.width, self.height))

    def __repr__(self):
        return "<molscope.LiveView %s%s>" % (self.url, "" if self.running else " (stopped)")


def live(port=0):
    """Start the live view on 127.0.0.1 (port 0: a free one), or return the one running, as a
    LiveView that Jupyter shows as an iframe. Errors (no libmicrohttpd in this build, a port
    in use) raise TclError with molscope's message."""
    st = _status()
    url = call("display", "live", "on", int(port)) if st is None else st["url"]
    w, h = (int(x) for x in split(call("display", "get", "size")))
    _start_ticker()
    return LiveView(url, w + 24, h + 80)


__all__ = ["live", "LiveView"]
