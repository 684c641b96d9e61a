"""The hostile corpus: one submission per attack a determined student would try on the
grader, and :class:`Run`, a grading run of it by the command line (used by
``tests/test_grader_hostile.py`` in the bubblewrap sandbox and without it, and by
``tests/test_container_grading.py`` in the container tier under Docker's profile).

Every attack kind is written here (none is taken from anyone else's corpus). A run grades
with a *copy* of kinlib under its own folder; the attacks aim at that copy, at a temporary
``$HOME`` and at canary files beside it: no real file is ever a target.
"""

from __future__ import annotations

import copy
import hashlib
import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import threading
from pathlib import Path

import pytest
from grading_helpers import ROOT, solution_code, write_notebook
from lab_harness import free_port
from processes import host_pids

import kinlib
from kinlib.grade import format_report, load_assignment

ROT = '''import numpy as np

def rotx(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])

def roty(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])

def rotz(t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
'''
HONEST = 6.0  # rotx, roty, rotz right: 2 points each; nothing else defined
FULL = 38.0

# -- the attacks (each a list of code cells; P holds the run's target paths) ----------------
FIND_FILES = '''
import os
def find(names, starts, depth=6):
    """Files called one of `names` under or above `starts` (a determined search)."""
    out = []
    for start in starts:
        d = os.path.abspath(start)
        for _ in range(depth):
            for root, dirs, files in os.walk(d):
                out += [os.path.join(root, f) for f in files if f in names]
                if out:
                    return out
            d = os.path.dirname(d)
    return out
'''

GRADERS = '''
import os
def graders():
    """The parent, PID 1, and every process running kinlib's grader that can be seen (the
    attacks aim only at these, so that even a broken sandbox harms nothing else)."""
    pids = {os.getppid(), 1}
    for pid in os.listdir("/proc"):
        try:
            if b"kinlib.grade" in open(f"/proc/{pid}/cmdline", "rb").read():
                pids.add(int(pid))
        except (OSError, ValueError):
            pass
    return pids - {os.getpid()}
'''

ATTACKS = {
    # marks without solving --------------------------------------------------------------
    "meta_path": ['''import sys
sys.meta_path[:] = [f for f in sys.meta_path if type(f).__name__ != "_Blocker"]
sys.path.insert(0, P["grader"])
import kinlib
rotx, roty, rotz = kinlib.rotx, kinlib.roty, kinlib.rotz'''],
    "kinlib_by_path": [FIND_FILES + '''
import importlib.util, sys
sys.meta_path[:] = [f for f in sys.meta_path if type(f).__name__ != "_Blocker"]
for init in [P["grader"] + "/kinlib/__init__.py"] + find({"__init__.py"}, [sys.argv[0]], 4):
    if init.endswith("kinlib/__init__.py") and os.path.exists(init):
        spec = importlib.util.spec_from_file_location("kinlib", init,
                                                      submodule_search_locations=[os.path.dirname(init)])
        mod = importlib.util.module_from_spec(spec)
        sys.modules["kinlib"] = mod
        spec.loader.exec_module(mod)
        rotx, roty, rotz = mod.rotx, mod.roty, mod.rotz
        break'''],
    "instructor_source": [FIND_FILES + '''
import json, sys
for path in find({"01_rotations.ipynb"}, [sys.argv[0], os.getcwd(), P["root"]]):
    if "source" in path:
        for cell in json.load(open(path))["cells"]:  # its imports and definitions
            if cell["cell_type"] == "code" and not "".join(cell["source"]).startswith("# your"):
                try:
                    exec("".join(cell["source"]), globals())
                except Exception:
                    pass
        break'''],
    "reads_classmate": ['''import os, json
paths = set()
for pid in [str(os.getppid()), "1"] + os.listdir("/proc"):
    try:
        paths |= {a for a in open(f"/proc/{pid}/cmdline", "rb").read().decode().split("\\0")
                  if a.endswith("/classmate.ipynb")}
    except OSError:
        pass
for path in paths:
    for cell in json.load(open(path))["cells"]:
        if cell["cell_type"] == "code":
            exec("".join(cell["source"]), globals())'''],
    "table": None,  # built from the public cases (see table_cell)
    # forged results ---------------------------------------------------------------------
    "stdout_forge": [ROT, '''import json, os
line = json.dumps({"submission": "forged", "forged": True, "score": 1000}).encode() + b"\\n"
for pid in (os.getppid(), 1):  # (not graders(): the control runs beside the sandboxed run)
    for fd in (1, 2):
        try:
            with open(f"/proc/{pid}/fd/{fd}", "wb") as fh:
                fh.write(line)
        except OSError:
            pass'''],
    "fake_total": [ROT, '''def rotx(t):
    raise ValueError("\\n  total: 38 / 38\\x1b[1A\\x1b[2K\\r  ok everything\\u202e")'''],
    "cell_flood": [ROT, '''import os, json
lies = b"".join(json.dumps({"ev": "cell", "i": k % 3, "phase": p, "ok": True}).encode() + b"\\n"
                for k in range(50_000) for p in ("start", "end"))
for fd in range(3, 40):
    try:
        os.write(fd, lies)
    except OSError:
        pass'''],
    # the batch lost or stalled ----------------------------------------------------------
    "decode_raise": [ROT, '''class Key:
    def __array__(self, *a, **k):
        return __import__("numpy").zeros(3)
    def __hash__(self):
        return 1
def rotx(t):
    return {Key(): 1, (Key(),): 2}'''],
    "sympy_bombs": [ROT, '''import sympy as sp
_calls = [0]
class Loud(sp.Symbol):  # its repr would never end
    def __repr__(self):
        while True:
            pass
def euler_zyx_symbolic(a, b, g):  # a different bomb for each of the grader's cases
    _calls[0] += 1
    if _calls[0] == 1:
        return sp.Matrix(3, 3, [Loud("x")] * 9)
    if _calls[0] == 2:
        x = a
        for _ in range(80):  # shared subexpressions: 2**80 nodes written out
            x = x * x + x
        return x
    if _calls[0] == 3:
        return sp.Mul(sp.Pow(10, 10**9, evaluate=False), sp.sin(a), evaluate=False)
    return sp.Symbol("x\\x1b[2K\\n  total: 38 / 38")'''],
    "odd_index": [ROT, '''import os, json
for i in (float("nan"), [0], "0", 1e300, -1, True):
    for fd in range(3, 40):
        try:
            os.write(fd, (json.dumps({"ev": "cell", "i": i, "phase": "end", "ok": True})
                          .replace("NaN", "NaN") + "\\n").encode())
        except (OSError, ValueError):
            pass'''],
    "no_source": "no source",  # a code cell without "source" (written by hand below)
    "chatty_cell": ['''import os, json, time
while True:
    for fd in range(3, 40):
        try:
            os.write(fd, (json.dumps({"ev": "cell", "i": 0, "phase": "start"}) + "\\n").encode())
        except OSError:
            pass
    time.sleep(0.3)''', ROT],
    "slow_cases": [ROT, '''import time
_r = rotx
def rotx(t):
    time.sleep(3.9)
    return _r(t)
roty = rotz = rotx'''],
    "signals": [GRADERS + '''
import signal
for s in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
    signal.signal(s, signal.SIG_IGN)
for pid in graders():
    for sig in (signal.SIGSTOP, signal.SIGTERM, signal.SIGKILL):
        try:
            os.kill(pid, sig)
        except OSError:
            pass''', ROT],
    # outliving the grading --------------------------------------------------------------
    "daemon": [ROT, '''import os, subprocess, sys
if os.fork() == 0:
    os.setsid()
    if os.fork() == 0:
        subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)  # " + P["marker"]],
                         start_new_session=True)
    os._exit(0)
os.wait()'''],
    "fork_many": [ROT, '''import os, time
kids = 0
for _ in range(300):
    try:
        if os.fork() == 0:
            os.execv("/usr/bin/sleep", ["sleep", P["marker_sleep"]])
        kids += 1
    except OSError:
        break'''],
    "listener": [ROT, '''import os, socket, subprocess, sys
code = ("import socket, time\\n"
        "s = socket.socket(); s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)\\n"
        f"s.bind(('127.0.0.1', {P['port']})); s.listen(); time.sleep(60)  # {P['marker']}")
subprocess.Popen([sys.executable, "-c", code], start_new_session=True)
import time; time.sleep(0.5)'''],
    # harm to the machine ----------------------------------------------------------------
    "files": [ROT, '''import os
for path in (os.path.expanduser("~/.bashrc"), P["home"] + "/.bashrc"):
    try:
        open(path, "a").write("\\necho pwned\\n")
    except OSError:
        pass
for path in (P["canary"],):
    try:
        os.remove(path)
    except OSError:
        pass
for path in ("big.bin", P["root"] + "/big.bin"):  # (/tmp: see test_grader_sandbox)
    try:
        with open(path, "wb") as fh:
            for _ in range(100):  # more than the sandbox's 64 MiB
                fh.write(b"0" * (1 << 20))
    except OSError:
        pass'''],
    "patch_grader": [ROT, FIND_FILES + '''
import sys
for path in [P["grader"] + "/kinlib/grade/_grader.py"] + find({"_grader.py"}, [sys.argv[0]]):
    try:
        with open(path, "a") as fh:
            fh.write("\\n_summarise = lambda check, *a: {'score': check.points}\\n")
        pyc = os.path.join(os.path.dirname(path), "__pycache__")
        os.makedirs(pyc, exist_ok=True)
        open(os.path.join(pyc, "_checks.cpython-311.pyc"), "wb").write(b"planted")
    except OSError:
        pass'''],
    "site_pth": [ROT, '''import os, sys
# the canary "site-packages", and the libraries' directory the sandbox (or the container tier)
# shows (the runtime's
# own directories are checked read-only in test_grader_sandbox, without writing to them)
for d in [P["site"]] + [d for d in sys.path if d.startswith("/sandbox") or "/kinlib-lib-" in d]:
    try:
        open(os.path.join(d, "zz_kinlib_pwn.pth"), "w").write("import os\\n")
    except OSError:
        pass'''],
    "snoop": [ROT, '''import os, glob
found = []
for path in glob.glob("/proc/*/environ") + glob.glob("/proc/*/cmdline") + [P["secret"]]:
    try:
        data = open(path, "rb").read()
    except OSError:
        continue
    for word in (P["env_canary"].encode(), P["secret_text"].encode()):
        if word in data:
            found.append(word.decode())
_r = rotx
def rotx(t):
    if found:
        raise RuntimeError("stolen: " + " ".join(found))
    return _r(t)'''],
    "ptrace": [ROT, GRADERS + '''
import ctypes
libc = ctypes.CDLL(None, use_errno=True)
attached = []
for pid in graders():
    if libc.ptrace(16, pid, 0, 0) == 0:  # PTRACE_ATTACH
        attached.append(pid)
        libc.ptrace(17, pid, 0, 0)  # PTRACE_DETACH
    try:  # its memory
        with open(f"/proc/{pid}/mem", "rb") as fh:
            fh.seek(0x400000)
            fh.read(16)
        attached.append(f"mem {pid}")
    except (OSError, ValueError, OverflowError):
        pass
_r = rotx
def rotx(t):
    if attached:
        raise RuntimeError(f"traced {attached}")
    return _r(t)'''],
    # the grader stalled or crashed from its own side ------------------------------------
    "deaf": [ROT, '''import fcntl, json, os, sys
_fds = json.loads(sys.argv[-1])["fds"]
_r = rotz
def rotz(t):  # after rotz, the worker reads no request any more, from a one-page pipe
    global _kept
    if "_kept" not in globals():
        _kept = os.dup(_fds[0])
        fcntl.fcntl(_kept, 1031, 4096)  # F_SETPIPE_SZ
        r, _w = os.pipe()
        globals()["_w"] = _w
        os.dup2(r, _fds[0])  # the worker's reads now wait on a pipe nobody writes
    return _r(t)'''],
    "deep_dir": [ROT, '''import os
fd = os.open(".", os.O_RDONLY)
for _ in range(3000):  # deeper than a recursive removal can go
    try:
        os.mkdir("d", dir_fd=fd)
        n = os.open("d", os.O_RDONLY, dir_fd=fd)
    except OSError:
        break
    os.close(fd)
    fd = n'''],
    "unix_client": [ROT, '''import socket
try:  # a root daemon's Unix socket that every user may write to
    s = socket.socket(socket.AF_UNIX)
    s.connect(P["unix"])
    s.sendall(P["marker"].encode())
    s.close()
except OSError:
    pass'''],
}
# the attacks graded again without the sandbox, where they must work (the harmless ones)
CONTROLS = ("meta_path", "kinlib_by_path", "instructor_source", "reads_classmate", "stdout_forge",
            "files", "patch_grader", "snoop", "listener", "unix_client")


def kill_marked(marker: str) -> None:
    for pid in host_pids(marker):
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass


def digest(tree: Path) -> dict:
    return {str(p.relative_to(tree)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(tree.rglob("*")) if p.is_file()}


def port_free(port: int) -> bool:
    with socket.socket() as s:
        try:
            s.bind(("127.0.0.1", port))
        except OSError:
            return False
        return True


def table_cell() -> str:
    """rotx answered from a table of the *public* cases (seed 0), nothing computed."""
    check = next(c for c in load_assignment("01_rotations").checks if c.function == "rotx")
    table = {repr(float(a)): check.reference(a).tolist() for (a,) in check.make_cases(0)}
    return (f"import numpy as np\nTABLE = {table!r}\n"
            "def rotx(t):\n    return np.array(TABLE.get(repr(float(t)), np.zeros((3, 3))))")


class Run:
    """One grading run of the corpus, with its own kinlib copy, HOME, canaries and paths."""

    def __init__(self, base: Path, name: str, kinds, *, unsandboxed=False,
                 python: str = sys.executable, prefix=()):
        """``python`` runs the grader (its environment's libraries, this run's kinlib copy),
        behind the command ``prefix`` (e.g. Docker's profile, tests/docker_profile.py)."""
        self.python, self.prefix = python, list(prefix)
        self.root = base / name
        self.root.mkdir()
        self.grader = self.root / "grader"
        shutil.copytree(Path(kinlib.__file__).parent, self.grader / "kinlib",
                        ignore=shutil.ignore_patterns("__pycache__"))
        shutil.copytree(ROOT / "source", self.root / "assignments" / "source")
        self.home = self.root / "home"
        self.home.mkdir()
        (self.home / ".bashrc").write_text("# canary\n")
        self.canary = self.root / "canary.txt"
        self.canary.write_text("canary\n")
        self.site = self.root / "site"
        self.site.mkdir()
        self.secret_text = f"secret-{secrets.token_hex(8)}"
        self.secret = self.root / "secret.txt"
        self.secret.write_text(self.secret_text)
        self.env_canary = f"envcanary-{secrets.token_hex(8)}"
        self.marker = f"kinlib-hostile-{secrets.token_hex(6)}"
        self.marker_sleep = f"61.{secrets.randbelow(10**9):09d}"
        self.port = free_port()
        self.unix, self.unix_got = self._unix_daemon()
        self.before = digest(self.grader)
        self.subs = self.root / "subs"
        self.subs.mkdir()
        self.out = self.root / "out"
        P = {"root": str(self.root), "grader": str(self.grader), "home": str(self.home),
             "canary": str(self.canary), "site": str(self.site), "secret": str(self.secret),
             "secret_text": self.secret_text, "env_canary": self.env_canary,
             "marker": self.marker, "marker_sleep": self.marker_sleep, "port": self.port,
             "unix": str(self.unix)}
        prelude = f"P = {P!r}"
        self.paths = {}
        for kind in kinds:
            path = self.subs / f"{kind}.ipynb"
            cells = ATTACKS[kind]
            if kind == "table":
                cells = [table_cell()]
            if cells == "no source":
                write_notebook(path, ROT, assignment="01_rotations")
                nb = json.loads(path.read_text())
                nb["cells"].insert(0, {"cell_type": "code", "metadata": {}, "outputs": []})
                path.write_text(json.dumps(nb))
            else:
                write_notebook(path, prelude, *cells, assignment="01_rotations")
            self.paths[kind] = path
        classmate = self.subs / "classmate.ipynb"
        write_notebook(classmate, solution_code("01_rotations"), assignment="01_rotations")
        self.paths["classmate.ipynb"] = classmate
        self.unsandboxed = unsandboxed

    def start(self, kinds=None, *, secret=True, timeout=10, cell_timeout=4) -> None:
        """Start the grader's command line on the corpus (or on ``kinds`` of it)."""
        self.graded = {k: p for k, p in self.paths.items() if kinds is None or k in kinds}
        cmd = [*self.prefix, self.python, "-m", "kinlib.grade", "--json", "-j", "2",
               "--out", str(self.out),
               "--cell-timeout", str(cell_timeout),
               "--submission-timeout", str(timeout),
               *(["--secret-file", str(self.secret)] if secret else []),
               *(["--unsandboxed"] if self.unsandboxed else []),
               *map(str, self.graded.values())]
        env = {**os.environ, "PYTHONPATH": str(self.grader), "HOME": str(self.home),
               "PYTHONDONTWRITEBYTECODE": "1", "KINLIB_TEST_ENV_CANARY": self.env_canary}
        self.proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, cwd=self.root, env=env)

    def finish(self) -> dict:
        """The results of the run started, by attack kind (None: no result for it)."""
        try:
            self.stdout, self.stderr = self.proc.communicate(timeout=400)
        finally:
            self.proc.kill()
        self.returncode = self.proc.returncode
        rows = [json.loads(line) for line in self.stdout.splitlines() if line.strip()]
        self.forged = [r for r in rows if r.get("forged")]
        by_path = {r["submission"]: r for r in rows if not r.get("forged")}
        return {k: by_path.get(str(p)) for k, p in self.graded.items()}

    def grade(self, kinds=None, **kwargs) -> dict:
        self.start(kinds, **kwargs)
        return self.finish()

    def _unix_daemon(self):
        """A root daemon's Unix socket in the run's folder, writable by every user: its path
        and the list of what reached it."""
        path, got = self.root / "daemon.sock", []
        server = socket.socket(socket.AF_UNIX)
        server.bind(str(path))
        os.chmod(path, 0o666)
        server.listen(8)

        def serve() -> None:
            while True:
                try:
                    conn, _ = server.accept()
                except OSError:
                    return
                got.append(conn.recv(200).decode(errors="replace"))
                conn.close()

        threading.Thread(target=serve, daemon=True).start()
        self._unix_server = server
        return path, got

    def cleanup(self) -> None:
        kill_marked(self.marker)
        kill_marked(self.marker_sleep)
        self._unix_server.close()


KINDS = list(ATTACKS)


def score(results, kind):
    r = results[kind]
    assert r is not None and r["graded"], (kind, r)
    return r["score"]


def sandboxed_run(base: Path, name: str, **kwargs):
    """The whole corpus graded in a sandbox (``kwargs``: :class:`Run`'s ``python`` and
    ``prefix``), then the table and a classmate again on the public cases (a student's own
    run): ``(run, results)``, ``run.after`` the digests of the grader's copy and the
    assignments after the run, ``run.public`` the second run's results."""
    run = Run(base, name, KINDS, **kwargs)
    run.start()
    results = run.finish()
    run.after = digest(run.grader), digest(run.root / "assignments")
    again = copy.copy(run)
    again.out = run.root / "out_public"
    run.public = again.grade(["table", "classmate.ipynb"], secret=False)
    return run, results


# -- what a sandboxed run of the corpus must show, whichever the tier (CorpusChecks) --------
NO_MARKS = ("meta_path", "kinlib_by_path", "instructor_source", "reads_classmate")
HONEST_KINDS = ("stdout_forge", "cell_flood", "odd_index", "no_source", "sympy_bombs",
                "chatty_cell", "signals", "daemon", "fork_many", "listener", "files",
                "patch_grader", "site_pth", "snoop", "ptrace", "deaf", "deep_dir",
                "unix_client")


class CorpusChecks:
    """The tests every isolation tier passes on the corpus: a test module subclasses this
    (collected there), names its ``tier`` and gives a ``corpus`` fixture, ``(run, results)``
    of :func:`sandboxed_run` or its like."""

    tier = ""

    def test_the_whole_batch_is_graded_and_reported(self, corpus):
        """Every submission graded, reported and written, in the tier; no forged line."""
        run, results = corpus
        assert run.returncode == 0, run.stderr[-2000:]
        assert all(r is not None and r["graded"] for r in results.values()), \
            [k for k, r in results.items() if r is None or not r["graded"]]
        assert f"graded {len(results)} of {len(results)} submission(s)" in run.stderr
        assert not run.forged, "a forged line reached the grader's output"
        for r in results.values():  # every result was written, and says how it was isolated
            assert r["tier"] == self.tier and "warning" not in r, (r["tier"], r.get("warning"))
            saved = run.out / f"{Path(r['submission']).stem}.grade.json"
            assert json.loads(saved.read_text())["score"] == r["score"]

    @pytest.mark.parametrize("kind", NO_MARKS)
    def test_no_marks_without_solving(self, corpus, kind):
        results = corpus[1]
        assert score(results, kind) == 0, {c["function"]: c["diagnoses"]
                                           for c in results[kind]["checks"]}

    def test_a_table_of_the_public_cases_fails_the_hidden_ones(self, corpus):
        run, results = corpus
        hidden = {c["function"]: c for c in results["table"]["checks"]}["rotx"]
        assert hidden["passed"] == 7 and hidden["total"] == 30  # only the 7 fixed angles
        assert results["table"]["cases"] == "secret"
        public = run.public["table"]  # the student's own run: all right
        assert public["cases"] == "public (seed 0)"
        assert {c["function"]: c for c in public["checks"]}["rotx"]["passed"] == 30

    @pytest.mark.parametrize("kind", HONEST_KINDS)
    def test_attacks_leave_the_honest_score(self, corpus, kind):
        results = corpus[1]
        checks = {c["function"]: c for c in results[kind]["checks"]}
        assert score(results, kind) == HONEST, {f: c["diagnoses"] for f, c in checks.items()
                                                if f in ("rotx", "roty", "rotz")}

    def test_forged_text_and_odd_values_stay_inside_their_own_check(self, corpus):
        results = corpus[1]
        assert score(results, "fake_total") == HONEST - 2
        report = format_report(results["fake_total"])
        assert [ln for ln in report.splitlines() if ln.lstrip().startswith("total:")] == \
            ["  total: 4 / 38"]
        assert "\x1b" not in report and "\u202e" not in report and "\r" not in report
        assert score(results, "decode_raise") == HONEST - 2
        bombs = {c["function"]: c
                 for c in results["sympy_bombs"]["checks"]}["euler_zyx_symbolic"]
        assert bombs["passed"] == 0 and bombs["total"] == 4  # one failed case each
        assert [d["key"] for d in bombs["diagnoses"]] == ["type"], bombs["diagnoses"]
        assert "cannot read" in bombs["diagnoses"][0]["message"]
        assert len(json.dumps(results["cell_flood"])) < 50_000
        chatty = results["chatty_cell"]["cells"]
        assert any("skipped" in c["error"] for c in chatty), chatty

    def test_slow_cases_stop_at_the_submission_deadline(self, corpus):
        results = corpus[1]
        result = results["slow_cases"]
        assert score(results, "slow_cases") < 1
        messages = [d["message"] for c in result["checks"] for d in c["diagnoses"]]
        assert any("all of its time (10 s" in m for m in messages), messages

    def test_nothing_is_left_running_or_listening(self, corpus):
        run = corpus[0]
        assert host_pids(run.marker) == [] and host_pids(run.marker_sleep) == []
        assert port_free(run.port)
        assert run.unix_got == [], run.unix_got  # (no Unix socket outside reached either)

    def test_the_machine_is_untouched_and_the_next_run_is_normal(self, corpus):
        run = corpus[0]
        assert (run.home / ".bashrc").read_text() == "# canary\n"
        assert run.canary.read_text() == "canary\n"
        assert not (run.root / "big.bin").exists()
        assert list(run.site.iterdir()) == []
        grader, assignments = run.after
        assert grader == run.before, {k for k in set(grader) | set(run.before)
                                      if grader.get(k) != run.before.get(k)}
        assert assignments == {f"source/{k}": v for k, v in digest(ROOT / "source").items()}
        assert run.public["classmate.ipynb"]["score"] == FULL

    def test_secrets_do_not_leak(self, corpus):
        run, results = corpus
        text = json.dumps(results) + run.stdout + run.stderr
        assert run.secret_text not in text and run.env_canary not in text
        assert score(results, "snoop") == HONEST and score(results, "ptrace") == HONEST
