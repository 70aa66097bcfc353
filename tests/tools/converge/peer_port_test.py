#!/usr/bin/env python3
"""The Nori -> Mitsuba port's microfacet mapping evaluates Nori's microfacet BRDF (label peer).

Nori's microfacet, f = kd/pi + ks D F G / (4 cos_i cos_o) with ks = 1 - max(kd), Beckmann D,
dielectric Fresnel F and the rational Smith G1 approximation, is written here from its
definition and compared with Mitsuba's evaluation of the ported blendbsdf at 2000 random
direction pairs for three materials (Veach's plates, a coloured one, a pure specular one).
Exit 77 (skipped) when Mitsuba 3 is not installed; runs itself under the interpreter of
PTLAB_MITSUBA_PYTHON or ./lab peer-install's virtual environment.
"""
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.dont_write_bytecode = True
sys.path.insert(0, os.path.join(ROOT, "tools", "converge", "peer"))

try:
    import mitsuba as mi
except ImportError:
    venv = os.environ.get("PTLAB_MITSUBA_PYTHON") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"),
        "ptlab", "mitsuba-venv", "bin", "python")
    # (A venv's python links to the system's: mark the second run instead of comparing paths.)
    if os.access(venv, os.X_OK) and not os.environ.get("PTLAB_PEER_TEST_REEXEC"):
        os.environ["PTLAB_PEER_TEST_REEXEC"] = "1"
        os.execv(venv, [venv, __file__])
    print(f"skipped: Mitsuba 3 is not installed (no {venv}); ./lab peer-install installs it")
    sys.exit(77)

import nori_to_mitsuba as port  # noqa: E402

INT_IOR, EXT_IOR = 1.5046, 1.000277
TOLERANCE = 1e-4  # relative, with a floor of 1e-3 under the denominator (float32 in Mitsuba)


def fresnel(cos_i, eta_ext, eta_int):
    if cos_i < 0:
        eta_ext, eta_int, cos_i = eta_int, eta_ext, -cos_i
    eta = eta_ext / eta_int
    sin2_t = eta * eta * (1 - cos_i * cos_i)
    if sin2_t > 1:
        return 1.0
    cos_t = math.sqrt(1 - sin2_t)
    rs = (eta_ext * cos_i - eta_int * cos_t) / (eta_ext * cos_i + eta_int * cos_t)
    rp = (eta_int * cos_i - eta_ext * cos_t) / (eta_int * cos_i + eta_ext * cos_t)
    return (rs * rs + rp * rp) / 2


def smith_g1(v, m, alpha):
    if sum(v[i] * m[i] for i in range(3)) / v[2] <= 0:
        return 0.0
    tan = math.sqrt(max(0.0, 1 - v[2] ** 2)) / v[2]
    if tan == 0:
        return 1.0
    b = 1 / (alpha * tan)
    return 1.0 if b >= 1.6 else (3.535 * b + 2.181 * b * b) / (1 + 2.276 * b + 2.577 * b * b)


def nori_microfacet_cos(wi, wo, kd, alpha):
    """f(wi, wo) cos(theta_o), as Mitsuba's eval returns it."""
    if wi[2] <= 0 or wo[2] <= 0:
        return [0.0] * 3
    ks = 1 - max(kd)
    h = [wi[i] + wo[i] for i in range(3)]
    length = math.sqrt(sum(x * x for x in h))
    h = [x / length for x in h]
    tan2 = (1 - h[2] ** 2) / h[2] ** 2
    d = math.exp(-tan2 / alpha ** 2) / (math.pi * alpha ** 2 * h[2] ** 4)
    f = fresnel(sum(wi[i] * h[i] for i in range(3)), EXT_IOR, INT_IOR)
    g = smith_g1(wi, h, alpha) * smith_g1(wo, h, alpha)
    return [(kd[k] / math.pi + ks * d * f * g / (4 * wi[2] * wo[2])) * wo[2] for k in range(3)]


def main():
    mi.set_variant("scalar_rgb")
    rng = random.Random(43)

    def direction():
        z = rng.uniform(-0.2, 1.0)
        phi = rng.uniform(0, 2 * math.pi)
        r = math.sqrt(1 - z * z)
        return [r * math.cos(phi), r * math.sin(phi), z]

    worst = 0.0
    for kd, alpha in [([0.0175, 0.0225, 0.0325], 0.05), ([0.5, 0.3, 0.2], 0.3), ([0, 0, 0], 0.1)]:
        node = port.Node("bsdf", {"type": "microfacet"}, 1, 1)
        node.children = [port.Node("color", {"name": "kd", "value": ",".join(map(str, kd))}, 1, 1),
                         port.Node("float", {"name": "alpha", "value": str(alpha)}, 1, 1)]
        bsdf = mi.load_dict(port.Port("test.xml").bsdf(node))
        si = mi.SurfaceInteraction3f()
        si.n = mi.Vector3f(0, 0, 1)
        si.sh_frame = mi.Frame3f(si.n)
        for _ in range(2000):
            wi, wo = direction(), direction()
            si.wi = mi.Vector3f(wi)
            got = bsdf.eval(mi.BSDFContext(), si, mi.Vector3f(wo))
            want = nori_microfacet_cos(wi, wo, kd, alpha)
            for k in range(3):
                err = abs(got[k] - want[k]) / max(want[k], 1e-3)
                worst = max(worst, err)
                if err > TOLERANCE:
                    print(f"FAIL kd={kd} alpha={alpha} wi={wi} wo={wo}: Mitsuba {got[k]}, "
                          f"Nori {want[k]}")
                    sys.exit(1)
    print(f"ok: the ported microfacet matches Nori's within {worst:.2g} (relative)")


if __name__ == "__main__":
    main()
