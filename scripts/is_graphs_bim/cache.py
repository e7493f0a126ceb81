"""A conversion cache: DIR/<sha256 of the IFC bytes>-v<CONVERTER_VERSION>/<stem>.agraph.json.

A result appears complete only once its JSON is in place, and the JSON is moved in last, with an
atomic rename, from a temporary directory inside DIR: an interrupted conversion leaves a
`.tmp-*` directory behind, never a half-written result under its final name.
"""
import hashlib
import os
import shutil
import tempfile

from . import CONVERTER_VERSION


def cache_key(ifc_path):
    h = hashlib.sha256()
    with open(ifc_path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return f"{h.hexdigest()}-v{CONVERTER_VERSION}"


def lookup(cache_dir, ifc_path):
    """(final json path, hit?) for an IFC file."""
    stem = os.path.splitext(os.path.basename(ifc_path))[0]
    final_dir = os.path.join(os.path.abspath(cache_dir), cache_key(ifc_path))
    json_path = os.path.join(final_dir, stem + ".agraph.json")
    return json_path, os.path.isfile(json_path)


def store(cache_dir, ifc_path, write_into):
    """Runs write_into(out_prefix) in a temporary directory inside cache_dir, then moves the
    files into the cache entry (mesh first, JSON last). Returns the final JSON path."""
    json_path, _ = lookup(cache_dir, ifc_path)
    final_dir = os.path.dirname(json_path)
    stem = os.path.basename(json_path)[: -len(".agraph.json")]
    os.makedirs(cache_dir, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix=".tmp-", dir=cache_dir)
    try:
        write_into(os.path.join(tmp, stem))
        os.makedirs(final_dir, exist_ok=True)
        names = sorted(os.listdir(tmp), key=lambda n: n.endswith(".agraph.json"))
        for name in names:
            os.replace(os.path.join(tmp, name), os.path.join(final_dir, name))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return json_path
