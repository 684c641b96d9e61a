"""The student's process: runs a submission's cells, then calls its functions on cases.

Started by :mod:`kinlib.grade._sandbox` as ``python -I path/to/_worker.py IN OUT BLOCKED``
with two pipe file descriptors: requests arrive on ``IN``, replies leave on ``OUT``, one
JSON line each (:mod:`kinlib.grade._wire`). The student's own printing goes to a file (fd 1
and 2 are redirected before any of their code runs), so it cannot be mistaken for a reply.

Requests and replies:

- ``{"op": "cells", "cells": [[i, source], ...]}`` → for each cell ``{"ev": "cell", "i": i,
  "phase": "start"}`` then ``{"ev": "cell", "i": i, "phase": "end", "ok": bool, "error":
  str}``; finally ``{"ev": "cells_done"}``.
- ``{"op": "call", "id": n, "name": f, "cases": [[args...], ...]}`` → ``{"ev": "missing",
  "what": ...}`` if ``f`` is not a function of the submission, else one ``{"ev": "case",
  "i": k, "ok": bool, "value" | "error": ...}`` per case; finally ``{"ev": "call_done"}``;
  every reply carries the call's ``id``, a random token (the grader drops other replies).
- ``{"op": "exit"}``.

Nothing here is trusted by the grader: it compares the values itself, in its own process.

The worker does not import kinlib (its wire format is loaded from ``_wire.py`` by path), and
the modules named in ``BLOCKED`` (comma-separated: kinlib and the peer libraries) cannot be
imported by the submission, so an answer cannot simply be the reference's.
"""

from __future__ import annotations

import importlib.util
import os
import re
import sys
import traceback

_spec = importlib.util.spec_from_file_location(
    "_kinlib_wire", os.path.join(os.path.dirname(os.path.abspath(__file__)), "_wire.py"))
_wire = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(_wire)
decode, dumps, encode, loads = _wire.decode, _wire.dumps, _wire.encode, _wire.loads

_MAGIC = re.compile(r"^(\s*)[%!].*$", re.M)


def _error_text(exc: BaseException, limit: int = 600) -> str:
    try:
        lines = traceback.format_exception_only(type(exc), exc)
        text = "".join(lines).strip()
    except BaseException:
        text = type(exc).__name__
    return text[:limit]


def _where(exc: BaseException) -> str:
    """The last line of the student's own code in the traceback, e.g. 'cell 3, line 7'."""
    try:
        tb = traceback.extract_tb(exc.__traceback__)
        for frame in reversed(tb):
            if frame.filename.startswith("<cell "):
                return f"{frame.filename[1:-1]}, line {frame.lineno}"
    except BaseException:
        pass
    return ""


def _strip_magics(source: str) -> str:
    """IPython magics and shell escapes (``%matplotlib``, ``!pip``) become ``pass``."""
    return _MAGIC.sub(lambda m: m.group(1) + "pass", source)


def _display(*objs, **kwargs) -> None:
    """Stands in for IPython's ``display`` outside a kernel: shows nothing."""


class _Blocker:
    """A meta-path finder that refuses the blocked top-level modules."""

    def __init__(self, names):
        self.names = frozenset(names)

    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in self.names:
            raise ImportError(f"{name} cannot be used in this assignment: write the code "
                              "yourself with numpy")
        return None


def main(fd_in: int, fd_out: int, blocked: str = "") -> None:
    names = [n for n in blocked.split(",") if n]
    for n in list(sys.modules):
        if n.split(".")[0] in names:
            del sys.modules[n]
    sys.meta_path.insert(0, _Blocker(names))
    requests = os.fdopen(fd_in, "rb", buffering=0)
    replies = os.fdopen(fd_out, "wb", buffering=0)

    # the student's printing goes to output.txt in the (temporary) working directory
    log = os.open("output.txt", os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o600)
    os.dup2(log, 1)
    os.dup2(log, 2)
    os.close(log)
    null = os.open(os.devnull, os.O_RDONLY)
    os.dup2(null, 0)
    os.close(null)
    sys.stdout = open(1, "w", buffering=1, closefd=False)
    sys.stderr = open(2, "w", buffering=1, closefd=False)

    namespace = {"__name__": "__main__", "display": _display}
    while True:
        line = requests.readline()
        if not line:
            os._exit(0)
        request = loads(line)
        op = request.get("op")
        if op == "exit":
            os._exit(0)
        elif op == "cells":
            _cells(namespace, request["cells"], replies)
        elif op == "call":
            _call(namespace, request["name"], request["cases"], request.get("id"), replies)
        else:
            replies.write(dumps({"ev": "error", "error": f"unknown op {op!r}"}))


def _cells(namespace: dict, cells: list, replies) -> None:
    for i, source in cells:
        replies.write(dumps({"ev": "cell", "i": i, "phase": "start"}))
        try:
            code = compile(_strip_magics(source), f"<cell {i}>", "exec")
            exec(code, namespace)  # running the submission is the point
            end = {"ev": "cell", "i": i, "phase": "end", "ok": True}
        except BaseException as exc:  # SystemExit, KeyboardInterrupt too
            end = {"ev": "cell", "i": i, "phase": "end", "ok": False,
                   "error": _error_text(exc), "where": _where(exc)}
        replies.write(dumps(end))
    replies.write(dumps({"ev": "cells_done"}))


def _call(namespace: dict, name: str, cases: list, call_id, replies) -> None:
    fn = namespace.get(name)
    if fn is None or not callable(fn):
        what = "not defined" if fn is None else f"a {type(fn).__name__}, not a function"
        replies.write(dumps({"ev": "missing", "what": what, "id": call_id}))
        replies.write(dumps({"ev": "call_done", "id": call_id}))
        return
    for k, args in enumerate(cases):
        try:
            value = fn(*decode(args))
        except BaseException as exc:
            payload = dumps({"ev": "case", "i": k, "ok": False, "error": _error_text(exc),
                             "where": _where(exc), "id": call_id})
        else:
            try:
                payload = dumps({"ev": "case", "i": k, "ok": True, "value": encode(value),
                                 "id": call_id})
            except BaseException as exc:  # e.g. a __dir__ that raises
                payload = dumps({"ev": "case", "i": k, "ok": False, "id": call_id,
                                 "error": "the returned value could not be read: "
                                          + _error_text(exc, 200)})
        replies.write(payload)
    replies.write(dumps({"ev": "call_done", "id": call_id}))


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]), sys.argv[3] if len(sys.argv) > 3 else "")
