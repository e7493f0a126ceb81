"""Typed, field-naming access to a layout YAML document (used by building_layout)."""
from __future__ import annotations

import math

HEADER_KEYS = ("name", "schema", "units", "space_boundaries", "placement", "storey", "defaults",
               "floor_slab", "ceiling_slab", "points", "walls", "rooms", "doors", "steps", "ramps")
# a multi-storey layout: these at the top, the plan of each storey under storeys[i]
MULTI_KEYS = ("name", "schema", "units", "space_boundaries", "placement", "defaults", "points",
              "storeys", "stairs")
STOREY_KEYS = ("name", "elevation", "floor_slab", "ceiling_slab", "walls", "rooms", "doors", "steps", "ramps")
DEFAULTS = {"wall_height": 2.9, "wall_thickness": 0.15, "exterior_thickness": 0.3,
            "door_width": 0.9, "door_height": 2.1}
SCHEMAS = ("IFC4", "IFC2X3")
UNITS = ("m", "mm")


class LayoutError(ValueError):
    """An invalid layout; ``str()`` names the file and the field."""

    def __init__(self, source: str, field: str, message: str):
        self.source, self.field, self.message = source, field, message
        super().__init__(f"layout {source}: {field + ': ' if field else ''}{message}")


class Reader:
    """Reads fields of the YAML tree; every error names the offending field."""

    def __init__(self, source: str, data, allow_invalid: bool = False):
        self.source = source
        self.allow_zero = allow_invalid
        if not isinstance(data, dict):
            raise self.error("", "the document must be a mapping")
        self.data = data
        self.defaults = dict(DEFAULTS)
        self.points: dict[str, tuple[float, float]] = {}
        self.prefix = ""  # "storeys[i]." in a storey's reader

    def error(self, field: str, message: str) -> LayoutError:
        return LayoutError(self.source, self.prefix + field if field else self.prefix.rstrip("."), message)

    def sub(self, data: dict, prefix: str) -> "Reader":
        """A reader of one storey's mapping: fields named ``<prefix><field>``, sharing the
        defaults and points of the whole layout."""
        r = Reader(self.source, data, self.allow_zero)
        r.defaults, r.points, r.prefix = self.defaults, self.points, prefix
        return r

    # --- scalars -------------------------------------------------------------------------
    def number(self, d: dict, key: str, f: str, default=None, lo=None, lo_open=False, hi=None) -> float:
        fld = f"{f}.{key}" if f else key
        v = d.get(key, default)
        if v is None:
            raise self.error(fld, "missing (a number is required)")
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise self.error(fld, f"expected a number, got {v!r}")
        v = float(v)
        if lo is not None and (v < lo or (lo_open and v == lo)):
            raise self.error(fld, f"{v:g} must be {'>' if lo_open else '>='} {lo:g}")
        if hi is not None and v > hi:
            raise self.error(fld, f"{v:g} must be <= {hi:g}")
        return v

    def string(self, d: dict, key: str, f: str, default=None) -> str:
        fld = f"{f}.{key}" if f else key
        v = d.get(key, default)
        if v is None:
            raise self.error(fld, "missing (a string is required)")
        return self.to_str(v, fld)

    def to_str(self, v, fld: str) -> str:
        if isinstance(v, bool) or not isinstance(v, (str, int, float)) or str(v) == "":
            raise self.error(fld, f"expected a non-empty string, got {v!r}")
        return str(v)

    def boolean(self, d: dict, key: str, f: str, default: bool) -> bool:
        v = d.get(key, default)
        if not isinstance(v, bool):
            raise self.error(f"{f}.{key}" if f else key, f"expected true or false, got {v!r}")
        return v

    def choice(self, d: dict, key: str, choices, default) -> str:
        v = d.get(key, default)
        if v not in choices:
            raise self.error(key, f"{v!r} is not one of {', '.join(choices)}")
        return v

    # --- structure -----------------------------------------------------------------------
    def mapping(self, d: dict, key: str, f: str = "") -> dict:
        v = d.get(key, {})
        if not isinstance(v, dict):
            raise self.error(f"{f}.{key}" if f else key, "expected a mapping")
        return v

    def list(self, d: dict, key: str, f: str, default=()):
        v = d.get(key, default)
        if v is None and default is None:
            return None
        if not isinstance(v, (list, tuple)):
            raise self.error(f"{f}.{key}" if f else key, "expected a list")
        return v

    def items(self, key: str, required: bool = False):
        seq = self.list(self.data, key, "")
        if required and not seq:
            raise self.error(key, "at least one entry is required")
        for i, item in enumerate(seq):
            if not isinstance(item, dict):
                raise self.error(f"{key}[{i}]", "expected a mapping")
            yield i, item

    def done(self, d: dict, f: str, allowed=None) -> None:
        known = {"walls": ("id", "from", "to", "thickness", "height", "external"),
                 "rooms": ("name", "long_name", "corners", "floor"),
                 "doors": ("id", "wall", "at", "width", "height", "connects", "leaf")}
        allowed = allowed or known[f.split("[")[0]]
        for k in d:
            if k not in allowed:
                raise self.error(f"{f}.{k}", f"unknown key (expected one of: {', '.join(allowed)})")

    def point(self, d: dict, key: str, f: str) -> tuple[float, float]:
        if key not in d:
            raise self.error(f"{f}.{key}", "missing (a point [x, y] or a name from points)")
        return self.to_point(d[key], f"{f}.{key}")

    def to_point(self, v, fld: str) -> tuple[float, float]:
        if isinstance(v, str):
            if v not in self.points:
                raise self.error(fld, f"no point '{v}' in points")
            return self.points[v]
        if (not isinstance(v, (list, tuple)) or len(v) != 2
                or not all(isinstance(c, (int, float)) and not isinstance(c, bool) and math.isfinite(c) for c in v)):
            raise self.error(fld, f"expected [x, y] or a point name, got {v!r}")
        return (float(v[0]), float(v[1]))

    # --- the header ----------------------------------------------------------------------
    def header(self, default_name: str, multi: bool = False) -> dict:
        d = self.data
        keys = MULTI_KEYS if multi else HEADER_KEYS
        for k in d:
            if k not in keys:
                hint = " (a layout with storeys gives them per storey)" if multi and k in HEADER_KEYS else ""
                raise self.error(k, f"unknown key{hint} (expected one of: {', '.join(keys)})")
        out = {"name": self.string(d, "name", "", default_name),
               "schema": self.choice(d, "schema", SCHEMAS, "IFC4"),
               "units": self.choice(d, "units", UNITS, "m"),
               "space_boundaries": self.boolean(d, "space_boundaries", "", False)}
        pl = self.mapping(d, "placement")
        self.done(pl, "placement", ("rotation_deg", "translation"))
        out["rotation_deg"] = self.number(pl, "rotation_deg", "placement", 0.0)
        t = self.list(pl, "translation", "placement", [0.0, 0.0, 0.0])
        if len(t) not in (2, 3) or not all(isinstance(c, (int, float)) and not isinstance(c, bool) for c in t):
            raise self.error("placement.translation", f"expected [x, y] or [x, y, z], got {t!r}")
        out["translation"] = tuple(float(c) for c in (list(t) + [0.0])[:3])
        if not multi:
            st = self.mapping(d, "storey")
            self.done(st, "storey", ("name", "elevation"))
            out["storey_name"] = self.string(st, "name", "storey", "Ground floor")
            out["elevation"] = self.number(st, "elevation", "storey", 0.0)
        df = self.mapping(d, "defaults")
        self.done(df, "defaults", tuple(DEFAULTS))
        for k in DEFAULTS:
            self.defaults[k] = self.number(df, k, "defaults", DEFAULTS[k], lo=0.0, lo_open=True)
        for k, v in self.mapping(d, "points").items():
            self.points[str(k)] = self.to_point(v, f"points.{k}")
        if multi:
            out["storey_name"], out["elevation"] = "", 0.0
            out["floor_thickness"] = out["ceiling_thickness"] = 0.0
            out["slab_outline"] = None
            return out
        out.update(self.slabs())
        return out

    def storey(self, default_name: str) -> dict:
        """A storey's own header (in a storey's reader): name, elevation, slabs."""
        d = self.data
        for k in d:
            if k not in STOREY_KEYS:
                raise self.error(k, f"unknown key (expected one of: {', '.join(STOREY_KEYS)})")
        out = {"storey_name": self.string(d, "name", "", default_name),
               "elevation": self.number(d, "elevation", "", None)}
        out.update(self.slabs())
        return out

    def slabs(self) -> dict:
        out = {}
        out["floor_thickness"], out["slab_outline"] = self._slab("floor_slab", True)
        out["ceiling_thickness"], _ = self._slab("ceiling_slab", False)
        return out

    def _slab(self, key: str, with_outline: bool):
        v = self.data.get(key, {})
        if v is False:
            return 0.0, None
        if not isinstance(v, dict):
            raise self.error(key, "expected a mapping or false")
        self.done(v, key, ("thickness", "outline") if with_outline else ("thickness",))
        thick = self.number(v, "thickness", key, 0.25, lo=0.0, lo_open=True)
        outline = None
        if "outline" in v:
            outline = [self.to_point(p, f"{key}.outline[{i}]") for i, p in enumerate(self.list(v, "outline", key))]
            if len(outline) < 3:
                raise self.error(f"{key}.outline", "needs at least 3 points")
        return thick, outline
