"""A visualizer's own meshcat server never outlives its Python process or kernel.

The control case shows the tests can fail: a server started the way meshcat starts it
(``meshcat.Visualizer()``) survives when its process is killed. kinlib's own server
(``kinlib._viewer_server``) must not, whether the process exits or is killed with SIGKILL,
and the same must hold for a real Jupyter kernel killed the way nbval kills it.
"""

import os
import re
import signal
import subprocess
import sys
import textwrap
import time

import pytest

from kinlib._viewer_server import own_server, start_server

ENV_KEYS = ("KINLIB_MESHCAT_ZMQ_URL", "KINLIB_MESHCAT_WEB_URL", "KINLIB_MESHCAT_SERVER_PID")


def alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, dead but not yet reaped, counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            state = fh.read().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError):
        return False
    return state not in ("Z", "X")


def wait_gone(pid: int, timeout: float = 10.0) -> bool:
    deadline = time.monotonic() + timeout
    while alive(pid):
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


def cmdline(pid: int) -> str:
    with open(f"/proc/{pid}/cmdline", "rb") as fh:
        return fh.read().replace(b"\0", b" ").decode()


def no_session_server_env() -> dict:
    return {k: v for k, v in os.environ.items() if k not in ENV_KEYS}


def run_and_read_pid(code: str) -> tuple[subprocess.CompletedProcess, int]:
    proc = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, timeout=120, env=no_session_server_env())
    pids = [line.split()[1] for line in proc.stdout.splitlines() if line.startswith("PID ")]
    assert pids, f"no PID line; stdout={proc.stdout!r} stderr={proc.stderr[-2000:]!r}"
    return proc, int(pids[0])


pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"),
                                reason="reads /proc; dying with the parent is Linux-only")


def test_control_meshcats_own_server_survives_a_killed_parent():
    proc, pid = run_and_read_pid("""
        import os, signal, warnings
        warnings.simplefilter("ignore")
        import meshcat
        v = meshcat.Visualizer()
        print("PID", v.window.server_proc.pid, flush=True)
        os.kill(os.getpid(), signal.SIGKILL)
    """)
    try:
        assert proc.returncode == -signal.SIGKILL
        time.sleep(1.0)
        assert alive(pid) and "meshcat.servers.zmqserver" in cmdline(pid)
    finally:
        os.killpg(pid, signal.SIGKILL)
    assert wait_gone(pid)


@pytest.mark.parametrize("ending", ["SIGKILL", "SIGTERM", "normal exit", "sys.exit(3)"])
def test_visualizer_server_ends_with_its_process(ending):
    end = {"SIGKILL": "os.kill(os.getpid(), signal.SIGKILL)",
           "SIGTERM": "os.kill(os.getpid(), signal.SIGTERM)",
           "normal exit": "pass", "sys.exit(3)": "sys.exit(3)"}[ending]
    proc, pid = run_and_read_pid(f"""
        import os, signal, sys
        from kinlib.robots import planar_2r
        from kinlib.viz import RobotVisualizer
        from kinlib._viewer_server import own_server
        a = RobotVisualizer(planar_2r(), prefix="a")
        b = RobotVisualizer(planar_2r(), prefix="b")
        assert a.url() == b.url() == own_server().web_url, "one server per process"
        print("PID", own_server().pid, flush=True)
        {end}
    """)
    assert proc.returncode in (0, 3, -signal.SIGKILL, -signal.SIGTERM), proc.stderr[-2000:]
    assert wait_gone(pid), f"the server {pid} outlived its process ({ending}): {cmdline(pid)}"


def test_server_of_a_hard_killed_jupyter_kernel_goes_too():
    from jupyter_client.manager import start_new_kernel

    env = no_session_server_env()
    seen = []
    km, kc = start_new_kernel(kernel_name="python3", env=env)
    try:
        reply = kc.execute_interactive(
            "from kinlib.robots import puma560\n"
            "from kinlib.viz import RobotVisualizer\n"
            "from kinlib._viewer_server import own_server\n"
            "viz = RobotVisualizer(puma560(), prefix='kernel')\n"
            "print('PID', own_server().pid)\n",
            timeout=120, output_hook=lambda msg: seen.append(msg))
        assert reply["content"]["status"] == "ok", reply["content"]
        text = "".join(m["content"]["text"] for m in seen if m["msg_type"] == "stream")
        pid = int(re.search(r"^PID (\d+)$", text, re.M).group(1))
        assert alive(pid)
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=True)  # SIGKILL, as nbval does
    assert wait_gone(pid), f"the kernel's server {pid} is still running"


def test_own_server_is_reused_and_restarted_if_it_died():
    first = own_server()
    assert own_server() is first
    first.stop()
    assert wait_gone(first.pid)
    second = own_server()
    try:
        assert second is not first and alive(second.pid)
    finally:
        second.stop()


def test_start_server_reports_addresses_and_stops_its_group(tmp_path):
    server = start_server(log=str(tmp_path / "log"))
    try:
        assert server.zmq_url.startswith("tcp://") and server.web_url.startswith("http://")
        assert os.getpgid(server.pid) == server.pid
    finally:
        server.stop()
    assert wait_gone(server.pid)
    server.stop()  # a second stop is harmless
