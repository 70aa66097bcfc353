"""Port of Nori-format scene XML (ptlab's format) to a Mitsuba 3 scene dict, for the features
the shared Nori scenes use. docs/peer.md lists every model difference between the two.

Supported: <mesh|shape type="obj|sphere|rectangle|cube|disk"> with transform toWorld, one
<bsdf type="diffuse|dielectric|mirror|microfacet"> and one <emitter type="area">. The camera,
sampler and integrator are not ported: the peer runner builds them from ptlab's loaded scene
(tools/converge/peer/mitsuba_peer.py), so both renderers use the same film and camera.
Anything else is a PortError naming file:line and what is accepted.
"""

import math
import os
import xml.parsers.expat

# Nori's defaults (ptlab's loader, engine/io/xml_bsdfs.cpp, uses the same).
NORI_INT_IOR = 1.5046  # BK7
NORI_EXT_IOR = 1.000277  # air
NORI_MICROFACET_ALPHA = 0.1


class PortError(Exception):
    """A scene feature the port cannot express; the message names file:line."""


class Node:
    """An XML element with the line it starts on."""

    def __init__(self, tag, attrs, line, column):
        self.tag, self.attrs, self.line, self.column = tag, attrs, line, column
        self.children = []


def parse_xml(path):
    """Parses `path` into Nodes (expat, so that every element keeps its line)."""
    parser = xml.parsers.expat.ParserCreate()
    stack, root = [], []

    def start(tag, attrs):
        node = Node(tag, attrs, parser.CurrentLineNumber, parser.CurrentColumnNumber + 1)
        (stack[-1].children if stack else root).append(node)
        stack.append(node)

    def end(_tag):
        stack.pop()

    parser.StartElementHandler, parser.EndElementHandler = start, end
    try:
        with open(path, "rb") as f:
            parser.ParseFile(f)
    except OSError as e:
        raise PortError(f"{path}: cannot read: {e.strerror}") from e
    except xml.parsers.expat.ExpatError as e:
        raise PortError(f"{path}:{e.lineno}:{e.offset + 1}: malformed XML: "
                        f"{xml.parsers.expat.ErrorString(e.code)}") from e
    return root[0]


def is_mitsuba_format(path):
    """Mitsuba's scene files carry <scene version="...">; Nori's root has no version."""
    return "version" in parse_xml(path).attrs


class Matrix:
    """A 4x4 row-major matrix (lists), enough for Nori's transform steps."""

    def __init__(self, rows=None):
        self.m = rows or [[float(i == j) for j in range(4)] for i in range(4)]

    def __mul__(self, o):
        return Matrix([[sum(self.m[i][k] * o.m[k][j] for k in range(4)) for j in range(4)]
                       for i in range(4)])


def _vec(text, where, count=3):
    parts = [p for p in text.replace(",", " ").split() if p]
    try:
        values = [float(p) for p in parts]
    except ValueError:
        values = []
    if len(values) == 1 and count == 3:
        values = values * 3
    if len(values) != count:
        raise PortError(f"{where}: '{text}' is not {count} numbers")
    return values


def _norm(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


class Port:
    """Nori scene XML -> Mitsuba dict (shapes only; see the module comment)."""

    def __init__(self, path, lookat="nori"):
        self.path, self.dir, self.lookat = path, os.path.dirname(os.path.abspath(path)), lookat

    def where(self, node):
        return f"{self.path}:{node.line}:{node.column}"

    def props(self, node):
        """name -> (tag, value, node) of the property children (color, float, string, ...)."""
        out = {}
        for c in node.children:
            if c.tag in ("color", "float", "integer", "string", "boolean", "point", "vector"):
                out[c.attrs.get("name", "")] = (c.tag, c.attrs.get("value", ""), c)
        return out

    def color(self, props, name, default):
        if name not in props:
            return default
        _, value, node = props[name]
        return _vec(value, self.where(node))

    def number(self, props, name, default):
        if name not in props:
            return default
        _, value, node = props[name]
        try:
            return float(value)
        except ValueError:
            raise PortError(f"{self.where(node)}: '{value}' is not a number") from None

    def transform(self, node):
        t = Matrix()
        for step in node.children:
            w = self.where(step)
            if step.tag == "translate":
                v = _vec(step.attrs.get("value", ""), w)
                s = Matrix()
                for i in range(3):
                    s.m[i][3] = v[i]
            elif step.tag == "scale":
                v = _vec(step.attrs.get("value", ""), w)
                s = Matrix()
                for i in range(3):
                    s.m[i][i] = v[i]
            elif step.tag == "rotate":
                axis = _norm(_vec(step.attrs.get("axis", ""), w))
                angle = math.radians(float(step.attrs.get("angle", "0")))
                c, si = math.cos(angle), math.sin(angle)
                x, y, z = axis
                k = 1 - c  # Rodrigues' rotation about the unit axis, right-handed
                s = Matrix([[c + x * x * k, x * y * k - z * si, x * z * k + y * si, 0],
                            [y * x * k + z * si, c + y * y * k, y * z * k - x * si, 0],
                            [z * x * k - y * si, z * y * k + x * si, c + z * z * k, 0],
                            [0, 0, 0, 1]])
            elif step.tag == "matrix":
                v = _vec(step.attrs.get("value", ""), w, 16)
                s = Matrix([v[4 * i:4 * i + 4] for i in range(4)])
            elif step.tag == "lookat":
                origin = _vec(step.attrs.get("origin", ""), w)
                target = _vec(step.attrs.get("target", ""), w)
                up = _vec(step.attrs.get("up", ""), w)
                d = _norm([target[i] - origin[i] for i in range(3)])
                if self.lookat == "nori2015":
                    left = _cross(d, _norm(up))
                    new_up = _cross(left, d)
                else:
                    left = _norm(_cross(_norm(up), d))
                    new_up = _norm(_cross(d, left))
                cols = [left, new_up, d, origin]
                s = Matrix([[cols[c][r] for c in range(4)] for r in range(3)] + [[0, 0, 0, 1]])
            else:
                raise PortError(f"{w}: transform step <{step.tag}> is not ported; expected "
                                "translate, scale, rotate, matrix or lookat")
            t = s * t
        return t

    def bsdf(self, node):
        p, kind = self.props(node), node.attrs.get("type", "")
        if kind == "diffuse":
            return {"type": "diffuse",
                    "reflectance": {"type": "rgb", "value": self.color(p, "albedo", [0.5] * 3)}}
        if kind == "dielectric":
            # ptlab's extensions (Schlick's Fresnel, radiance scaling) are not Nori's model.
            for name in ("schlick", "scaleRadiance"):
                if name in p and p[name][1].strip().lower() == "true":
                    raise PortError(f"{self.where(p[name][2])}: dielectric '{name}' = true is "
                                    "not ported; Mitsuba's dielectric has exact Fresnel and "
                                    "always scales radiance on refraction (docs/peer.md)")
            return {"type": "dielectric",
                    "int_ior": self.number(p, "intIOR", NORI_INT_IOR),
                    "ext_ior": self.number(p, "extIOR", NORI_EXT_IOR)}
        if kind == "mirror":
            return {"type": "conductor", "material": "none"}
        if kind == "microfacet":
            # Nori's microfacet: f = kd/pi + ks D F G / (4 cos_i cos_o), ks = 1 - max(kd),
            # sampled as the specular lobe with probability ks. Mitsuba has no such sum; a
            # blend with weight ks of diffuse(kd / max(kd)) and a smooth-Fresnel Beckmann
            # reflector is the same function: (1-ks) kd/max(kd)/pi = kd/pi. The reflector is
            # roughconductor with eta = intIOR/extIOR and k = 0, whose conductor Fresnel is the
            # dielectric Fresnel term Nori uses (docs/peer.md).
            kd = self.color(p, "kd", [0.5] * 3)
            alpha = self.number(p, "alpha", NORI_MICROFACET_ALPHA)
            eta = self.number(p, "intIOR", NORI_INT_IOR) / self.number(p, "extIOR", NORI_EXT_IOR)
            kd_max = max(kd)
            ks = 1.0 - kd_max
            specular = {"type": "roughconductor", "distribution": "beckmann", "alpha": alpha,
                        "eta": {"type": "rgb", "value": [eta] * 3},
                        "k": {"type": "rgb", "value": [0.0] * 3}}
            diffuse = {"type": "diffuse", "reflectance": {
                "type": "rgb", "value": [c / kd_max if kd_max > 0 else 0.0 for c in kd]}}
            if ks >= 1.0:
                return specular
            return {"type": "blendbsdf", "weight": ks, "bsdf_0": diffuse, "bsdf_1": specular}
        raise PortError(f"{self.where(node)}: bsdf type '{kind}' is not ported; expected "
                        "diffuse, dielectric, mirror or microfacet")

    def shape(self, node, mi):
        kind, p = node.attrs.get("type", ""), self.props(node)
        shape = {}
        if kind == "obj":
            if "filename" not in p:
                raise PortError(f"{self.where(node)}: obj mesh without a 'filename'")
            filename = os.path.join(self.dir, p["filename"][1])
            if not os.path.isfile(filename):
                raise PortError(f"{self.where(p['filename'][2])}: mesh file '{filename}' not found")
            shape = {"type": "obj", "filename": filename}
            # Nori shades an OBJ without normals with its flat geometric normal; Mitsuba's
            # loader would smooth it, unless asked for face normals.
            if not _obj_has_normals(filename):
                shape["face_normals"] = True
        elif kind == "sphere":
            # ptlab tessellates (3968 triangles, engine/io/shapes.h); Mitsuba's is analytic.
            center = self.color(p, "center", [0.0] * 3)
            shape = {"type": "sphere", "center": center, "radius": self.number(p, "radius", 1.0)}
        elif kind in ("rectangle", "cube"):
            # The same canonical shapes: [-1,1]^2 in z = 0 (normal +z) and the cube [-1,1]^3.
            shape = {"type": kind}
        elif kind == "disk":
            # ptlab's disk is a 64-gon (area 0.16 % below the circle's); Mitsuba's is analytic.
            shape = {"type": "disk"}
        else:
            raise PortError(f"{self.where(node)}: shape type '{kind}' is not ported; expected "
                            "obj, sphere, rectangle, cube or disk")
        bsdf = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.5] * 3}}
        for c in node.children:
            if c.tag == "transform" and c.attrs.get("name") == "toWorld":
                shape["to_world"] = mi.ScalarTransform4f(self.transform(c).m)
            elif c.tag == "bsdf":
                bsdf = self.bsdf(c)
            elif c.tag == "emitter":
                if c.attrs.get("type") != "area":
                    raise PortError(f"{self.where(c)}: emitter type '{c.attrs.get('type')}' on "
                                    "a shape is not ported; expected area")
                radiance = self.color(self.props(c), "radiance", None)
                if radiance is None:
                    raise PortError(f"{self.where(c)}: area emitter without 'radiance'")
                shape["emitter"] = {"type": "area",
                                    "radiance": {"type": "rgb", "value": radiance}}
            elif c.tag not in ("string", "float", "point", "integer", "boolean", "color"):
                raise PortError(f"{self.where(c)}: <{c.tag}> inside a shape is not ported")
        shape["bsdf"] = bsdf
        return shape

    def scene_dict(self, mi):
        """The scene's shapes as a Mitsuba dict (no sensor, integrator or sampler)."""
        root = parse_xml(self.path)
        if root.tag != "scene":
            raise PortError(f"{self.where(root)}: root element <{root.tag}>; expected <scene>")
        out = {"type": "scene"}
        for i, c in enumerate(root.children):
            if c.tag in ("mesh", "shape"):
                out[f"shape_{i:04d}"] = self.shape(c, mi)
            elif c.tag in ("camera", "sampler", "integrator"):
                continue  # built by the runner from ptlab's scene
            elif c.tag == "emitter":
                raise PortError(f"{self.where(c)}: emitter type '{c.attrs.get('type')}' is not "
                                "ported; only area emitters on shapes are")
            else:
                raise PortError(f"{self.where(c)}: <{c.tag}> is not ported")
        return out


def _obj_has_normals(filename):
    with open(filename, "rb") as f:
        for line in f:
            if line.startswith(b"vn "):
                return True
    return False
