"""kinlib.viz stays out of ``import kinlib``, and a visualizer needs no server: it starts
no process and listens on no port (the scene goes over the notebook's own connection)."""

import os
import subprocess
import sys
import textwrap

import pytest


def test_import_kinlib_does_not_load_meshcat_or_widgets():
    code = ("import sys, kinlib, kinlib.kinematics.holonomic, kinlib.robots\n"
            "heavy = ('meshcat', 'ipywidgets', 'anywidget', 'kinlib.viz', 'zmq')\n"
            "bad = [m for m in heavy if m in sys.modules]\n"
            "assert not bad, bad\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr


PROBE = textwrap.dedent('''
    import os, socket, sys
    sys.path.insert(0, sys.argv[1])
    from test_viz_session import listening_ports, children
    control = len(sys.argv) > 2
    if control:  # what the check must catch: a process that listens and has a child
        server = socket.socket(); server.bind(("127.0.0.1", 0)); server.listen()
        import subprocess
        kid = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    from kinlib.robots import puma560
    from kinlib.viz import RobotVisualizer, joint_panel
    viz = RobotVisualizer(puma560(), frames=True)
    viz.set_configuration(puma560().poses["ready"])
    viz.animate([puma560().poses["zero"], puma560().poses["ready"]])
    viz.jupyter_cell(); viz.snapshot(); joint_panel(viz)
    print(sorted(listening_ports(os.getpid())), len(children()))
    if control:
        kid.kill()
''')


def listening_ports(pid) -> set[int]:
    """The TCP ports process ``pid`` listens on (its sockets in /proc/net/tcp*)."""
    inodes = set()
    for fd in os.listdir(f"/proc/{pid}/fd"):
        try:
            target = os.readlink(f"/proc/{pid}/fd/{fd}")
        except OSError:
            continue
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


def children() -> list[str]:
    """This process's child processes."""
    kids = []
    for task in os.listdir("/proc/self/task"):
        with open(f"/proc/self/task/{task}/children") as fh:
            kids += fh.read().split()
    return kids


@pytest.mark.skipif(not os.path.isdir("/proc"), reason="needs /proc (Linux)")
@pytest.mark.parametrize("control", [False, True])
def test_a_visualizer_starts_no_process_and_listens_on_no_port(control):
    here = os.path.dirname(__file__)
    args = [sys.executable, "-c", PROBE, here] + (["control"] if control else [])
    done = subprocess.run(args, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    ports, kids = done.stdout.strip().splitlines()[-1].rsplit(" ", 1)
    if control:
        assert ports != "[]" and kids == "1", done.stdout
    else:
        assert (ports, kids) == ("[]", "0"), done.stdout
        assert "You can open the visualizer" not in done.stdout + done.stderr
