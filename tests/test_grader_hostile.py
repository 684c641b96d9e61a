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
def sandboxed(runs):
    return runs[0]


@pytest.fixture(scope="module")
def control(runs):
    return runs[1]


def test_the_whole_batch_is_graded_and_reported(sandboxed):
    hc.check_batch(*sandboxed, "bubblewrap")
    assert all(r["sandbox"].startswith("bubblewrap") for r in sandboxed[1].values())


@pytest.mark.parametrize("kind", hc.NO_MARKS)
def test_no_marks_without_solving(sandboxed, kind):
    hc.check_no_marks(sandboxed[1], kind)


def test_a_table_of_the_public_cases_fails_the_hidden_ones(sandboxed):
    hc.check_table(*sandboxed)


@pytest.mark.parametrize("kind", hc.HONEST_KINDS)
def test_attacks_leave_the_honest_score(sandboxed, kind):
    hc.check_honest(sandboxed[1], kind)


def test_forged_text_and_odd_values_stay_inside_their_own_check(sandboxed):
    hc.check_forged_text(sandboxed[1])


def test_slow_cases_stop_at_the_submission_deadline(sandboxed):
    hc.check_slow(sandboxed[1])


def test_nothing_is_left_running_or_listening(sandboxed):
    hc.check_nothing_left(sandboxed[0])


def test_the_machine_is_untouched_and_the_next_run_is_normal(sandboxed):
    hc.check_untouched(sandboxed[0])


def test_secrets_do_not_leak(sandboxed):
    hc.check_secrets(*sandboxed)


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
