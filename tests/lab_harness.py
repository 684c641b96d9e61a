"""JupyterLab for the browser tests: a real server on a free port, in a temporary world.

:class:`Lab` starts ``python -m jupyter lab`` the way a student's ``make lab`` does, but
with every Jupyter directory (config, runtime, settings, workspaces, IPython) in a
temporary folder, a random token, a copy of the notebooks (the run saves nothing into the
repository), notebook windowing off (every cell stays in the page, so it can be read), and
no news or update checks (nothing from the network); ``env`` is added to the server's
environment (its kernels inherit it) and ``save_widget_state`` turns on JupyterLab's *Save
Jupyter widget state in notebooks*. ``base_url`` serves it under a path,
as a JupyterHub serves ``/user/NAME/`` (with the ``notebook`` package installed, the same
server serves Jupyter Notebook 7's pages as well, under ``notebooks/``).

The server asks Linux to SIGTERM it when the test process dies, however it dies (a
SIGTERMed server shuts its kernels down). Every process the server starts inherits
``KINLIB_LAB_RUN=<random marker>``: the kernels and anything they start.
:meth:`Lab.stop` shuts the server down through its REST API (which shuts the kernels
down), then signals its process group, and finally kills whatever still carries the
marker: :func:`marked_processes` must be empty afterwards, and the tests check that it is,
also after a failing test and after pytest itself is killed (test_lab_cleanup.py).
"""

from __future__ import annotations

import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

from kinlib._process import die_with

MARK = "KINLIB_LAB_RUN"
SETTINGS = {
    # every cell in the DOM (the default windowing drops cells scrolled out of view)
    "@jupyterlab/notebook-extension/tracker.jupyterlab-settings": {"windowingMode": "none"},
    # no news, no update checks: nothing from the network
    "@jupyterlab/apputils-extension/notification.jupyterlab-settings": {
        "fetchNews": "false", "checkForUpdates": False},
}

#: JupyterLab's Jupyter Widgets settings (``saveState``: a save stores the widget state)
WIDGETS_SETTINGS = "@jupyter-widgets/jupyterlab-manager/plugin.jupyterlab-settings"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def marked_processes(marker: str) -> list[int]:
    """Pids of live processes whose environment has ``KINLIB_LAB_RUN=marker``."""
    needle = f"{MARK}={marker}".encode() + b"\0"
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == os.getpid():
            continue
        try:
            with open(f"/proc/{entry}/environ", "rb") as fh:
                env = fh.read() + b"\0"
            with open(f"/proc/{entry}/stat", "rb") as fh:
                state = fh.read().rsplit(b")", 1)[1].split()[0]
        except OSError:
            continue
        if needle in env and state != b"Z":
            found.append(int(entry))
    return found


class Lab:
    """A JupyterLab server over a copy of ``notebooks`` (a folder), rooted in ``work``."""

    def __init__(self, notebooks: Path, work: Path, start_timeout: float = 60.0, *,
                 base_url: str = "/", env: dict | None = None,
                 save_widget_state: bool = False):
        self.base_url = "/" + base_url.strip("/") + "/" if base_url.strip("/") else "/"
        self.work = Path(work)
        self.root = self.work / "notebooks"
        self.marker = secrets.token_hex(8)
        self.token = secrets.token_hex(16)
        self.port = free_port()
        self.proc: subprocess.Popen | None = None
        self.log = self.work / "lab.log"
        self.extra_env = dict(env or {})  # for the server and its kernels
        self.save_widget_state = save_widget_state
        self._closing: list[threading.Thread] = []
        self._closed: list = []
        shutil.copytree(notebooks, self.root, ignore=shutil.ignore_patterns(
            ".ipynb_checkpoints", "__pycache__"))
        self._start(start_timeout)

    @property
    def origin(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    @property
    def base(self) -> str:
        """The server's root URL, with its base path (no trailing slash)."""
        return f"{self.origin}{self.base_url.rstrip('/')}"

    def url(self, path: str) -> str:
        return f"{self.base}/{path.lstrip('/')}?token={self.token}"

    def _env(self) -> dict:
        env = dict(os.environ)
        dirs = {"JUPYTER_CONFIG_DIR": "config", "JUPYTER_RUNTIME_DIR": "runtime",
                "JUPYTERLAB_SETTINGS_DIR": "settings", "JUPYTERLAB_WORKSPACES_DIR": "workspaces",
                "IPYTHONDIR": "ipython", "MPLCONFIGDIR": "matplotlib"}
        for key, sub in dirs.items():
            (self.work / sub).mkdir(parents=True, exist_ok=True)
            env[key] = str(self.work / sub)
        env[MARK] = self.marker
        env.pop("MPLBACKEND", None)
        env["PYTHONUNBUFFERED"] = "1"
        env.update(self.extra_env)
        return env

    def _start(self, timeout: float) -> None:
        env = self._env()
        settings = dict(SETTINGS)
        if self.save_widget_state:  # a save stores the widget state, as nbclient's does
            settings[WIDGETS_SETTINGS] = {"saveState": True}
        for name, values in settings.items():
            path = Path(env["JUPYTERLAB_SETTINGS_DIR"]) / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(json.dumps(values))
        cmd = [sys.executable, "-m", "jupyter", "lab", "--no-browser",
               f"--port={self.port}", "--ServerApp.port_retries=0", "--ServerApp.ip=127.0.0.1",
               f"--IdentityProvider.token={self.token}",
               f"--ServerApp.root_dir={self.root}",
               "--LabApp.news_url=", "--ServerApp.open_browser=False",
               f"--ServerApp.base_url={self.base_url}", "--LabApp.expose_app_in_browser=True"]
        if os.getuid() == 0:
            cmd.append("--allow-root")
        with open(self.log, "wb") as log:
            self.proc = subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT,
                                         stdin=subprocess.DEVNULL, start_new_session=True,
                                         cwd=self.work, preexec_fn=die_with(os.getpid()))
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError(f"jupyter lab exited with {self.proc.returncode}:\n"
                                   + self.log.read_text(errors="replace")[-3000:])
            try:
                self.api("GET", "api/status")
                return
            except (OSError, urllib.error.URLError):
                time.sleep(0.25)
        self.stop()
        raise RuntimeError(f"jupyter lab did not answer within {timeout:g} s:\n"
                           + self.log.read_text(errors="replace")[-3000:])

    def _request(self, method: str, path: str, timeout: float, body: dict | None = None):
        """A call of the server's REST API (``body``: sent as JSON): (status, raw answer)."""
        headers = {"Authorization": f"token {self.token}"}
        data = None
        if body is not None:
            data, headers["Content-Type"] = json.dumps(body).encode(), "application/json"
        req = urllib.request.Request(self.url(path), data=data, method=method, headers=headers)
        with urllib.request.urlopen(req, timeout=timeout) as resp:
            return resp.status, resp.read()

    def api(self, method: str, path: str, timeout: float = 10.0, body: dict | None = None):
        """A call of the server's REST API (``body``: sent as JSON); its JSON answer."""
        _, answer = self._request(method, path, timeout, body)
        return json.loads(answer) if answer else None

    def close_session(self, session_id: str) -> None:
        """Close a notebook's session (its kernel shuts down) without waiting, as JupyterLab
        does when a student closes the tab: the server's answer (204 once the kernel has
        stopped, 0.3-0.9 s here) comes while the next notebook opens. See
        :meth:`closed_sessions`."""
        def close():
            try:
                status, _ = self._request("DELETE", f"api/sessions/{session_id}", 60)
            except urllib.error.HTTPError as e:
                status = e.code
            except OSError as e:
                status = repr(e)
            self._closed.append(status)

        thread = threading.Thread(target=close, daemon=True)
        thread.start()
        self._closing.append(thread)

    def closed_sessions(self) -> list:
        """Wait for every :meth:`close_session`; the server's answers (HTTP status codes, or
        the error of a request that got none)."""
        for thread in self._closing:
            thread.join(70)
        return list(self._closed) + ["no answer"] * sum(t.is_alive() for t in self._closing)

    def kernels(self) -> list[dict]:
        return self.api("GET", "api/kernels")

    def stop(self, timeout: float = 20.0) -> list[int]:
        """Stop the server and its kernels (and what they started); the pids that needed
        SIGKILL at the end (an empty list when everything shut down by itself)."""
        if self.proc is not None and self.proc.poll() is None:
            try:
                self.api("POST", "api/shutdown", timeout=5.0)
            except (OSError, urllib.error.URLError):
                pass
            try:
                self.proc.wait(timeout)
            except subprocess.TimeoutExpired:
                for sig, wait in ((signal.SIGTERM, 10.0), (signal.SIGKILL, 5.0)):
                    try:
                        os.killpg(self.proc.pid, sig)
                    except ProcessLookupError:
                        break
                    try:
                        self.proc.wait(wait)
                        break
                    except subprocess.TimeoutExpired:
                        continue
        killed = []
        deadline = time.monotonic() + 10.0
        while marked_processes(self.marker) and time.monotonic() < deadline:
            time.sleep(0.2)  # kernels shutting down
        for pid in marked_processes(self.marker):
            try:
                os.kill(pid, signal.SIGKILL)
                killed.append(pid)
            except ProcessLookupError:
                pass
        return killed
