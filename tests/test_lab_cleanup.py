"""The JupyterLab harness leaves nothing behind: not when a test fails, not when pytest
itself is killed.

Each case runs pytest in a subprocess on a small test file that starts a ``Lab``, opens a
one-cell notebook in it through the server's REST API (a session, as JupyterLab opens a
notebook: the server starts its kernel), runs the cell in that kernel (it opens a 3-D
viewer; the viewer widget starts no process of its own), records the pids that carry the
run's marker, and then fails (``fail``) or waits to be SIGKILLed (``kill``). Afterwards no
process may carry the marker and the port must be closed. The recorded pids are the
control: the processes existed while the test ran. (No browser: the page holds no process
of the harness; the browser suite, ``test_lab.py``, checks the same ``Lab.stop`` after its
run of every notebook.)
"""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import nbformat
import pytest
from lab_harness import marked_processes

TESTS = Path(__file__).resolve().parent
VIEWER = """from kinlib.robots import autorob_test_robot
from kinlib.viz import RobotVisualizer

viz = RobotVisualizer(autorob_test_robot(), prefix="cleanup")
viz.jupyter_cell(height=200)"""
INNER = '''
import json, os, sys, time
from pathlib import Path
from queue import Empty
import pytest
from jupyter_client import BlockingKernelClient
from lab_harness import Lab, marked_processes

RECORD = Path(os.environ["RECORD"])


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    server = Lab(Path(os.environ["NOTEBOOKS"]), tmp_path_factory.mktemp("lab"))
    try:
        yield server
    finally:
        server.stop()


def cmdline(pid):
    try:
        return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\\0", b" ").decode()
    except OSError:
        return ""


def test_inner(lab):
    name = "00_viewer.ipynb"
    session = lab.api("POST", "api/sessions", timeout=60, body={
        "path": name, "name": name, "type": "notebook", "kernel": {"name": "python3"}})
    connection = lab.work / "runtime" / f"kernel-{session['kernel']['id']}.json"
    client = BlockingKernelClient(connection_file=str(connection))
    client.load_connection_file()
    client.start_channels()
    try:
        # the kernel is ready once it answers kernel_info (not wait_for_ready: a client that
        # no manager made also asks for heartbeats, and on a loaded machine one that comes
        # a second late made it report the kernel dead)
        deadline = time.monotonic() + 60
        while True:
            asked = client.kernel_info()
            try:
                reply = client.get_shell_msg(timeout=5)
            except Empty:  # no answer yet
                assert time.monotonic() < deadline, "the kernel did not answer kernel_info"
                continue
            if reply["parent_header"].get("msg_id") == asked:
                break
        code = json.loads((lab.root / name).read_text())["cells"][0]["source"]
        reply = client.execute_interactive("".join(code), timeout=120)
        assert reply["content"]["status"] == "ok", reply["content"]
    finally:
        client.stop_channels()
    pids = marked_processes(lab.marker)
    RECORD.write_text(json.dumps({"marker": lab.marker, "port": lab.port, "root": str(lab.root),
                                  "pytest": os.getpid(),
                                  "processes": {p: cmdline(p) for p in pids}}))
    if os.environ["MODE"] == "kill":
        time.sleep(300)  # the outer test kills this pytest
    assert False, "a deliberate failure, with the lab running"
'''


def _cmdline(pid: int | str) -> str:
    return Path(f"/proc/{pid}/cmdline").read_bytes().replace(b"\0", b" ").decode(
        errors="replace")


def _listeners(port: int) -> list[str]:
    """The command lines of the processes listening on TCP ``port`` (from /proc/net: a
    socket in LISTEN state, and the processes holding it; "?" for one whose holder is not
    found). Connecting would not do: on a busy machine another test's server or kernel may
    be given the freed port, and a connect to a port nobody listens on can even succeed
    (a socket connected to itself, when its own ephemeral port is that port)."""
    inodes = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        try:
            rows = Path(table).read_text().splitlines()[1:]
        except OSError:
            continue
        for row in rows:
            f = row.split()
            if int(f[1].rsplit(":", 1)[1], 16) == port and f[3] == "0A":  # 0A: LISTEN
                inodes.add(f[9])
    holders = {}
    for entry in os.listdir("/proc") if inodes else []:
        if not entry.isdigit():
            continue
        try:
            fds = os.listdir(f"/proc/{entry}/fd")
            for fd in fds:
                link = os.readlink(f"/proc/{entry}/fd/{fd}")
                if link.startswith("socket:[") and link[8:-1] in inodes:
                    holders[link[8:-1]] = _cmdline(entry)
        except OSError:
            continue
    return [holders.get(inode, "?") for inode in sorted(inodes)]


@pytest.mark.parametrize("mode", ["fail", "kill"])
def test_lab_leaves_nothing_running(mode, tmp_path):
    (tmp_path / "test_inner.py").write_text(INNER)
    notebooks = tmp_path / "notebooks"
    notebooks.mkdir()
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(VIEWER)])
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nbformat.write(nb, notebooks / "00_viewer.ipynb")
    record = tmp_path / "record.json"
    env = dict(os.environ, RECORD=str(record), MODE=mode, NOTEBOOKS=str(notebooks),
               PYTHONPATH=os.pathsep.join([str(TESTS), os.environ.get("PYTHONPATH", "")]))
    env.pop("PYTEST_ADDOPTS", None)  # the outer run's options are not the inner one's
    inner = subprocess.Popen([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                              "-p", "no:randomly", str(tmp_path / "test_inner.py")],
                             cwd=tmp_path, env=env, stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, start_new_session=True)
    try:
        if mode == "kill":
            deadline = time.monotonic() + 120
            while not record.exists() and inner.poll() is None \
                    and time.monotonic() < deadline:
                time.sleep(0.2)
            assert record.exists(), inner.communicate(timeout=30)[0].decode()[-3000:]
            os.kill(inner.pid, signal.SIGKILL)
        out = inner.communicate(timeout=180)[0].decode()
    finally:
        if inner.poll() is None:
            os.killpg(inner.pid, signal.SIGKILL)
    assert record.exists(), f"the inner test did not get as far as the record:\n{out[-3000:]}"
    facts = json.loads(record.read_text())
    running = " ".join(facts["processes"].values())
    assert "jupyter" in running and "ipykernel" in running, running  # the control
    assert "meshcat" not in running, running  # the viewer is a widget: no server
    assert facts["root"] in running, running  # the port check below knows the server by it
    if mode == "fail":
        assert inner.returncode == 1 and "a deliberate failure" in out, out[-3000:]
    else:
        assert inner.returncode == -signal.SIGKILL
    deadline = time.monotonic() + 30
    while (left := marked_processes(facts["marker"])) and time.monotonic() < deadline:
        time.sleep(0.25)
    assert not left, f"left running after the {mode}: " + "; ".join(
        facts["processes"].get(str(p), str(p)) for p in left)
    # nothing of this run listens on its port (another test's process may, since it was freed)
    ours = [c for c in _listeners(facts["port"]) if c == "?" or facts["root"] in c]
    assert not ours, f"JupyterLab's port is still open: {ours}"


def test_the_port_check_sees_a_listener():
    """The control for the port check: a socket listening here is found, with this
    process's command line; once closed, nothing listens."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
        assert _listeners(port) == []  # bound, not listening
        s.listen()
        found = _listeners(port)
        assert found == [_cmdline("self")], found
    assert _listeners(port) == []
