"""The student process and the wire format, below the grader: limits, deaths, bad data."""

import secrets

import numpy as np
import pytest
from processes import wait_gone

from kinlib.grade._bwrap import find_sandbox
from kinlib.grade._sandbox import BLOCKED, Worker, WorkerDied, WorkerTimeout
from kinlib.grade._wire import Odd, WireError, decode, dumps, encode, loads


@pytest.fixture(scope="module")
def sandbox():
    return find_sandbox(BLOCKED)


def host_pids(marker: str) -> list[int]:
    """Processes on this machine (outside any sandbox) whose command line holds ``marker``."""
    import os

    found = []
    for pid in os.listdir("/proc"):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as fh:
                if marker.encode() in fh.read():
                    found.append(int(pid))
        except (OSError, ValueError):
            pass
    return found


def run_cells(worker, *sources, timeout=30.0):
    worker.request({"op": "cells", "cells": [[i, s] for i, s in enumerate(sources)]})
    events = []
    while True:
        m = worker.receive(timeout)
        events.append(m)
        if m["ev"] == "cells_done":
            return [e for e in events if e.get("phase") == "end"]


def test_memory_limit_stops_a_growing_allocation(sandbox):
    # 2.5 GB in 250 MB steps: fine for this machine, over the 1 GiB limit given here
    grow = ("import numpy as np\nkeep = []\nfor _ in range(10):\n"
            "    keep.append(np.ones(31_250_000))")
    with Worker(sandbox=sandbox, memory_mb=1024) as w:
        (end,) = run_cells(w, grow)
        assert not end["ok"] and "MemoryError" in end["error"]
    with Worker(sandbox=sandbox, memory_mb=4096) as w:  # the control: a higher limit
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
        for _ in range(100):  # the grandchild, seen from outside
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
