"""kinlib.viz stays out of ``import kinlib``; the session's meshcat server is the right one."""

import os
import subprocess
import sys

import pytest

ZMQ_ENV, WEB_ENV, PID_ENV = ("KINLIB_MESHCAT_ZMQ_URL", "KINLIB_MESHCAT_WEB_URL",
                             "KINLIB_MESHCAT_SERVER_PID")


def test_import_kinlib_does_not_load_meshcat_or_widgets():
    code = ("import sys, kinlib, kinlib.holonomic, kinlib.robots\n"
            "heavy = ('meshcat', 'ipywidgets', 'kinlib.viz', 'zmq')\n"
            "bad = [m for m in heavy if m in sys.modules]\n"
            "assert not bad, bad\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


def _listening_ports(pid):
    inodes = set()
    for fd in os.listdir(f"/proc/{pid}/fd"):
        target = os.readlink(f"/proc/{pid}/fd/{fd}")
        if target.startswith("socket:["):
            inodes.add(target[8:-1])
    ports = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        with open(table) as fh:
            for line in fh.readlines()[1:]:
                cols = line.split()
                if cols[3] == "0A" and cols[9] in inodes:  # 0A = LISTEN
                    ports.add(int(cols[1].rsplit(":", 1)[1], 16))
    return ports


def test_session_server_is_alive_and_is_the_one_in_the_env():
    pid = os.environ.get(PID_ENV)
    if pid is None:
        pytest.skip(f"{ZMQ_ENV} was given from outside; conftest started no server")
    if not os.path.isdir("/proc"):
        pytest.skip("needs /proc (Linux)")
    with open(f"/proc/{pid}/cmdline", "rb") as fh:
        assert b"meshcat.servers.zmqserver" in fh.read()
    assert os.getpgid(int(pid)) == int(pid)  # its own process group: killed as one
    port = int(os.environ[ZMQ_ENV].rsplit(":", 1)[1])
    web_port = int(os.environ[WEB_ENV].split(":")[2].split("/")[0])
    assert {port, web_port} <= _listening_ports(pid)
