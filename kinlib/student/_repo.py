"""Where a student repository may be written, and writing it: the files of a release,
changed ones only, the previous release's files that are no longer produced removed, and
the manifest that says which files the release wrote."""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path, PurePosixPath

from ..errors import KinlibError

__all__ = ["MANIFEST", "FORMAT", "Written", "previous_release", "check_destination",
           "write_files"]

#: the manifest in the student repository's root (committed with it): which files the
#: release wrote, so that the next release into a clone of it can update it
MANIFEST = ".kinlib-student-release.json"
FORMAT = "kinlib student release"
#: what may be in a folder the first release is written into
_EMPTY_OK = {".git"}
_EXECUTABLE = {"binder/postBuild"}


@dataclass(frozen=True)
class Written:
    """What a release did: its ``files`` (paths relative to ``dest``), those it wrote
    because they were new or different (``changed``) and the previous release's files it
    ``removed``."""

    dest: Path
    files: tuple[str, ...]
    changed: tuple[str, ...]
    removed: tuple[str, ...]


def _safe(rel, where: str) -> str:
    """``rel``, a manifest's entry, if it names a file inside the repository (relative,
    no ``..``, not in ``.git``)."""
    p = PurePosixPath(rel) if isinstance(rel, str) else None
    if (p is None or not rel or p.is_absolute() or ".." in p.parts or "\\" in rel
            or p.parts[0] == ".git" or str(p) != rel):
        raise KinlibError(f"{where}: {rel!r} is not a path inside the student repository; "
                          "this manifest was not written by kinlib: restore it from the "
                          "repository's history, or start from an empty folder")
    return rel


def previous_release(dest: Path) -> dict | None:
    """The manifest of the release in ``dest`` (its ``files`` checked), or None when there
    is none."""
    path = dest / MANIFEST
    if not path.is_file():
        return None
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except ValueError as exc:
        raise KinlibError(f"{path}: not valid JSON ({exc}); restore it from the student "
                          "repository's history, or start from an empty folder") from None
    if not isinstance(data, dict) or data.get("format") != FORMAT \
            or not isinstance(data.get("files"), list):
        raise KinlibError(f"{path}: not the manifest of a kinlib student release (expected "
                          f"\"format\": {FORMAT!r} and a list of \"files\")")
    data["files"] = [_safe(rel, str(path)) for rel in data["files"]]
    return data


def check_destination(root: Path, dest: Path, solution_marker: str) -> dict | None:
    """Refuse a ``dest`` that would publish or mix with the instructor's repository
    ``root``, that holds files of something other than a student release, or instructor
    files that the release would leave there (a notebook holding ``solution_marker``, an
    ``instructor/`` or ``assignments/source/`` folder); the previous release's manifest
    (None for a new or empty folder)."""
    r, d = root.resolve(), dest.resolve()
    if d == r or r.is_relative_to(d):
        raise KinlibError(
            f"{dest} is the course repository or holds it ({r}): a student repository "
            "there would publish instructor/ and assignments/source/, the solutions. "
            "Give a folder of its own, such as build/student-repo")
    if d.is_relative_to(r) and not d.is_relative_to(r / "build"):
        raise KinlibError(
            f"{dest} is inside the course repository ({r}) but not under build/: the "
            "student repository would lie among the instructor's own files, where a commit "
            "of the instructor repository takes it in and the instructor's folders "
            "(instructor/, assignments/source/: the solutions) sit beside it. Write it to "
            "build/student-repo (ignored by git) or to a folder outside the repository")
    if d.exists() and not d.is_dir():
        raise KinlibError(f"{dest} is a file, not a folder")
    previous = previous_release(d) if d.is_dir() else None
    if previous is None and d.is_dir():
        others = sorted(p.name for p in d.iterdir() if p.name not in _EMPTY_OK)
        if others:
            shown = ", ".join(others[:5]) + (", ..." if len(others) > 5 else "")
            raise KinlibError(
                f"{dest} is not empty ({shown}) and holds no student release (no {MANIFEST}): "
                "give a new or empty folder, or a clone of the student repository a release "
                "was published to; nothing was written")
    leaks = _instructor_files(d, set(previous["files"]), solution_marker) if previous else []
    if leaks:
        raise KinlibError(
            f"{dest} holds instructor files that a release would leave in place and publish: "
            f"{', '.join(leaks)} (solution blocks, or instructor/ or assignments/source/); "
            "remove them first (nothing was written)")
    return previous


def _walk(dest: Path):
    """Every file under ``dest`` but in ``.git``, as a path relative to it."""
    for top, dirs, files in os.walk(dest):
        dirs[:] = sorted(x for x in dirs if not (Path(top) == dest and x == ".git"))
        for name in sorted(files):
            yield (Path(top) / name).relative_to(dest).as_posix()


def _instructor_files(dest: Path, ours, solution_marker: str) -> list[str]:
    """The files under ``dest`` that are not the previous release's (``ours``: those a
    release rewrites or removes) and that are an instructor's: in an ``instructor/`` or
    ``assignments/source/`` folder, or a notebook holding a solution block."""
    found = []
    for rel in _walk(dest):
        parts = rel.split("/")
        if rel in ours:
            continue
        if ("instructor" in parts[:-1] or rel.startswith("assignments/source/")
                or (rel.endswith(".ipynb") and solution_marker
                    in (dest / rel).read_text(encoding="utf-8", errors="replace"))):
            found.append(rel)
    return found


def write_files(dest: Path, files: dict[str, bytes], previous: dict | None,
                manifest: dict) -> Written:
    """Write the release ``files`` (relative path -> content) into ``dest`` (checked by
    :func:`check_destination`, whose result is ``previous``): only those that are new or
    changed; then remove the previous release's files that are gone from it, and write
    the manifest (``manifest`` plus the list of files)."""
    old = set(previous["files"]) if previous else set()
    foreign = [rel for rel in files if rel not in old and (dest / rel).exists()]
    if foreign:
        raise KinlibError(
            f"{dest}: the release would overwrite {', '.join(sorted(foreign))}, which the "
            "previous release did not write; move them out of the way (nothing was written)")
    changed = []
    for rel, content in sorted(files.items()):
        path = dest / rel
        if not path.is_file() or path.read_bytes() != content:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(content)
            changed.append(rel)
        if rel in _EXECUTABLE:
            path.chmod(0o755)
    removed = []
    for rel in sorted(old - set(files) - {MANIFEST}):
        path = dest / rel
        if path.is_file() or path.is_symlink():
            path.unlink()
            removed.append(rel)
        parent = path.parent
        while parent != dest and parent.is_dir() and not any(parent.iterdir()):
            parent.rmdir()
            parent = parent.parent
    record = {"format": FORMAT, **manifest, "files": sorted(files)}
    text = json.dumps(record, indent=1, ensure_ascii=False) + "\n"
    if not (dest / MANIFEST).is_file() or (dest / MANIFEST).read_text(encoding="utf-8") != text:
        (dest / MANIFEST).write_text(text, encoding="utf-8")
    return Written(dest, tuple(sorted(files)), tuple(changed), tuple(removed))
