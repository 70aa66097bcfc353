"""Mitsuba 3 as a peer renderer of `ptlab converge` (tools/converge/peer_variant.h).

Renders a scene progressively in passes and hands every pass to ptlab, which measures it
against the same reference as its own variants. The protocol, on stdout, one JSON object a
line:
  {"event": "ready", "mitsuba": VERSION, "variant": ..., "load_seconds": s, ...}
  {"event": "pass", "pass": k, "spp": n, "seconds": s, "cpu_seconds": c, "file": PATH}
      PATH holds the pass's own samples as float32 (height, width, 4): the filter-weighted
      sums of R, G, B and the sum of the filter weights. After a pass the runner waits for a
      line on stdin ("next" or "stop"); the wait is not timed.
  {"event": "done", "passes": k, "spp": n}
  {"event": "error", "message": ...}   then exit status 2 (bad input) or 3 (no Mitsuba)
Times: seconds and cpu_seconds are cumulative over the passes' renders only; scene loading
(load_seconds) and the first render that compiles the kernels (warmup_seconds) are reported
apart, in the ready line.
Seeds: pass k of seed S renders with Mitsuba's seed (S * 65536 + k) mod 2^32.
Passes have --pass-spp samples, or what the sampler rounds that to (orthogonal: 25 for 16).
"""

import argparse
import glob
import json
import os
import re
import sys
import time

sys.dont_write_bytecode = True  # keep the source tree clean
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import nori_to_mitsuba  # noqa: E402

EXIT_INPUT, EXIT_NO_MITSUBA = 2, 3

# The protocol gets a private copy of stdout, and fd 1 becomes stderr: Mitsuba's logger writes
# its warnings to fd 1 (without a final newline before its colour reset), which would otherwise
# run into the protocol's lines.
PROTOCOL = os.fdopen(os.dup(1), "w")
os.dup2(2, 1)
sys.stdout = sys.stderr


def emit(obj):
    PROTOCOL.write(json.dumps(obj) + "\n")
    PROTOCOL.flush()


def fail(message, status=EXIT_INPUT):
    emit({"event": "error", "message": message})
    sys.exit(status)


def find_libllvm():
    """Dr.Jit's LLVM backend needs LLVM >= 15; 15 itself miscompiles (cannot select
    fminimum), so prefer the newest libLLVM installed (./lab installs Debian's libllvm19)."""
    for pattern in ("/usr/lib/llvm-*/lib/libLLVM.so*", "/usr/lib/*/libLLVM-*.so*",
                    "/usr/lib/*/libLLVM.so*"):
        best = None
        for path in glob.glob(pattern):
            digits = "".join(ch if ch.isdigit() else " " for ch in os.path.basename(path)).split()
            if not digits and "llvm-" in path:
                digits = path.split("llvm-")[1].split("/")[0].split(".")
            try:
                major = int(digits[0])
            except (IndexError, ValueError):
                continue
            if major >= 16 and (best is None or major > best[0]):
                best = (major, path)
        if best:
            return best[1]
    return None


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", required=True)
    ap.add_argument("--width", type=int, required=True)
    ap.add_argument("--height", type=int, required=True)
    ap.add_argument("--filter", default="gaussian", choices=["box", "tent", "gaussian"])
    ap.add_argument("--filter-radius", type=float, default=2.0)
    ap.add_argument("--filter-stddev", type=float, default=0.5)
    ap.add_argument("--camera-to-world", help="16 numbers, row-major (ptlab's loaded camera)")
    ap.add_argument("--fov", type=float, help="horizontal, degrees")
    ap.add_argument("--near", type=float, default=1e-4)
    ap.add_argument("--far", type=float, default=1e4)
    ap.add_argument("--aperture", type=float, default=0.0)
    ap.add_argument("--focus", type=float, default=1.0)
    ap.add_argument("--lookat", default="nori", choices=["nori", "nori2015"])
    ap.add_argument("--variant", default="llvm_ad_rgb", choices=["llvm_ad_rgb", "scalar_rgb"])
    ap.add_argument("--sampler", default="independent",
                    choices=["independent", "multijitter", "stratified", "ldsampler",
                             "orthogonal"])
    ap.add_argument("--max-depth", type=int, default=-1)
    ap.add_argument("--rr-depth", type=int, default=5)
    ap.add_argument("--pass-spp", type=int, default=16)
    ap.add_argument("--spp", type=int, default=0, help="total samples per pixel")
    ap.add_argument("--time", type=float, default=0.0, help="render seconds, whole passes")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", required=True, help="folder for the pass files")
    return ap.parse_args()


def rfilter_dict(a):
    if a.filter == "box":
        if abs(a.filter_radius - 0.5) > 1e-6:
            fail(f"a box filter of radius {a.filter_radius}: Mitsuba's box has radius 0.5")
        return {"type": "box"}
    if a.filter == "tent":
        return {"type": "tent", "radius": a.filter_radius}
    # Mitsuba's Gaussian has radius 4 stddev; Nori's default (2, 0.5) is one of those.
    if abs(a.filter_radius - 4 * a.filter_stddev) > 1e-6:
        fail(f"a Gaussian filter of radius {a.filter_radius} and stddev {a.filter_stddev}: "
             "Mitsuba's Gaussian has radius 4 stddev")
    return {"type": "gaussian", "stddev": a.filter_stddev}


def sensor_dict(a, mi, native_scene):
    film = {"type": "hdrfilm", "width": a.width, "height": a.height, "pixel_format": "rgb",
            "sample_border": False, "rfilter": rfilter_dict(a)}
    sampler = {"type": a.sampler, "sample_count": a.pass_spp}
    if a.camera_to_world:
        m = [float(x) for x in a.camera_to_world.split(",")]
        to_world = mi.ScalarTransform4f([m[4 * i:4 * i + 4] for i in range(4)])
        fov = a.fov
        near, far = a.near, a.far
    elif native_scene is not None:
        params = mi.traverse(native_scene.sensors()[0])
        to_world = mi.ScalarTransform4f(params["to_world"].matrix.numpy()[0]) \
            if hasattr(params["to_world"].matrix, "numpy") else params["to_world"]
        fov = float(params["x_fov"][0]) if hasattr(params["x_fov"], "__len__") \
            else float(params["x_fov"])
        near, far = float(params["near_clip"]), float(params["far_clip"])
    else:
        fail("no camera given (--camera-to-world and --fov)")
    sensor = {"type": "perspective", "fov": fov, "fov_axis": "x", "near_clip": near,
              "far_clip": far, "to_world": to_world, "film": film, "sampler": sampler}
    if a.aperture > 0:
        sensor.update({"type": "thinlens", "aperture_radius": a.aperture,
                       "focus_distance": a.focus})
    return sensor


def main():
    a = parse_args()
    if a.spp <= 0 and a.time <= 0:
        fail("give --spp or --time")
    if a.pass_spp <= 0:
        fail("--pass-spp must be >= 1")
    if a.spp > 0:
        a.pass_spp = min(a.pass_spp, a.spp)
    if "DRJIT_LIBLLVM_PATH" not in os.environ and a.variant.startswith("llvm"):
        lib = find_libllvm()
        if lib:
            os.environ["DRJIT_LIBLLVM_PATH"] = lib
    try:
        import drjit as dr
        import mitsuba as mi
        import numpy as np
    except ImportError as e:
        fail(f"Mitsuba 3 is not installed for {sys.executable} ({e}); ./lab peer-install "
             "installs it", EXIT_NO_MITSUBA)
    try:
        mi.set_variant(a.variant)
    except Exception as e:  # the LLVM backend can be missing (no libLLVM)
        fail(f"Mitsuba variant {a.variant} is not usable here: {e}", EXIT_NO_MITSUBA)
    if a.threads > 0:
        dr.set_thread_count(a.threads)
    os.makedirs(a.out, exist_ok=True)

    t0 = time.perf_counter()
    native = None
    try:
        if nori_to_mitsuba.is_mitsuba_format(a.scene):
            native = mi.load_file(a.scene)
            scene = native
        else:
            shapes = nori_to_mitsuba.Port(a.scene, a.lookat).scene_dict(mi)
            scene = mi.load_dict(shapes)
        sensor = mi.load_dict(sensor_dict(a, mi, native))
        integrator = mi.load_dict({"type": "path", "max_depth": a.max_depth,
                                   "rr_depth": a.rr_depth})
    except nori_to_mitsuba.PortError as e:
        fail(f"Mitsuba cannot render this scene: {e}")
    except Exception as e:  # Mitsuba's own parse and load errors
        fail(f"Mitsuba cannot read {a.scene}: {str(e).strip().splitlines()[-1]}")
    load_seconds = time.perf_counter() - t0

    # Samplers round the sample count to what they can stratify (orthogonal: the square of a
    # prime, so 16 becomes 25): a pass is what the sampler takes, and the events say so.
    a.pass_spp = int(sensor.sampler().sample_count())

    def render(seed):
        integrator.render(scene, sensor, seed=seed, spp=a.pass_spp, develop=False)
        bitmap = sensor.film().bitmap(raw=True)
        dr.sync_thread()
        return bitmap

    # The first render compiles the kernels (llvm) and is not timed as a pass; later passes
    # reuse them (the seed is not part of the kernel).
    t0 = time.perf_counter()
    if a.variant.startswith("llvm"):
        render(0xFFFFFFFF)
    warmup_seconds = time.perf_counter() - t0
    emit({"event": "ready", "mitsuba": mi.__version__, "drjit": dr.__version__,
          "variant": a.variant, "load_seconds": load_seconds, "warmup_seconds": warmup_seconds,
          "libllvm": os.environ.get("DRJIT_LIBLLVM_PATH", "")})

    seconds = cpu_seconds = 0.0
    k = 0
    while True:
        t0, c0 = time.perf_counter(), time.process_time()
        bitmap = render((a.seed * 65536 + k) % (1 << 32))
        seconds += time.perf_counter() - t0
        cpu_seconds += time.process_time() - c0
        raw = np.array(bitmap, dtype=np.float32)
        names = re.findall(r"float32 (\w+);", str(bitmap.struct_()))
        rgbw = raw[:, :, [names.index(c) for c in ("R", "G", "B", "W")]]
        path = os.path.join(a.out, f"pass_{k:06d}.f32")
        np.ascontiguousarray(rgbw).tofile(path)
        spp = (k + 1) * a.pass_spp
        emit({"event": "pass", "pass": k, "spp": spp, "seconds": seconds,
              "cpu_seconds": cpu_seconds, "file": path})
        k += 1
        if sys.stdin.readline().strip() != "next":
            break
        if (a.spp > 0 and spp + a.pass_spp > a.spp) or (a.time > 0 and seconds >= a.time):
            break
    emit({"event": "done", "passes": k, "spp": k * a.pass_spp})


if __name__ == "__main__":
    main()
