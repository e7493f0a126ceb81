"""A damaged IFC is named as damaged: references to entities the file lacks (a file cut short and
resealed), instances IfcOpenShell cannot read. Real files, damaged copies made here."""
import glob
import json
import os
import re
import sys

import pytest

from conftest import REPO, SHARED_BIM, fails

OFFICE = os.path.join(REPO, "bim", "office.ifc")
LINE = re.compile(rb"(?m)^#(\d+)=([A-Z0-9_]+)\((.*)\);$")


def converted(proc):
    assert proc.returncode == 0, proc.stderr
    with open(proc.stdout.strip().splitlines()[-1], encoding="utf-8") as fh:
        return json.load(fh)


def resealed_half(src, dst):
    """The first half of src's lines, with its end markers put back (as a careless tool does)."""
    with open(src, "rb") as fh:
        lines = fh.read().splitlines(keepends=True)
    dst.write_bytes(b"".join(lines[: len(lines) // 2]) + b"ENDSEC;\nEND-ISO-10303-21;\n")
    return dst


def without(src, dst, sid):
    """src without the instance #sid."""
    with open(src, "rb") as fh:
        data = fh.read()
    cut = re.sub(rb"(?m)^#%d=.*\n" % sid, b"", data)
    assert len(cut) < len(data)
    dst.write_bytes(cut)
    return dst


def references(data):
    """{id: (TYPE, ids it references)} of a file written one instance per line, no '#' in
    strings (the project's own files)."""
    return {int(m.group(1)): (m.group(2).decode(), {int(n) for n in re.findall(rb"#(\d+)",
                                                                               m.group(3))})
            for m in LINE.finditer(data)}


def assert_examples_true(line, data):
    """Each '#A=TYPE references #B which is not in the file' in the message is so in `data`."""
    inst = references(data)
    examples = re.findall(r"#(\d+)=([A-Z0-9_]+) references #(\d+) which is not in the file", line)
    assert examples, line
    for owner, kind, target in examples:
        assert inst[int(owner)][0] == kind and int(target) in inst[int(owner)][1], line
        assert int(target) not in inst, line


def test_office_cut_in_half_is_an_error_naming_dangling_references(run_converter, tmp_path):
    half = resealed_half(OFFICE, tmp_path / "half.ifc")
    data = half.read_bytes()
    inst = references(data)
    missing = {r for _, refs in inst.values() for r in refs} - set(inst)
    assert len(missing) > 10
    line = fails(run_converter([half, "-o", tmp_path / "h", "--quiet"]), "half.ifc",
                 "the file looks truncated or damaged",
                 f"{len(missing)} referenced entities are not in it (dangling references",
                 "and ", "more", "--allow-dangling")
    assert_examples_true(line, data)
    assert not (tmp_path / "h.agraph.json").exists()
    # The cache (agraph_node's way) says the same and keeps nothing.
    fails(run_converter([half, "--cache-dir", tmp_path / "c", "--quiet"]),
          f"{len(missing)} referenced entities are not in it")
    assert not glob.glob(str(tmp_path / "c" / "*" / "*.agraph.json"))


def test_allow_dangling_converts_with_a_warning(run_converter, tmp_path):
    half = resealed_half(OFFICE, tmp_path / "half.ifc")
    proc = run_converter([half, "-o", tmp_path / "h", "--quiet", "--allow-dangling"])
    g = converted(proc)
    hits = [w for w in g["warnings"] if "dangling references" in w]
    assert len(hits) == 1 and "Converted anyway (--allow-dangling)" in hits[0], g["warnings"]
    assert "the file looks truncated or damaged" in hits[0] and hits[0] in proc.stderr


def test_a_wall_without_its_placement_is_named(run_converter, tmp_path):
    data = open(OFFICE, "rb").read()
    wall, (_, refs) = next((i, v) for i, v in references(data).items() if v[0] == "IFCWALL")
    placement = min(r for r in refs if references(data)[r][0] == "IFCLOCALPLACEMENT")
    damaged = without(OFFICE, tmp_path / "office.ifc", placement)
    line = fails(run_converter([damaged, "-o", tmp_path / "h", "--quiet"]),
                 f"#{wall}=IFCWALL references #{placement} which is not in the file",
                 "1 referenced entity is not in it (dangling references, from ", "They touch walls")
    assert_examples_true(line, damaged.read_bytes())


def test_dangling_reference_outside_the_model_is_a_warning(run_converter, tmp_path):
    """IfcApplication's organisation lost: nothing the converter reads; converted as before."""
    data = open(OFFICE, "rb").read()
    org = next(i for i, v in references(data).items() if v[0] == "IFCORGANIZATION")
    damaged = without(OFFICE, tmp_path / "office.ifc", org)
    g = converted(run_converter([damaged, "-o", tmp_path / "d", "--quiet"]))
    intact = converted(run_converter([OFFICE, "-o", tmp_path / "i", "--quiet"]))
    hits = [w for w in g["warnings"] if "dangling references" in w]
    assert len(hits) == 1 and "None touches walls" in hits[0], g["warnings"]
    assert f"#{org} which is not in the file" in hits[0]
    assert g["warnings"] == intact["warnings"] + hits
    for key in ("rooms", "walls", "wall_surfaces", "doorways"):
        assert g[key] == intact[key], key


def test_hash_in_a_string_is_no_reference(run_converter, tmp_path):
    data = open(OFFICE, "rb").read()
    named = data.replace(b"'office'", b"'office #99999=X, #88888 ''#77777'''", 1)
    assert named != data
    (tmp_path / "office.ifc").write_bytes(named)
    proc = run_converter([tmp_path / "office.ifc", "-o", tmp_path / "h", "--quiet"])
    converted(proc)
    assert "dangling" not in proc.stderr


def test_real_file_cut_in_half_is_an_error(run_converter, tmp_path):
    src = os.path.join(SHARED_BIM, "AC20-FZK-Haus.ifc")
    if not os.path.isfile(src):
        pytest.skip(f"../shared/bim not found: {src} is absent")
    half = resealed_half(src, tmp_path / "fzk.ifc")
    line = fails(run_converter([half, "-o", tmp_path / "h", "--quiet"]), "fzk.ifc",
                 "the file looks truncated or damaged", "dangling references", "They touch walls")
    assert re.search(r"#\d+=IFC[A-Z]+ references #\d+ which is not in the file", line), line


def test_intact_files_have_no_dangling_reference_and_count_like_ifcopenshell():
    """No false alarm on any real file; the instance count matches IfcOpenShell's (it is the
    check that a file was read whole)."""
    import ifcopenshell
    sys.path.insert(0, os.path.join(REPO, "scripts"))
    from is_graphs_bim import integrity
    files = sorted(glob.glob(os.path.join(REPO, "bim", "*.ifc")) +
                   glob.glob(os.path.join(SHARED_BIM, "*.ifc")))
    assert len(files) >= 6
    for path in files:
        data = open(path, "rb").read()
        count, missing = integrity.defined_and_missing(data)
        assert missing == set(), path
        assert integrity.dangling(data) is None, path
        assert count == len(ifcopenshell.open(path).wrapped_data.entity_names()), path


def test_unknown_entity_type_is_named(run_converter, tmp_path):
    data = open(OFFICE, "rb").read()
    odd = data.replace(b"\n#10=", b"\n#999999=IFCFOOBAR(1,2);\n#10=", 1)
    assert odd != data
    (tmp_path / "odd.ifc").write_bytes(odd)
    fails(run_converter([tmp_path / "odd.ifc", "-o", tmp_path / "h"]), "odd.ifc",
          "damaged or truncated IFC file", "the first instance not read: #999999=IFCFOOBAR "
          "(no entity IFCFOOBAR in IFC4: an unknown entity type)")
