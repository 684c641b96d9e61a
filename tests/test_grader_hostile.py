"""A determined student against the grader: the hostile corpus (``tests/hostile_corpus.py``:
one submission per attack) in the bubblewrap sandbox.

Each submission is graded by the command line, in the sandbox, with a secret seed and a
short per-submission time limit, as an instructor would run it, by a *copy* of kinlib under
a temporary directory. Each test asserts the honest score, canaries untouched, nothing left
running, the grader's files unchanged, and that the next run is normal. The same checks
hold the container tier to the same corpus (``tests/test_container_grading.py``).

The control: the attacks that can be run safely are graded again ``--unsandboxed``, where
they must succeed (marks without solving, a forged line in the grader's output, the
secret read from ``/proc``, a canary deleted, the grader's code changed, a port held after
the grader ended). So each sandboxed result is the sandbox's doing, not an attack that
never worked.
"""

from __future__ import annotations

import hostile_corpus as hc
import pytest

from kinlib.grade import format_report


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The corpus in the sandbox, and the control without it, graded side by side."""
    base = tmp_path_factory.mktemp("hostile")
    control = hc.Run(base, "control", hc.CONTROLS, unsandboxed=True)
    sandboxed = None
    try:
        sandboxed = hc.Run(base, "sandboxed", hc.KINDS)
        sandboxed.start()
        # (the control holds no slow attack: generous deadlines keep a loaded machine from
        # stopping an attack that would have worked)
        control.start(timeout=120, cell_timeout=40)
        control_results = control.finish()
        listening = not hc.port_free(control.port)  # (its daemon has outlived the grader)
        control.cleanup()
        results = sandboxed.finish()
        sandboxed.after = hc.digest(sandboxed.grader), hc.digest(sandboxed.root / "assignments")
        again = hc.copy.copy(sandboxed)  # the next run, on the public cases: normal
        again.out = sandboxed.root / "out_public"
        sandboxed.public = again.grade(["table", "classmate.ipynb"], secret=False)
        yield (sandboxed, results), (control, control_results, listening)
    finally:
        if sandboxed is not None:
            sandboxed.cleanup()
        control.cleanup()


@pytest.fixture(scope="module")
def corpus(runs):
    return runs[0]


@pytest.fixture(scope="module")
def control(runs):
    return runs[1]


class TestInBubblewrap(hc.CorpusChecks):
    """The corpus's checks (tests/hostile_corpus.py), in the bubblewrap sandbox."""

    tier = "bubblewrap"

    def test_every_result_names_bubblewrap(self, corpus):
        assert all(r["sandbox"].startswith("bubblewrap") for r in corpus[1].values())


# -- the control: the same attacks without the sandbox succeed ------------------------------
def test_control_without_the_sandbox_the_attacks_work(control):
    run, results, listening = control
    assert all(r["warning"] for r in results.values() if r)
    assert "WARNING: graded WITHOUT the sandbox" in format_report(results["meta_path"])
    for kind in ("meta_path", "kinlib_by_path"):
        assert hc.score(results, kind) == hc.HONEST, kind  # kinlib's rotx, roty, rotz
    for kind in ("instructor_source", "reads_classmate"):
        assert hc.score(results, kind) == hc.FULL, kind
    assert run.forged, "the forged line did not reach the grader's output"
    assert not run.canary.exists() and "pwned" in (run.home / ".bashrc").read_text()
    assert hc.digest(run.grader) != run.before
    stolen = {c["function"]: c for c in results["snoop"]["checks"]}["rotx"]
    stolen = stolen["diagnoses"][0]["message"]
    assert run.env_canary in stolen and run.secret_text in stolen
    assert listening, "the listener did not outlive the unsandboxed grading"
    assert run.unix_got == [run.marker], run.unix_got
