"""BCF 2.1 (buildingSMART BCF-XML, release_2_1 schemas in test/data/bcf21) for wall deviations.

One topic per wall not AS_PLANNED (MOVED, NOT_BUILT, EXTRA) and per door or opening CLOSED (an
item with "element" "door" / "opening", its start-end the opening's span): markup.bcf (the topic,
its IFC GUID in the description), viewpoint.bcfv (a perspective camera 1.6 m high looking at the
wall or door from the side the robot walked, it selected and coloured by its IFC GlobalId) and
snapshot.png. Written against the XSDs with the standard library (ElementTree); topic and
viewpoint GUIDs are UUID5 of the wall's key, so a rerun gives the same topics (BCF managers then
update instead of duplicating). docs/deviations.md says why not a BCF library.
"""
import datetime
import math
import os
import shutil
import tempfile
import uuid
import xml.etree.ElementTree as ET
import zipfile

NAMESPACE = uuid.UUID("5b0c8f3e-6a1d-4c2e-9f57-2d1e0a7b9c41")  # is_graphs deviation topics
COLOURS = {"MOVED": "FF7F0E", "NOT_BUILT": "D62AD6", "EXTRA": "1F5FFF", "CLOSED": "D62728"}
AUTHOR = "is_graphs"


def built_segment(w):
    """Where a MOVED wall's mid-line was built: moved by offset along its normal, turned about
    its middle by angle."""
    (x0, y0), (x1, y1) = w["start"], w["end"]
    nx, ny = w.get("normal", [0.0, 0.0])
    mx, my = 0.5 * (x0 + x1) + w["offset_m"] * nx, 0.5 * (y0 + y1) + w["offset_m"] * ny
    a = math.radians(w["angle_deg"])
    c, s = math.cos(a), math.sin(a)
    hx, hy = 0.5 * (x1 - x0), 0.5 * (y1 - y0)
    rx, ry = c * hx - s * hy, s * hx + c * hy
    return mx - rx, my - ry, mx + rx, my + ry


def is_door(w):
    return w.get("element", "wall") != "wall"


def topic_title(w):
    if is_door(w):
        return "%s %s closed (open in the plan)" % (
            w["element"].capitalize(), w["name"] or w["guid"] or "#%d" % w["doorway_id"])
    name = w["name"] or (w["guid"] or ("wall %d" % w["wall_id"] if w["wall_id"] >= 0 else ""))
    if w["status"] == "MOVED":
        return "Wall %s built %+.0f cm / %+.1f° off the plan" % (
            name, 100 * w["offset_m"], w["angle_deg"])
    if w["status"] == "NOT_BUILT":
        return "Wall %s not built" % name
    return "Wall not in the plan (%.1f m at %.1f, %.1f)" % (
        w["length_m"], 0.5 * (w["start"][0] + w["end"][0]), 0.5 * (w["start"][1] + w["end"][1]))


def description(w):
    if is_door(w):
        ident = "IFC GlobalId %s" % w["guid"] if w["guid"] else (
            "A-Graph doorway %d (the IFC element has no GlobalId)" % w["doorway_id"])
        return ("%s: a %.2f m %s at (%.2f, %.2f) in the model's coordinates is closed: %d of "
                "the robot's viewpoints facing it saw a wall-height surface across it and none "
                "saw through it; never walked through." % (
                    ident, w["width_m"], w["element"], w["position"][0], w["position"][1],
                    w["blocked_views"]))
    ident = "IFC GlobalId %s" % w["guid"] if w["guid"] else (
        "A-Graph wall %d (the IFC wall has no GlobalId)" % w["wall_id"] if w["wall_id"] >= 0
        else "no IFC element")
    if w["status"] == "MOVED":
        return ("%s: built %.3f m (σ %.3f m) along its first face's normal and turned %.2f° "
                "(anticlockwise) from the plan. Measured by the robot's LiDAR (is_graphs)." % (
                    ident, w["offset_m"], w["sigma_m"], w["angle_deg"]))
    if w["status"] == "NOT_BUILT":
        return ("%s: not built: %d of the robot's sight lines or steps went through where it "
                "should stand." % (ident, w["rays_through"]))
    return ("A wall-height surface the plan does not have: %.2f m long, from (%.2f, %.2f) to "
            "(%.2f, %.2f) in the model's coordinates, %.1f m high as seen." % (
                w["length_m"], w["start"][0], w["start"][1], w["end"][0], w["end"][1],
                w.get("height_m", 0.0)))


def _sub(parent, tag, text=None, **attrs):
    e = ET.SubElement(parent, tag, {k: str(v) for k, v in attrs.items()})
    if text is not None:
        e.text = str(text)
    return e


def _xyz(parent, tag, x, y, z):
    e = _sub(parent, tag)
    _sub(e, "X", "%.4f" % x)
    _sub(e, "Y", "%.4f" % y)
    _sub(e, "Z", "%.4f" % z)


def _write(root, path):
    ET.ElementTree(root).write(path, encoding="UTF-8", xml_declaration=True)


def camera(w, path):
    """Eye 1.6 m high, 4 m off the wall's middle on the side nearest the robot's path."""
    (x0, y0), (x1, y1) = w["start"], w["end"]
    mx, my = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    length = math.hypot(x1 - x0, y1 - y0) or 1.0
    nx, ny = (y1 - y0) / length, -(x1 - x0) / length
    if path:
        nearest = min(path, key=lambda p: (p[1] - mx) ** 2 + (p[2] - my) ** 2)
        if (nearest[1] - mx) * nx + (nearest[2] - my) * ny < 0:
            nx, ny = -nx, -ny
    distance = max(4.0, 0.9 * length)
    return (mx + distance * nx, my + distance * ny, 1.6), (-nx, -ny, 0.0)


def viewpoint(w, path, guid, out):
    root = ET.Element("VisualizationInfo", Guid=guid)
    if w["guid"]:
        comps = _sub(root, "Components")
        sel = _sub(comps, "Selection")
        _sub(sel, "Component", IfcGuid=w["guid"])
        _sub(comps, "Visibility", DefaultVisibility="true")
        colour = _sub(_sub(comps, "Coloring"), "Color", Color=COLOURS[w["status"]])
        _sub(colour, "Component", IfcGuid=w["guid"])
    cam = _sub(root, "PerspectiveCamera")
    eye, direction = camera(w, path)
    _xyz(cam, "CameraViewPoint", *eye)
    _xyz(cam, "CameraDirection", *direction)
    _xyz(cam, "CameraUpVector", 0.0, 0.0, 1.0)
    _sub(cam, "FieldOfView", "60.0")
    lines = _sub(root, "Lines")  # where it stands in the plan (and was built, MOVED)
    segments = [tuple(w["start"]) + tuple(w["end"])]
    if w["status"] == "MOVED":
        segments.append(built_segment(w))
    for x0, y0, x1, y1 in segments:
        line = _sub(lines, "Line")
        _xyz(line, "StartPoint", x0, y0, 1.0)
        _xyz(line, "EndPoint", x1, y1, 1.0)
    _write(root, out)


def markup(w, topic, view, index, date, building, out):
    root = ET.Element("Markup")
    if building:
        header = _sub(root, "Header")
        f = _sub(header, "File", isExternal="true")
        _sub(f, "Filename", building)
    t = _sub(root, "Topic", Guid=topic, TopicType="Issue", TopicStatus="Open")
    _sub(t, "Title", topic_title(w))
    _sub(t, "Priority", "Normal")
    _sub(t, "Index", index)
    _sub(t, "Labels", "As-built deviation")
    _sub(t, "Labels", w["status"])
    _sub(t, "CreationDate", date)
    _sub(t, "CreationAuthor", AUTHOR)
    _sub(t, "Description", description(w))
    vp = _sub(root, "Viewpoints", Guid=view)
    _sub(vp, "Viewpoint", "viewpoint.bcfv")
    _sub(vp, "Snapshot", "snapshot.png")
    _write(root, out)


def key(w):
    if is_door(w):  # its own namespace: a door never shares a topic with a wall
        return "door:" + (w["guid"] or "#%d" % w["doorway_id"])
    if w["guid"]:
        return w["guid"]
    if w["wall_id"] >= 0:
        return "wall#%d" % w["wall_id"]
    return "extra:%.2f,%.2f,%.2f,%.2f" % (w["start"][0], w["start"][1], w["end"][0], w["end"][1])


def write_bcf(walls, path, building, out, snapshot):
    """Writes the BCF zip `out` (through a temporary file); snapshot(w, png_path) draws one."""
    date = datetime.datetime.now(datetime.timezone.utc).replace(microsecond=0).isoformat()
    work = tempfile.mkdtemp(prefix="bcf_")
    try:
        version = ET.Element("Version", VersionId="2.1")
        _sub(version, "DetailedVersion", "2.1")
        _write(version, os.path.join(work, "bcf.version"))
        index = 0
        for w in walls:
            if w["status"] not in COLOURS:
                continue
            index += 1
            topic = str(uuid.uuid5(NAMESPACE, "topic:" + key(w)))
            view = str(uuid.uuid5(NAMESPACE, "viewpoint:" + key(w)))
            folder = os.path.join(work, topic)
            os.makedirs(folder)
            markup(w, topic, view, index, date, building, os.path.join(folder, "markup.bcf"))
            viewpoint(w, path, view, os.path.join(folder, "viewpoint.bcfv"))
            snapshot(w, os.path.join(folder, "snapshot.png"))
        tmp = out + ".tmp"
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
            for base, _, files in sorted(os.walk(work)):
                for name in sorted(files):
                    full = os.path.join(base, name)
                    z.write(full, os.path.relpath(full, work))
        os.replace(tmp, out)
    finally:
        shutil.rmtree(work, ignore_errors=True)
