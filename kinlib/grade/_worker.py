"""The student's process: runs a submission's cells, then calls its functions on cases.

Started by :mod:`kinlib.grade._sandbox` as ``python -I [-S] path/to/_worker.py CONFIG``,
``CONFIG`` a JSON object: ``fds`` (two pipe file descriptors: requests arrive on the first,
replies leave on the second, one JSON line each, :mod:`kinlib.grade._wire`), ``blocked``
(modules the submission may not import), ``path`` (directories put first on ``sys.path``:
the sandbox's libraries), ``uid`` (drop to this uid first: the sandbox run by root),
``nproc`` (the cap on processes) and, in the container tier, ``confine`` (what
:mod:`kinlib.grade._confine` applies before anything else: the uid, limits, Landlock and
seccomp; if that fails the process exits, status 72, having run nothing). The student's
own printing goes to ``/dev/null`` (fd 1 and 2 are redirected before any of their code
runs), so it cannot be mistaken for a reply.

Requests and replies:

- ``{"op": "cells", "cells": [[i, source], ...]}`` → for each cell ``{"ev": "cell", "i": i,
  "phase": "start"}`` then ``{"ev": "cell", "i": i, "phase": "end", "ok": bool, "error":
  str}``; finally ``{"ev": "cells_done"}``.
- ``{"op": "call", "id": n, "name": f, "cases": [[args...], ...]}`` → ``{"ev": "missing",
  "what": ...}`` if ``f`` is not a function of the submission, else one ``{"ev": "case",
  "i": k, "ok": bool, "value" | "error": ...}`` per case; finally ``{"ev": "call_done"}``;
  every reply carries the call's ``id``, a random token (the grader drops other replies).
- ``{"op": "probe", "read": [...], "write": [...], "imports": [...]}`` (the container tier
  only, before any cell) → ``{"ev": "probe", ...}``: what the confined process can still
  do (:func:`kinlib.grade._confine.probe`).
- ``{"op": "exit"}``.

Nothing here is trusted by the grader: it compares the values itself, in its own process.

The worker does not import kinlib (its wire format is loaded from ``_wire.py`` by path). In
the sandbox (:mod:`kinlib.grade._bwrap`) kinlib and the peer libraries are not there at
all; the ``blocked`` modules are refused by an import hook as well (in the unsandboxed mode
that hook is all there is, and a determined submission can remove it).
"""

from __future__ import annotations

import importlib.util
import os
import re
import resource
import sys
import traceback

decode = dumps = encode = loads = None  # from _wire.py, loaded by _load_wire()


def _load_wire() -> None:
    global decode, dumps, encode, loads
    spec = importlib.util.spec_from_file_location(
        "_kinlib_wire", os.path.join(os.path.dirname(os.path.abspath(__file__)), "_wire.py"))
    wire = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(wire)
    decode, dumps, encode, loads = wire.decode, wire.dumps, wire.encode, wire.loads


def _become(uid: int | None, nproc: int | None) -> None:
    """Drop root (the sandbox run by root) and cap the processes, before anything else."""
    if uid is not None:
        os.setgroups([])
        os.setresgid(uid, uid, uid)
        os.setresuid(uid, uid, uid)
        if 0 in os.getresuid() or 0 in os.getresgid():
            os._exit(70)
    if nproc:
        resource.setrlimit(resource.RLIMIT_NPROC, (nproc, nproc))

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


def _load_confine():
    """:mod:`kinlib.grade._confine`, loaded by path (the container tier)."""
    spec = importlib.util.spec_from_file_location(
        "_kinlib_confine",
        os.path.join(os.path.dirname(os.path.abspath(__file__)), "_confine.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main(config: dict) -> None:
    here = os.path.dirname(os.path.abspath(__file__))
    sys.path[:0] = list(config.get("path", ()))
    _load_wire()  # (before dropping root: the worker's files may be root's alone)
    confine = None
    if config.get("confine"):  # the container tier: confined here, before any cell runs
        sys.path[:] = [p for p in sys.path if os.path.abspath(p) != here]
        confine = _load_confine()
        try:
            confine.confine(config["confine"])
        except BaseException:
            os._exit(72)  # never run a submission unconfined
    else:
        _become(config.get("uid"), config.get("nproc"))
    fd_in, fd_out = config["fds"]
    names = list(config.get("blocked", ()))
    for n in list(sys.modules):
        if n.split(".")[0] in names:
            del sys.modules[n]
    sys.meta_path.insert(0, _Blocker(names))
    requests = os.fdopen(fd_in, "rb", buffering=0)
    replies = os.fdopen(fd_out, "wb", buffering=0)

    # the student's printing is not kept (it cannot fill a disk or pass for a reply)
    null = os.open(os.devnull, os.O_RDWR)
    for fd in (0, 1, 2):
        os.dup2(null, fd)
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
        elif op == "probe" and confine is not None:  # what the confinement still allows
            replies.write(dumps({"ev": "probe", **confine.probe(request)}))
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
            value = fn(*decode(args, sympy=True))  # (sympy imported when a sympy value comes)
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
    import json

    main(json.loads(sys.argv[1]))
