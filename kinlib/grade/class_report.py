"""The class report: what a class got right and the mistakes it made most, as one HTML page.

For each assignment and function: how many students are right (every case passed), the
mean score, and the most common diagnosed mistakes (the keys of each result's
``checks[*].diagnoses``), each with how many students made it, its message and one example
from a student's result (input, what they returned, what was expected). The page starts
with the class's most common mistakes as a chart ("4 of 10 (40 %): 01_rotations · rotx —
transposed"), and each assignment has a chart of its functions.

The page is self-contained: inline SVG and one inline style sheet, no script, nothing
fetched (a Content-Security-Policy that allows nothing else says so to the browser too),
so it opens from ``file://`` anywhere. Everything that comes from a submission (messages
can quote what a student's code raised, examples what it returned) is HTML-escaped.
"""

from __future__ import annotations

import re
from collections import defaultdict
from html import escape

from ._grader import assignment_names

__all__ = ["class_stats", "class_report", "write_report"]

#: diagnoses that are not mistakes of their own: a case not run after an earlier one hung,
#: the note on credit held back for trivial answers
NOT_MISTAKES = ("not run", "trivial")
TOP = 3  # mistakes shown per function
GLANCE = 10  # mistakes in the class's chart
#: what says a function was not done yet, not that it was done wrong (kept out of the chart
#: of mistakes and counted apart)
NOT_DONE = ("raised NotImplementedError", "missing")


def _short(text, n: int = 300) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= n else text[:n - 1] + "…"


def _example(check: dict, message: str) -> dict | None:
    """The example of ``check`` that shows ``message`` (else its first)."""
    examples = [e for e in check.get("examples", []) if isinstance(e, dict)]
    for e in examples:
        if e.get("message") == message:
            return e
    return examples[0] if examples else None


def _key(diagnosis: dict) -> str:
    """A diagnosis's key; for an exception, with its name ("raised NotImplementedError":
    not done yet, is another story than "raised ValueError")."""
    key = str(diagnosis.get("key"))
    m = re.match(r"raised (\w[\w.]*)", str(diagnosis.get("message", "")))
    return f"raised {m[1][:60]}" if key == "raised" and m else key


def class_stats(results: list[dict]) -> list[dict]:
    """The numbers of the report, per assignment (in the course's order)::

        [{"assignment", "title", "max_score", "students", "not_graded", "mean",
          "functions": [{"function", "title", "points", "students", "right", "mean",
                         "mistakes": [{"key", "students", "message", "example"}, ...]}]}]

    ``students`` counts the graded submissions of the assignment, ``right`` those whose
    every case of the function passed, a mistake's ``students`` those whose result names it
    (most common first; its message and example are the first such student's; an exception
    is named: ``"raised ValueError"``).
    """
    by_assignment: dict[str, list[dict]] = defaultdict(list)
    not_graded: dict[str, int] = defaultdict(int)
    for r in results:
        if r.get("graded"):
            by_assignment[r["assignment"]].append(r)
        else:
            not_graded[str(r.get("assignment") or "(unknown assignment)")] += 1
    names = [a for a in assignment_names() if a in by_assignment]
    names += sorted(a for a in by_assignment if a not in names)
    out = []
    for a in names:
        rs = by_assignment[a]
        functions: dict[str, dict] = {}
        for r in rs:
            for c in r["checks"]:
                f = functions.setdefault(c["function"], {
                    "function": c["function"], "title": c.get("title", ""),
                    "points": c["points"], "students": 0, "right": 0, "scores": [],
                    "mistakes": {}})
                f["students"] += 1
                f["right"] += c["total"] > 0 and c["passed"] == c["total"]
                f["scores"].append(float(c["score"]))
                for d in c.get("diagnoses", []):
                    if not isinstance(d, dict) or d.get("key") in NOT_MISTAKES:
                        continue
                    key = _key(d)
                    m = f["mistakes"].setdefault(key, {
                        "key": key, "students": 0,
                        "message": str(d.get("message", "")),
                        "example": _example(c, d.get("message"))})
                    m["students"] += 1
        for f in functions.values():
            f["mean"] = sum(f.pop("scores")) / f["students"]
            f["mistakes"] = sorted(f["mistakes"].values(), key=lambda m: -m["students"])
        out.append({"assignment": a, "title": rs[0].get("title", ""),
                    "max_score": float(rs[0]["max_score"]), "students": len(rs),
                    "not_graded": not_graded.pop(a, 0),
                    "mean": sum(float(r["score"]) for r in rs) / len(rs),
                    "functions": list(functions.values())})
    for a, n in not_graded.items():  # nothing of it could be graded
        out.append({"assignment": a, "title": "", "max_score": 0.0, "students": 0,
                    "not_graded": n, "mean": 0.0, "functions": []})
    return out


def _pct(k: int, n: int) -> str:
    return f"{100 * k / n:.0f} %" if n else "–"


STYLE = """
body { font: 15px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 1100px;
       padding: 0 1em; color: #222; }
h1 { font-size: 1.6em; } h2 { margin-top: 2em; border-bottom: 1px solid #ccc; }
table { border-collapse: collapse; width: 100%; margin: 1em 0; }
th, td { border-bottom: 1px solid #e4e4e4; padding: .35em .5em; text-align: left;
         vertical-align: top; }
th { background: #f4f4f4; } td.n { text-align: right; white-space: nowrap; }
code { font-size: .85em; background: #f6f6f6; padding: 0 .2em; word-break: break-all; }
.mistake { margin-bottom: .6em; } .key { font-weight: 600; color: #b44a00; }
.example { color: #555; font-size: .9em; } svg { max-width: 100%; height: auto; }
svg text { font: 12px system-ui, sans-serif; fill: #222; }
.legend span { display: inline-block; width: .9em; height: .9em; margin: 0 .3em 0 1em;
               vertical-align: middle; }
"""
GREEN, ORANGE, GREY = "#4a9a4a", "#e07b1a", "#e6e6e6"


def _bar_chart(rows: list[tuple[str, list[tuple[float, str]], str]], title: str) -> str:
    """An inline SVG of horizontal bars: each row a label, stacked parts (fraction of the
    bar 0–1, colour) and a note at its right."""
    label_w, bar_w, note_w, h = 330, 320, 250, 24
    width, height = label_w + bar_w + note_w, h * len(rows) + 8
    parts = [f'<svg role="img" width="{width}" '
             f'height="{height}" viewBox="0 0 {width} {height}">'
             f"<title>{escape(title)}</title>"]
    for i, (label, stack, note) in enumerate(rows):
        y = 4 + i * h
        parts.append(f'<text x="{label_w - 8}" y="{y + 16}" text-anchor="end">'
                     f"{escape(_short(label, 48))}</text>")
        parts.append(f'<rect x="{label_w}" y="{y + 3}" width="{bar_w}" height="{h - 8}" '
                     f'fill="{GREY}"/>')
        x = float(label_w)
        for frac, colour in stack:
            w = max(0.0, min(1.0, frac)) * bar_w
            if w > 0:
                parts.append(f'<rect x="{x:.1f}" y="{y + 3}" width="{w:.1f}" '
                             f'height="{h - 8}" fill="{colour}"/>')
            x += w
        parts.append(f'<text x="{label_w + bar_w + 8}" y="{y + 16}">'
                     f"{escape(_short(note, 40))}</text>")
    parts.append("</svg>")
    return "".join(parts)


def _glance(stats: list[dict]) -> str:
    found, undone = [], []
    for s in stats:
        for f in s["functions"]:
            for m in f["mistakes"]:
                row = (m["students"] / f["students"], m["students"], f["students"],
                       s["assignment"], f["function"], m)
                (undone if m["key"] in NOT_DONE else found).append(row)
    found.sort(key=lambda t: (-t[0], -t[1], t[3], t[4]))
    undone.sort(key=lambda t: (-t[0], -t[1], t[3], t[4]))
    found = found[:GLANCE]
    apart = ""
    if undone:
        apart = ("<p>Not done yet (not defined, or still raising NotImplementedError), "
                 "counted apart from the mistakes: "
                 + "; ".join(f"{escape(a)} · <code>{escape(fn)}</code> {k} of {n}"
                             for _, k, n, a, fn, _m in undone[:GLANCE]) + ".</p>")
    if not found:
        return "<p>No mistakes were diagnosed.</p>" + apart
    chart = _bar_chart([(f"{a} · {fn}: {m['key']}", [(share, ORANGE)],
                         f"{k} of {n} students ({_pct(k, n)})")
                        for share, k, n, a, fn, m in found],
                       "The class's most common mistakes: the share of the students who "
                       "handed in the assignment")
    items = "".join(f"<li><b>{_pct(k, n)}</b> of the class ({k} of {n}) — "
                    f"{escape(a)} · <code>{escape(fn)}</code>: "
                    f'<span class="key">{escape(m["key"])}</span> — '
                    f"{escape(_short(m['message']))}</li>"
                    for _, k, n, a, fn, m in found)
    return f"{chart}<ol>{items}</ol>{apart}"


def _example_html(e: dict | None) -> str:
    if not e:
        return ""
    out = [f"e.g. input <code>{escape(_short(e.get('input', ''), 200))}</code>"]
    if e.get("got") is not None:
        out.append(f"returned <code>{escape(_short(e['got'], 200))}</code>")
    if e.get("expected") is not None:
        out.append(f"expected <code>{escape(_short(e['expected'], 200))}</code>")
    return f'<div class="example">{"; ".join(out)}</div>'


def _assignment(s: dict) -> str:
    a = escape(s["assignment"])
    head = f'<h2 id="{a}">{a}{" — " + escape(s["title"]) if s["title"] else ""}</h2>'
    if not s["students"]:
        return f"{head}<p>{s['not_graded']} submission(s), none could be graded.</p>"
    n = s["students"]
    line = (f"<p>{n} student(s) graded, mean score <b>{s['mean']:.4g} / "
            f"{s['max_score']:g}</b> ({_pct(s['mean'], s['max_score'])})")
    if s["not_graded"]:
        line += f"; {s['not_graded']} submission(s) could not be graded"
    chart_rows, table = [], []
    for f in s["functions"]:
        top = f["mistakes"][0] if f["mistakes"] else None
        wrong = top["students"] / f["students"] if top else 0.0
        note = f"{_pct(f['right'], f['students'])} right"
        if top:
            note += f" · {_pct(top['students'], f['students'])} {top['key']}"
        chart_rows.append((f["function"], [(f["right"] / f["students"], GREEN),
                                           (wrong, ORANGE)], note))
        mistakes = "".join(
            f'<div class="mistake"><span class="key">{escape(m["key"])}</span>: '
            f"{m['students']} of {f['students']} ({_pct(m['students'], f['students'])}) — "
            f"{escape(_short(m['message']))}{_example_html(m['example'])}</div>"
            for m in f["mistakes"][:TOP])
        table.append(f"<tr><td><code>{escape(f['function'])}</code><br>"
                     f"{escape(f['title'])}</td><td class=n>{f['points']:g}</td>"
                     f"<td class=n>{f['right']} of {f['students']} "
                     f"({_pct(f['right'], f['students'])})</td>"
                     f"<td class=n>{f['mean']:.3g} / {f['points']:g}</td>"
                     f"<td>{mistakes or '—'}</td></tr>")
    chart = _bar_chart(chart_rows, f"{s['assignment']}: the share of students right in each "
                                   "function (green) and with its most common mistake "
                                   "(orange)")
    return (f"{head}{line}.</p>{chart}<p class=legend><span style=\"background:{GREEN}\">"
            f"</span>right (every case) <span style=\"background:{ORANGE}\"></span>"
            "the most common mistake</p><table><tr><th>function</th><th>points</th>"
            "<th>right</th><th>mean</th><th>most common mistakes (students)</th></tr>"
            + "".join(table) + "</table>")


def class_report(results: list[dict], title: str = "Class report") -> str:
    """The report of ``results`` (of :func:`~kinlib.grade.grade_many`, or loaded from
    result files) as one self-contained HTML page."""
    stats = class_stats(results)
    graded = sum(s["students"] for s in stats)
    cases = sorted({str(r.get("cases")) for r in results if r.get("graded")})
    intro = (f"<p>{graded} submission(s) graded"
             + (f", {len(results) - graded} could not be" if len(results) > graded else "")
             + f"; cases: {escape(', '.join(cases) or '–')}. A student is <i>right</i> in a "
             "function when every case passed; a mistake counts the students whose result "
             "names it.</p>")
    toc = "".join(f'<li><a href="#{escape(s["assignment"])}">{escape(s["assignment"])}'
                  f"</a></li>" for s in stats)
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; "
            "style-src 'unsafe-inline'\">"
            f"<title>{escape(title)}</title><style>{STYLE}</style></head><body>"
            f"<h1>{escape(title)}</h1>{intro}<ul>{toc}</ul>"
            "<h2>At a glance: the most common mistakes</h2>"
            f"{_glance(stats)}{''.join(_assignment(s) for s in stats)}</body></html>\n")


def write_report(results: list[dict], path, title: str = "Class report") -> None:
    """Write :func:`class_report` of ``results`` to ``path`` (UTF-8)."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(class_report(results, title))
