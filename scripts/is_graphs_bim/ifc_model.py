"""Opening an IFC file safely: input checks, schema, units, storeys, diagnostics.

Everything that can go wrong with the input is reported as a `ConversionError` (fatal) or through
`Diagnostics.warn` (the conversion goes on); never as a Python traceback.
"""
import gc
import hashlib
import os
import re
import sys
from dataclasses import dataclass, field

import ifcopenshell
import ifcopenshell.util.element as uelement
import ifcopenshell.util.placement as uplacement
import ifcopenshell.util.unit as uunit

from . import integrity

PROG = "ifc_to_agraph"
_SI_PREFIXES = {"EXA", "PETA", "TERA", "GIGA", "MEGA", "KILO", "HECTO", "DECA", "DECI", "CENTI",
                "MILLI", "MICRO", "NANO", "PICO", "FEMTO", "ATTO"}


def entity_label(entity):
    """'IfcWall #123' for an entity, '' for None."""
    return "" if entity is None else f"{entity.is_a()} #{entity.id()}"


class ConversionError(Exception):
    """A fatal input problem; `entity` (optional) is the IFC entity it is about; `names_path`:
    the message already names the file's path (then the line does not repeat its name)."""

    def __init__(self, what, entity=None, names_path=False):
        super().__init__(what)
        self.what = what
        self.entity = entity
        self.names_path = names_path

    def line(self, file_name):
        where = f"{entity_label(self.entity)}: " if self.entity is not None else ""
        return f"{PROG}: error: {'' if self.names_path else file_name + ': '}{where}{self.what}"


@dataclass
class Diagnostics:
    """Collects warnings (for the JSON) and echoes them to stderr as they happen."""
    file_name: str
    echo: bool = True
    warnings: list = field(default_factory=list)

    def warn(self, what, entity=None):
        text = f"{entity_label(entity)}: {what}" if entity is not None else what
        guid = getattr(entity, "GlobalId", None) if entity is not None else None
        if guid:
            text += f" [GlobalId {guid}]"
        self.warnings.append(text)
        if self.echo:
            print(f"{PROG}: warning: {self.file_name}: {text}", file=sys.stderr)


@dataclass
class IfcModel:
    path: str
    file: object            # ifcopenshell.file
    sha256: str
    schema: str
    application: str
    length_unit_m: float     # metres per file length unit
    building_name: str


def _starts_with(head):
    """'; it starts with <its first line>' for text, '; it is binary data' otherwise."""
    line = head[:200].split(b"\n", 1)[0].strip()
    try:
        text = line.decode("utf-8")
    except UnicodeDecodeError:
        return "; it is binary data"
    if not text.isprintable():
        return "; it is binary data"
    return f"; it starts with {text[:60]!r}" if text else ""


def _check_bytes(path, data):
    head = data[:4096].lstrip(b"\xef\xbb\xbf \t\r\n")
    if head.startswith(b"PK\x03\x04"):
        raise ConversionError("is a ZIP archive (.ifczip?): unzip it first; only IFC-SPF text "
                              "(ISO-10303-21) files are read")
    if head.startswith(b"<"):
        raise ConversionError("is XML (ifcXML?): only IFC-SPF text (ISO-10303-21) files are read")
    if not head.startswith(b"ISO-10303-21;"):
        raise ConversionError("not an IFC file: it does not start with 'ISO-10303-21;' "
                              f"(an IFC-SPF STEP file is expected){_starts_with(head)}")
    if b"FILE_SCHEMA" not in head:
        raise ConversionError("not an IFC file: no FILE_SCHEMA in its header")
    tail = data[-256:].rstrip(b" \t\r\n\x00\x1a")
    if not tail.endswith(b"END-ISO-10303-21;"):
        raise ConversionError("truncated IFC file: it does not end with 'END-ISO-10303-21;' "
                              "(cut off while copying or exporting?)")
    if data.count(b"ENDSEC;") < 2:
        raise ConversionError("truncated or malformed IFC file: HEADER or DATA section not closed")


_FILE_SCHEMA = re.compile(rb"FILE_SCHEMA\s*\(\s*\(\s*'([^']*)'")
# Older IFC2x editions IfcOpenShell has no schema for; the walls, spaces, doors, openings and
# storeys the converter reads kept their names and attributes in IFC2X3, their successor.
_READ_AS_IFC2X3 = {"IFC2X", "IFC2X_FINAL", "IFC2X2", "IFC2X2_FINAL", "IFC2X2_ADD1"}
_SI_LENGTH = re.compile(rb"#(\d+)\s*=\s*IFCSIUNIT\s*\(\s*\*\s*,\s*\.LENGTHUNIT\.\s*,"
                        rb"\s*\.([A-Za-z_]+)\.\s*,", re.IGNORECASE)


def _unknown_prefixes(data):
    """[(step id, prefix)] of SI length units whose prefix IfcOpenShell would silently drop."""
    return [(int(m.group(1)), m.group(2).decode("ascii", "replace"))
            for m in _SI_LENGTH.finditer(data) if m.group(2).upper().decode() not in _SI_PREFIXES]


def _length_unit(f, diag):
    """Metres per file length unit, with warnings for missing or odd unit assignments."""
    assignments = f.by_type("IfcUnitAssignment")
    if not assignments:
        diag.warn("no IfcUnitAssignment in the file: assuming lengths are in metres")
        return 1.0, True
    length_units = [u for u in (assignments[0].Units or [])
                    if getattr(u, "UnitType", None) == "LENGTHUNIT"]
    if not length_units:
        diag.warn("no length unit in the IfcUnitAssignment: assuming metres")
        return 1.0, True
    unit = length_units[0]
    if unit.is_a("IfcSIUnit"):
        if unit.Name != "METRE":
            diag.warn(f"length unit is {unit.Name}, not METRE: assuming metres", unit)
            return 1.0, True
        if unit.Prefix is not None and unit.Prefix not in _SI_PREFIXES:
            diag.warn(f"unknown SI prefix {unit.Prefix!r} on the length unit: assuming metres", unit)
            return 1.0, True
    try:
        scale = float(uunit.calculate_unit_scale(f))
    except Exception as exc:  # odd conversion-based units
        diag.warn(f"cannot evaluate the length unit ({exc}): assuming metres", unit)
        return 1.0, True
    if not (scale > 0.0 and scale < 1e6):
        diag.warn(f"length unit scale {scale} is not usable: assuming metres", unit)
        return 1.0, True
    return scale, False


_INSTANCE = re.compile(rb"(?m)^([ \t]*#\d+[ \t]*=[ \t]*)([A-Za-z0-9_]+)[ \t]*\((.*)\)[ \t]*;[ \t]*$")


def _top_level_args(text):
    """The top-level arguments of a STEP instance's attribute list, as (start, end) spans."""
    spans, depth, start, i, n = [], 0, 0, 0, len(text)
    while i < n:
        c = text[i]
        if c == 0x27:  # a string: '' is an escaped quote
            i += 1
            while i < n and not (text[i] == 0x27 and (i + 1 >= n or text[i + 1] != 0x27)):
                i += 2 if text[i] == 0x27 else 1
        elif c == 0x28:
            depth += 1
        elif c == 0x29:
            depth -= 1
        elif c == 0x2C and depth == 0:
            spans.append((start, i))
            start = i + 1
        i += 1
    spans.append((start, n))
    return spans


def _underived_stars(data, schema):
    """`data` with every `*` (derived) that stands for an attribute the schema does not derive
    replaced by `$` (unset), and {entity: count}. Renga writes Name as `*`; IfcOpenShell then
    fails to build the geometry of every such product ("Type held at index 2 is 7Derived")."""
    try:
        decls = ifcopenshell.ifcopenshell_wrapper.schema_by_name(schema)
    except Exception:
        return data, {}
    fixed = {}

    def repl(m):
        args = m.group(3)
        if b"*" not in args:
            return m.group(0)
        try:
            decl = decls.declaration_by_name(m.group(2).decode("ascii"))
            derived = decl.derived()
        except Exception:
            return m.group(0)
        spans = _top_level_args(args)
        out, last = [], 0
        for k, (a, b) in enumerate(spans):
            if args[a:b].strip() == b"*" and k < len(derived) and not derived[k]:
                out += [args[last:a], b"$"]
                last = b
                fixed[decl.name()] = fixed.get(decl.name(), 0) + 1
        if not out:
            return m.group(0)
        return m.group(1) + m.group(2) + b"(" + b"".join(out) + args[last:] + b");"

    return _INSTANCE.sub(repl, data), fixed


def _report_dangling(report, diag, allow_dangling):
    """An error when dangling references touch what the converter reads (walls, spaces, storeys,
    doors, ... their placements and geometry, their relations), else a warning."""
    what = f"the file looks truncated or damaged: {report.describe()}"
    if report.touches_model and not allow_dangling:
        raise ConversionError(f"{what}. They touch walls, spaces, storeys, doors or their "
                              "placements, geometry or relations, which IfcOpenShell would read "
                              "as unset: re-export the file (--allow-dangling converts anyway)")
    if report.touches_model:
        diag.warn(f"{what}. Converted anyway (--allow-dangling): the missing placements, geometry "
                  "or relations are read as unset; check the result")
    else:
        diag.warn(f"{what}. None touches walls, spaces, storeys, doors or their placements or "
                  "geometry: converted")


def _first_unread(data, parsed, schema):
    """'; the first instance not read: #N=TYPE, after #P=TYPE' (IfcOpenShell stops reading at an
    instance it cannot parse: unknown type, bad syntax)."""
    try:
        decls = ifcopenshell.ifcopenshell_wrapper.schema_by_name(schema)
    except Exception:
        decls = None
    previous = None
    for sid, kind in integrity.instances_in_order(data):
        if sid not in parsed:
            why = ""
            if decls is not None:
                try:
                    decls.declaration_by_name(kind)
                except Exception:
                    why = f" (no entity {kind} in {schema}: an unknown entity type)"
            after = f", after #{previous[0]}={previous[1]}" if previous else ""
            return f"; the first instance not read: #{sid}={kind}{why}{after}"
        previous = (sid, kind)
    return ""


def _quietly(read):
    """read() with Python's unraisable-exception hook silenced until what a failed read built is
    gone: IfcOpenShell destroys a file it gave up on half-built, and its destructor's KeyError
    was printed as a stray `Exception ignored in ...` after the real error."""
    hook = sys.unraisablehook
    sys.unraisablehook = lambda unraisable: None
    try:
        try:
            return read()
        except Exception as exc:
            failure = str(exc).strip() or type(exc).__name__
        gc.collect()  # the traceback (and the half-built file) released above: freed now
        raise RuntimeError(failure)
    finally:
        sys.unraisablehook = hook


def open_model(path, diag, allow_dangling=False):
    """Reads and checks `path`; returns (IfcModel, forced_unit) or raises ConversionError.
    allow_dangling: references to entities the file lacks are a warning, not an error."""
    try:
        data = integrity.read_bytes(path)
    except integrity.PathError as exc:
        raise ConversionError(str(exc), names_path=True) from None
    _check_bytes(path, data)
    defined, missing = integrity.defined_and_missing(data)
    if missing:
        _report_dangling(integrity.dangling(data), diag, allow_dangling)
    header = _FILE_SCHEMA.search(data[:65536])
    declared = header.group(1).decode("ascii", "replace").strip().upper() if header else ""
    read_as = "IFC2X3" if declared in _READ_AS_IFC2X3 else declared
    text, stars = _underived_stars(data, read_as) if b"*" in data else (data, {})
    if not stars:
        text = data  # nothing replaced: IfcOpenShell reads the file itself
    try:
        if declared in _READ_AS_IFC2X3:
            text = text.replace(header.group(0), b"FILE_SCHEMA(('IFC2X3'", 1)
            diag.warn(f"schema {declared} (an older IFC2x edition IfcOpenShell has no schema for) "
                      "read as IFC2X3, its successor: check the conversion's counts")
        if text is data:
            f = _quietly(lambda: ifcopenshell.open(path))
        else:
            f = _quietly(lambda: ifcopenshell.file.from_string(text.decode("utf-8", "replace")))
        if stars:
            what = ", ".join(f"{name} {count}" for name, count in sorted(stars.items()))
            diag.warn(f"{sum(stars.values())} attributes written '*' (derived) where the schema "
                      f"has a value, read as unset ({what})")
    except Exception as exc:
        why = str(exc).strip() or type(exc).__name__
        if declared and "schema" in why.lower():
            why += (f" (the file declares {declared}; IfcOpenShell {ifcopenshell.version} reads "
                    "IFC2X3, IFC4 and IFC4X3; older IFC2x editions are read as IFC2X3)")
        raise ConversionError(f"IfcOpenShell cannot parse it: {why}") from None
    try:
        parsed = set(f.wrapped_data.entity_names())
    except Exception:
        parsed = None
    if parsed is not None and len(parsed) < defined:
        raise ConversionError(f"damaged or truncated IFC file: only {len(parsed)} of "
                              f"{defined} entity instances could be read (the DATA section "
                              f"is cut or malformed){_first_unread(data, parsed, f.schema)}")
    if len(f.by_type("IfcProject")) == 0:
        raise ConversionError("no IfcProject: not a complete IFC model (truncated?)")
    bad_prefix = _unknown_prefixes(data)
    if bad_prefix:
        sid, prefix = bad_prefix[0]
        diag.warn(f"unknown SI prefix .{prefix}. on the length unit: ignored, assuming metres",
                  f.by_id(sid))
        scale, forced = 1.0, True
    else:
        scale, forced = _length_unit(f, diag)
    apps = sorted(f.by_type("IfcApplication"), key=lambda a: a.id())
    app = apps[0].ApplicationFullName or "" if apps else ""
    buildings = sorted(f.by_type("IfcBuilding"), key=lambda b: b.id())
    stem = os.path.splitext(os.path.basename(path))[0]
    name = (buildings[0].Name or buildings[0].LongName or "") if buildings else ""
    schema = f"{declared} (read as {f.schema})" if declared in _READ_AS_IFC2X3 else f.schema
    model = IfcModel(path=path, file=f, sha256=hashlib.sha256(data).hexdigest(), schema=schema,
                     application=app, length_unit_m=scale, building_name=name or stem)
    return model, forced


def placement_z(product, scale):
    """World z (metres) of a product's local placement origin, None if it has none."""
    if getattr(product, "ObjectPlacement", None) is None:
        return None
    try:
        return float(uplacement.get_local_placement(product.ObjectPlacement)[2][3]) * scale
    except Exception:
        return None


def storey_of(element):
    """The IfcBuildingStorey an element belongs to (containment, aggregation, voids, fills)."""
    seen = 0
    current = element
    while current is not None and seen < 12:
        if current.is_a("IfcBuildingStorey"):
            return current
        seen += 1
        nxt = uelement.get_container(current) or uelement.get_aggregate(current)
        if nxt is None and current.is_a("IfcOpeningElement"):
            rels = getattr(current, "VoidsElements", None) or ()
            nxt = rels[0].RelatingBuildingElement if rels else None
        if nxt is None:
            rels = getattr(current, "FillsVoids", None) or ()
            nxt = rels[0].RelatingOpeningElement if rels else None
        current = nxt
    return None


def list_storeys(model, diag=None, shapes=None):
    """[(entity, elevation_m)] sorted by elevation then STEP id: the storey's placement, else its
    Elevation; a storey without Elevation takes its placement's z or, without a placement, the
    bottom of its spaces (shapes: {step id: mesh.Shape}), and a warning says so."""
    out = []
    spaces_of = {}
    if shapes is not None:
        for sp in model.file.by_type("IfcSpace"):
            st = storey_of(sp)
            if st is not None and sp.id() in shapes:
                spaces_of.setdefault(st.id(), []).append(float(shapes[sp.id()].verts[:, 2].min()))
    for s in model.file.by_type("IfcBuildingStorey"):
        z = placement_z(s, model.length_unit_m)
        if s.Elevation is None:
            bottoms = spaces_of.get(s.id(), [])
            if z is not None:
                what = f"taken from its placement (z = {z:.3f} m)"
            elif bottoms:
                z = min(bottoms)
                what = (f"no placement either: taken from the bottom of its {len(bottoms)} "
                        f"space(s) (z = {z:.3f} m)")
            else:
                z = 0.0
                what = "no placement and no spaces either: elevation 0 assumed"
            if diag is not None:
                diag.warn(f"storey without Elevation: {what}", s)
        elif z is None:
            z = float(s.Elevation) * model.length_unit_m
        out.append((s, z))
    out.sort(key=lambda se: (se[1], se[0].id()))
    return out


def wall_is_external(wall):
    """Pset_WallCommon.IsExternal (Pset_CurtainWallCommon for curtain walls) as a bool, None when
    absent."""
    psets = uelement.get_psets(wall)
    pset = "Pset_CurtainWallCommon" if wall.is_a("IfcCurtainWall") else "Pset_WallCommon"
    value = psets.get(pset, {}).get("IsExternal")
    return None if value is None else bool(value)
