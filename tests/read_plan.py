# SPDX-License-Identifier: GPL-3.0-or-later
"""Independent reader for origamic's plan files: ezdxf for DXF, the standard library for SVG.

usage: /usr/bin/python3 read_plan.py PLAN.dxf PLAN.svg
prints JSON: {"insunits", "measurement", "dxf": {layer: [[x1, y1, x2, y2], ...]},
"svg": {layer: [...]}, "dxf_colours": {layer: aci}, "dxf_types": {layer: {entity type: count}},
"dxf_comments": [999 comment strings], "dxf_audit": [what ezdxf's audit fixed or found wrong], "svg_lines": {layer: [{"points": [[x, y], ...],
"dash": [numbers] or null}]}, "svg_title", "svg_desc", "svg_metadata" (its text)} with SVG converted
back to plan Y (up)."""
import json
import sys
import xml.etree.ElementTree as ET

import ezdxf
from ezdxf import comments


def dxf_segments(path):
    doc = ezdxf.readfile(path)
    layers = {}
    colours = {}
    types = {}
    for entity in doc.modelspace():
        kind = entity.dxftype()
        per_layer = types.setdefault(entity.dxf.layer, {})
        per_layer[kind] = per_layer.get(kind, 0) + 1
        if kind == "LWPOLYLINE":
            points = [(p[0], p[1]) for p in entity.get_points("xy")]
            closed = entity.closed
        elif kind == "POLYLINE":
            points = [(v.dxf.location[0], v.dxf.location[1]) for v in entity.vertices]
            closed = entity.is_closed
        elif kind == "LINE":
            points = [tuple(entity.dxf.start)[:2], tuple(entity.dxf.end)[:2]]
            closed = False
        else:
            raise SystemExit("unexpected entity " + kind)
        if closed:
            points.append(points[0])
        layer = entity.dxf.layer
        colours.setdefault(layer, set()).add(entity.dxf.color)
        layers.setdefault(layer, []).extend(
            [a[0], a[1], b[0], b[1]] for a, b in zip(points, points[1:]))
    header = doc.header
    return (layers, header.get("$INSUNITS"), header.get("$MEASUREMENT"), {k: sorted(v) for k, v in colours.items()},
            types, [tag.value for tag in comments.from_file(path)])


def svg_segments(path):
    root = ET.parse(path).getroot()
    ns = {"svg": "http://www.w3.org/2000/svg"}
    view = [float(v) for v in root.get("viewBox").split()]
    # SVG y runs down from the sheet's top edge, plan Y up from the main fold halfway down it.
    top = view[3] / 2
    layers = {}
    lines = {}
    for group in root.findall("svg:g", ns):
        segments = layers.setdefault(group.get("id"), [])
        for polyline in group.findall("svg:polyline", ns):
            pts = [tuple(float(c) for c in p.split(",")) for p in polyline.get("points").split()]
            pts = [(x, top - y) for x, y in pts]
            segments.extend([a[0], a[1], b[0], b[1]] for a, b in zip(pts, pts[1:]))
            dash = polyline.get("stroke-dasharray")
            lines.setdefault(group.get("id"), []).append(
                {"points": pts, "dash": [float(v) for v in dash.replace(",", " ").split()] if dash else None})
    text = {name: "".join(root.find("svg:" + name, ns).itertext()) if root.find("svg:" + name, ns) is not None else None
            for name in ("title", "desc", "metadata")}
    return layers, {"width": root.get("width"), "height": root.get("height"), "viewBox": view}, lines, text


def dxf_audit(path):
    auditor = ezdxf.readfile(path).audit()
    return [entry.message for entry in list(auditor.fixes) + list(auditor.errors)]


dxf, insunits, measurement, colours, types, dxf_comments = dxf_segments(sys.argv[1])
svg, size, svg_lines, svg_text = svg_segments(sys.argv[2])
print(json.dumps({"insunits": insunits, "measurement": measurement, "dxf": dxf, "dxf_colours": colours,
                  "dxf_types": types, "dxf_comments": dxf_comments, "dxf_audit": dxf_audit(sys.argv[1]), "svg": svg, "svg_size": size,
                  "svg_lines": svg_lines, "svg_title": svg_text["title"], "svg_desc": svg_text["desc"],
                  "svg_metadata": svg_text["metadata"]}))
