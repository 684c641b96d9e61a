"""The release tool makes the student editions: solution blocks inside functions become
``raise NotImplementedError``; blocks at the top level of a cell go, their placeholder
stays, and a notebook whose student edition would not define a name it reads is refused."""

import nbformat
import pytest

from kinlib import KinlibError
from kinlib.assign import release_notebook, release_source

TOP = "R_try = ...  # your answer\n### BEGIN SOLUTION\nc = 0.5\nR_try = c * 2\n### END SOLUTION\n"


def notebook(*sources):
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(s) for s in sources]
    return nb


def test_a_top_level_solution_goes_and_its_placeholder_stays():
    assert release_source(TOP) == "R_try = ...  # your answer"
    student = release_notebook(notebook(TOP, 'check("01.1", R_try)'))
    assert student.cells[0].source == "R_try = ...  # your answer"
    assert student.cells[1].source == 'check("01.1", R_try)'
    exec(student.cells[0].source, {})  # the blank edition runs


def test_a_solution_inside_a_function_raises_not_implemented():
    src = ("def f(x):\n    '''Twice x.'''\n"
           "    ### BEGIN SOLUTION\n    return 2 * x\n    ### END SOLUTION\n")
    scope = {}
    exec(release_source(src), scope)
    with pytest.raises(NotImplementedError):
        scope["f"](1)


def test_a_name_the_notebook_reads_needs_a_placeholder():
    no_placeholder = "### BEGIN SOLUTION\nR_try = 1\n### END SOLUTION\n"
    with pytest.raises(KinlibError, match=r"cell 0: the solution assigns R_try.*R_try = \.\.\."):
        release_notebook(notebook(no_placeholder, "print(R_try)"))
    # a helper name of the solution that nothing else reads needs none (c above)
    release_notebook(notebook(TOP, "print(R_try)"))
    with pytest.raises(KinlibError, match="assigns c"):
        release_notebook(notebook(TOP, "print(c)"))


def test_outputs_go_and_markers_in_markdown_are_refused():
    nb = notebook(TOP)
    nb.cells[0].outputs = [nbformat.v4.new_output("stream", text="x")]
    nb.cells[0].execution_count = 3
    student = release_notebook(nb)
    assert student.cells[0].outputs == [] and student.cells[0].execution_count is None
    nb.cells.append(nbformat.v4.new_markdown_cell("### BEGIN SOLUTION\nno\n### END SOLUTION"))
    with pytest.raises(KinlibError, match="markers belong in code cells"):
        release_notebook(nb)


def test_a_cell_for_the_instructor_only_is_left_out():
    discussion = nbformat.v4.new_markdown_cell("It is R_Z(θ): the half angles double.")
    discussion.metadata["tags"] = ["solution"]
    worked = nbformat.v4.new_code_cell("c2_by_hand = 1 + 1")
    worked.metadata["tags"] = ["solution"]
    nb = notebook(TOP, 'check("01.1", R_try)')
    nb.cells[1:1] = [discussion, worked]
    student = release_notebook(nb)
    assert [c.source for c in student.cells] == ["R_try = ...  # your answer",
                                                 'check("01.1", R_try)']
    nb.cells.append(nbformat.v4.new_code_cell("print(c2_by_hand)"))
    with pytest.raises(KinlibError, match=r"instructor only .* reads c2_by_hand"):
        release_notebook(nb)


# -- the command line: its folders, its dependencies -----------------------------------------

def _python_m(module: str, *args, poison=(), cwd=None):
    """``python -m module args`` in a fresh interpreter where the modules ``poison`` cannot be
    imported (``sys.modules[name] = None``: what a missing package looks like)."""
    import subprocess
    import sys

    code = ("import runpy, sys\n"
            f"for name in {list(poison)!r}:\n    sys.modules[name] = None\n"
            f"sys.argv = [{module!r}, *{list(args)!r}]\n"
            f"runpy.run_module({module!r}, run_name='__main__', alter_sys=True)\n")
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=cwd, timeout=300)


def test_without_nbformat_the_tool_names_the_course_extra(tmp_path):
    (tmp_path / "instructor").mkdir()
    nbformat.write(notebook(TOP, 'check("01.1", R_try)'), tmp_path / "instructor" / "01.ipynb")
    out = _python_m("kinlib.assign", "--check", poison=["nbformat"], cwd=tmp_path)
    assert out.returncode == 2, out.stdout + out.stderr
    assert "Traceback" not in out.stderr
    assert "python -m kinlib.assign needs nbformat" in out.stderr
    assert "pip install 'kinlib[course]'" in out.stderr
    control = _python_m("kinlib.assign", "--check", cwd=tmp_path)  # nbformat there: stale
    assert control.returncode == 1 and "notebooks/01.ipynb" in control.stderr, control
    empty = _python_m("kinlib.assign", cwd=tmp_path / "instructor")  # nothing to release
    assert empty.returncode == 2 and "Traceback" not in empty.stderr, empty
    assert "no source notebooks in" in empty.stderr and "--root" in empty.stderr


def test_the_folders_are_the_current_directory_s_unless_root_is_given(tmp_path, monkeypatch):
    from kinlib.assign import main

    source = tmp_path / "course" / "assignments" / "source"
    source.mkdir(parents=True)
    nbformat.write(notebook(TOP, 'check("01.1", R_try)'), source / "01_x.ipynb")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(KinlibError, match=r"no source notebooks in .*instructor/.*--root"):
        main(["--check"])
    assert main(["--root", "course", "--check"]) == 1  # stale: no release yet
    monkeypatch.chdir(tmp_path / "course")
    assert main([]) == 0
    released = nbformat.read(tmp_path / "course" / "assignments" / "release" / "01_x.ipynb",
                             as_version=4)
    assert released.cells[0].source == "R_try = ...  # your answer"
    assert main(["--check"]) == 0
