"""A malformed robot description never crashes, hangs or loads silently wrong.

Every file in ``tests/urdf_bad/`` has one defect (its first comment says which). Each must
raise :class:`kinlib.URDFError` whose message names the file, says what is wrong, names
the element, and gives the line: the expected line is found here by searching the file's
text, never copied from kinlib's message. Positive controls repair the defect and load.
"""

import time
from pathlib import Path

import numpy as np
import pytest

from kinlib import KinlibError, URDFError, load_urdf
from kinlib import urdf as urdf_module

CORPUS = Path(__file__).parent / "urdf_bad"

# file, key phrase, text that marks the offending line (its n-th occurrence), element named
CASES = [
    ("syntax_unclosed.urdf", "mismatched tag", ("</robot>", 0), None),
    ("not_xml.urdf", "XML syntax error", ("this is not", 0), None),
    ("empty.urdf", "no element found", None, None),
    ("not_robot.urdf", "expected <robot>", ("<model", 0), "<model name='bad'>"),
    ("robot_without_name.urdf", "missing or empty attribute name", ("<robot", 0), "<robot>"),
    ("link_without_name.urdf", "missing or empty attribute name", ("<link/>", 0), "<link>"),
    ("duplicate_link.urdf", "duplicate link name", ('<link name="a"/>', 1), "'a'"),
    ("duplicate_joint.urdf", "duplicate joint name", ('<joint name="j1"', 1), "'j1'"),
    ("joint_without_type.urdf", "missing attribute type", ("<joint", 0), "<joint name='j1'>"),
    ("unknown_joint_type.urdf", "unknown joint type 'hinge'", ("<joint", 0), "'j1'"),
    ("floating_joint.urdf", "does not support joint type 'floating'", ("<joint", 0), "'j1'"),
    ("planar_joint.urdf", "does not support joint type 'planar'", ("<joint", 0), "'j1'"),
    ("missing_parent.urdf", "missing <parent>", ("<joint", 0), "<joint name='j1'>"),
    ("missing_child.urdf", "missing <child>", ("<joint", 0), "<joint name='j1'>"),
    ("two_parents.urdf", "more than one <parent>", ("<joint", 0), "<joint name='j1'>"),
    ("parent_link_missing.urdf", "parent link 'ghost' does not exist", ("<joint", 0), "'j1'"),
    ("child_link_missing.urdf", "child link 'ghost' does not exist", ("<joint", 0), "'j1'"),
    ("self_parent.urdf", "is its own parent", ('<joint name="j2"', 0), "'j2'"),
    ("link_two_parents.urdf", "two parent joints", ('<joint name="j2"', 0), "'c'"),
    ("cycle.urdf", "cycle", ("<joint", 0), None),
    ("two_roots.urdf", "several root links", ('<link name="lonely"', 0), "'lonely'"),
    ("detached_cycle.urdf", "form a cycle", ('<link name="c"', 0), "['c', 'd']"),
    ("zero_axis.urdf", "zero vector", ("<axis", 0), "<joint name='j1'> <axis>"),
    ("axis_not_numeric.urdf", "expected 3 numbers", ("<axis", 0), "<joint name='j1'> <axis>"),
    ("xyz_two_numbers.urdf", "got 2", ("<origin", 0), "<joint name='j1'> <origin>"),
    ("xyz_four_numbers.urdf", "got 4", ("<origin", 0), "<joint name='j1'> <origin>"),
    ("rpy_wrong_length.urdf", "rpy='0.1 0.2'", ("<origin", 0), "<joint name='j1'> <origin>"),
    ("xyz_nan.urdf", "NaN or infinity", ("<origin", 0), "<joint name='j1'> <origin>"),
    ("rpy_inf.urdf", "NaN or infinity", ("<origin", 0), "<joint name='j1'> <origin>"),
    ("axis_nan.urdf", "NaN or infinity", ("<axis", 0), "<joint name='j1'> <axis>"),
    ("revolute_without_limit.urdf", "needs <limit", ("<joint", 0), "<joint name='j1'>"),
    ("prismatic_without_limit.urdf", "needs <limit", ("<joint", 0), "<joint name='j1'>"),
    ("limit_lower_above_upper.urdf", "greater than upper", ("<limit", 0), "<limit>"),
    ("limit_not_numeric.urdf", "lower='zero'", ("<limit", 0), "<joint name='j1'> <limit>"),
    ("mimic_missing_joint.urdf", "mimics 'ghost', which does not exist",
     ('<joint name="j2"', 0), "'j2'"),
    ("mimic_fixed_joint.urdf", "which is fixed", ('<joint name="j2"', 0), "'j2'"),
    ("mimic_cycle.urdf", "mimic joints form a cycle", ('<joint name="j1"', 0), "j1 -> j2"),
    ("geometry_unknown.urdf", "unknown geometry <capsule>", ("<capsule", 0),
     "<link name='a'> <capsule>"),
    ("box_two_sizes.urdf", "expected 3 numbers, got 2", ("<box", 0), "<link name='a'> <box>"),
    ("cylinder_without_radius.urdf", "missing attribute radius", ("<cylinder", 0),
     "<link name='a'> <cylinder>"),
    ("sphere_negative.urdf", "positive", ("<sphere", 0), "<link name='a'> <sphere>"),
    ("mesh_without_filename.urdf", "filename", ("<mesh", 0), "<link name='a'> <mesh>"),
    ("geometry_empty.urdf", "exactly one shape", ("<geometry", 0), "<geometry>"),
    ("billion_laughs.urdf", "<!DOCTYPE> declaration is not allowed", ("<!DOCTYPE", 0), None),
    ("external_entity.urdf", "<!DOCTYPE> declaration is not allowed", ("<!DOCTYPE", 0), None),
    ("parameter_entity.urdf", "<!DOCTYPE> declaration is not allowed", ("<!DOCTYPE", 0),
     None),
]

IDS = [c[0] for c in CASES]


def expected_line(text: str, anchor) -> int:
    needle, nth = anchor
    hits = [i + 1 for i, line in enumerate(text.splitlines()) if needle in line]
    assert len(hits) > nth, f"{needle!r} occurs {len(hits)} times"
    return hits[nth]


def check(exc: URDFError, label: str, case, text: str) -> None:
    _, phrase, anchor, element = case
    msg = str(exc)
    assert isinstance(exc, KinlibError) and isinstance(exc, ValueError)
    assert msg.startswith(label), msg
    assert phrase in msg, msg
    if anchor is not None:
        line = expected_line(text, anchor)
        assert msg.startswith((f"{label}:{line}: ", f"{label}: line {line}: ")), msg
    if element is not None:
        assert element in msg, msg
    assert "Traceback" not in msg


def test_corpus_and_table_agree():
    assert sorted(p.name for p in CORPUS.glob("*.urdf")) == sorted(IDS)
    assert len(IDS) == len(set(IDS))


@pytest.mark.parametrize("case", CASES, ids=IDS)
def test_bad_file(case):
    path = CORPUS / case[0]
    text = path.read_text()
    if text:
        first = text.splitlines()[1 if text.startswith("<?xml") else 0]
        assert first.startswith("<!--") or case[0] == "not_xml.urdf", "say what is wrong"
    with pytest.raises(URDFError) as exc:
        load_urdf(path)
    check(exc.value, str(path), case, text)
    with pytest.raises(URDFError) as exc:  # the same through the str(path) route
        load_urdf(str(path))
    check(exc.value, str(path), case, text)


@pytest.mark.parametrize("case", [c for c in CASES if c[0] not in ("empty.urdf",
                                                                    "not_xml.urdf")],
                         ids=lambda c: c[0])
def test_bad_text_and_bytes(case):
    text = (CORPUS / case[0]).read_text()
    for source, label in ((text, "<urdf string>"), (text.encode(), "<urdf bytes>")):
        with pytest.raises(URDFError) as exc:
            load_urdf(source)
        check(exc.value, label, case, text)


# -- the defect, and only the defect, is what is refused -------------------------------
REPAIRS = [
    ("duplicate_link.urdf", ('  <link name="a"/>\n  <joint', "  <joint"), 2),
    ("zero_axis.urdf", ('xyz="0 0 0"', 'xyz="0 0 1"'), 2),
    ("xyz_nan.urdf", ("0 nan 0", "0 0.5 0"), 2),
    ("limit_lower_above_upper.urdf", ('lower="1.5" upper="-1.5"', 'lower="-1.5" upper="1.5"'),
     2),
    ("mimic_cycle.urdf", ('    <mimic joint="j2"/>\n', ""), 3),
    ("cycle.urdf", ('<child link="a"/>', '<child link="d"/>'), 4),
    ("geometry_unknown.urdf", ('<capsule radius="0.1" length="1"/>',
                               '<cylinder radius="0.1" length="1"/>'), 1),
    ("revolute_without_limit.urdf", ('<axis xyz="0 0 1"/>\n',
                                     '<axis xyz="0 0 1"/>\n<limit lower="-1" upper="1"/>\n'),
     2),
]


@pytest.mark.parametrize("name, fix, n_links", REPAIRS, ids=[r[0] for r in REPAIRS])
def test_repaired_file_loads(name, fix, n_links):
    text = (CORPUS / name).read_text()
    assert fix[0] in text
    text = text.replace(fix[0], fix[1])
    if name == "cycle.urdf":  # j3 now ends in a new link d, so a is the root
        text = text.replace("</robot>", '  <link name="d"/>\n</robot>')
    robot = load_urdf(text)
    assert len(robot.link_names) == n_links


# -- size, depth, element count, arguments ---------------------------------------------
def no_hang(fn, seconds=10.0):
    t0 = time.perf_counter()
    with pytest.raises(URDFError) as exc:
        fn()
    assert time.perf_counter() - t0 < seconds  # a hang guard, not a speed test
    return str(exc.value)


def test_huge_file_is_refused_before_reading(tmp_path):
    path = tmp_path / "huge.urdf"
    with open(path, "wb") as fh:
        fh.seek(urdf_module.MAX_BYTES + 10)
        fh.write(b"\0")
    msg = no_hang(lambda: load_urdf(path))
    assert "huge.urdf" in msg and "larger than any robot description" in msg


def test_huge_string_is_refused():
    text = "<robot name='x'>" + " " * (urdf_module.MAX_BYTES + 1) + "</robot>"
    assert "limit" in no_hang(lambda: load_urdf(text))


def test_too_many_elements():
    links = "".join(f"<link name='l{i}'/>" for i in range(urdf_module.MAX_ELEMENTS + 1))
    assert "elements" in no_hang(lambda: load_urdf(f"<robot name='x'>{links}</robot>"))


def test_deep_nesting():
    text = "<robot name='x'>" + "<a>" * 10_000 + "</a>" * 10_000 + "</robot>"
    assert "nested more than" in no_hang(lambda: load_urdf(text))


@pytest.mark.parametrize("arg, phrase", [
    (42, "expected a file path or URDF text, got int"),
    (None, "got NoneType"),
    ("no/such/robot.urdf", "no/such/robot.urdf: cannot read the file"),
])
def test_bad_arguments(arg, phrase):
    with pytest.raises(URDFError, match=phrase):
        load_urdf(arg)


def test_directory_path(tmp_path):
    with pytest.raises(URDFError, match="cannot read the file"):
        load_urdf(tmp_path)


# -- URDF's defaults ---------------------------------------------------------------------
DEFAULTS = """<robot name="defaults">
  <link name="a"/> <link name="b"/> <link name="c"/> <link name="d"/>
  <gazebo reference="a"><material>Gazebo/Red</material></gazebo>
  <transmission name="t"><type>x</type></transmission>
  <joint name="no_origin_no_axis" type="continuous">
    <parent link="a"/> <child link="b"/>
    <dynamics damping="1"/> <limit effort="5" velocity="2"/>
  </joint>
  <joint name="only_xyz" type="prismatic">
    <parent link="b"/> <child link="c"/> <origin xyz="1 2 3"/> <axis xyz="0 2 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="only_rpy" type="fixed">
    <parent link="c"/> <child link="d"/> <origin rpy="0 0 1.5707963267948966"/>
    <axis xyz="0 0 0"/>
  </joint>
</robot>"""


def test_urdf_defaults():
    robot = load_urdf(DEFAULTS)
    j1, j2, j3 = (robot.joint(n) for n in ("no_origin_no_axis", "only_xyz", "only_rpy"))
    np.testing.assert_array_equal(j1.origin, np.eye(4))
    np.testing.assert_array_equal(j1.axis, [1, 0, 0])
    np.testing.assert_array_equal(j2.axis, [0, 1, 0])
    np.testing.assert_array_equal(j2.origin[:3, :3], np.eye(3))
    np.testing.assert_array_equal(j2.origin[:3, 3], [1, 2, 3])
    np.testing.assert_allclose(j3.origin[:3, :3], [[0, -1, 0], [1, 0, 0], [0, 0, 1]],
                               atol=1e-15)
    np.testing.assert_array_equal(robot.limits, [[-np.inf, np.inf], [0, 1]])
    T = robot.fk([np.pi / 2, 0.5])
    # about x by 90° then 1, 2, 3 + 0.5 along y: (1, 2.5, 3) -> (1, -3, 2.5)
    np.testing.assert_allclose(T[:3, 3], [1, -3, 2.5], atol=1e-15)
