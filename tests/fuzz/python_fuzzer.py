"""Random-input fuzzing of the Python entry points that take data (docs/reliability.md,
"Fuzzing"):

  dict  Scene.from_dict on random nested values: dicts and lists nested up to 40 deep (and
        ones that contain themselves), keys of the scene format and others, numbers of every
        size (ints of 400 digits, NaN, 1e308, -0.0), strings, bools, None and numpy arrays of
        every dtype. A scene it accepts must round-trip: from_dict(to_dict()) and
        from_text(to_text()) give the same text.
  item  A dataset item's reader on an item's bytes mutated: bit flips, bytes overwritten,
        truncated, extended, records rewritten with valid checksums (shapes, kinds, sizes
        forged). Each read must refuse (ValueError) or give exactly the original arrays.

Any other exception is a finding, and so is a crash (the process dies) or a hang (CTest's
time limit). Inputs come from a seeded generator: a finding is replayed by its seed and run.

Usage: python_fuzzer.py --kind dict|item [--runs N] [--seed S]
"""

import argparse
import json
import math
import os
import random
import sys
import tempfile
import time
import zlib

import numpy as np

import nxrender
import nxrender.dataset as nds

ALLOWED = (ValueError, TypeError, KeyError, IndexError, OverflowError, nxrender.Error)

KEYS = ["settings", "camera", "objects", "lights", "materials", "spectra", "xres", "yres",
        "mode", "sampl", "depth", "seed", "bands", "position", "look_at", "up", "fov", "shape",
        "sphere", "plane", "mesh", "box", "disk", "cylinder", "quad", "triangle", "center",
        "radius", "normal", "distance", "vertices", "faces", "normals", "uv", "transform",
        "material", "reflectance", "emission", "fluorescence", "absorption", "stokes", "yield",
        "medium", "sigma_a", "sigma_s", "g", "type", "color", "id", "name", "group", "file",
        "vA", "vB", "vC", "origin", "edge_u", "edge_v", "size", "height", "spectrum", "nm",
        "value", "scale", "at", "extrapolate", "roughness", "ior", "matte", "glass"]
WORDS = ["spectral_mcpt", "rt", "mcpt", "matte", "glass", "sphere", "mesh", "D65", "A", "blue",
         "red", "400:700:10", "point", "spot", "blackbody:3000", "csv:/dev/zero", "", "\0",
         "x" * 300, "1e+05", "nan", "../../etc/passwd", "<scene>", "&amp;"]


def number(rng):
    return rng.choice([0, 1, -1, 0.5, 2 ** 31, 2 ** 64, 10 ** rng.randrange(0, 400), -0.0,
                       float("nan"), float("inf"), 1e308, 1e-320, rng.uniform(-1e3, 1e3),
                       rng.randrange(-5, 100000), True, False])


def array(rng):
    shape = rng.choice([(0,), (3,), (2, 3), (4, 3), (1, 1, 1), (5, 2)])
    dtype = rng.choice([np.float32, np.float64, np.int64, np.uint32, np.int8, np.bool_,
                        np.complex64, np.float16])
    values = [rng.uniform(-3, 3) for _ in range(int(np.prod(shape)))]
    return np.array(values).reshape(shape).astype(dtype)


def value(rng, depth):
    kind = rng.random()
    if depth > 40 or kind < min(0.9, 0.3 + 0.1 * depth):  # leaves grow likelier with depth
        return number(rng)
    if kind > 0.98:  # a narrow chain, 10 to 40 deep
        v = number(rng)
        for _ in range(rng.randrange(10, 41)):
            v = [v] if rng.random() < 0.7 else {rng.choice(KEYS): v}
        return v
    if kind < 0.4:
        return rng.choice(WORDS)
    if kind < 0.45:
        return None
    if kind < 0.5:
        return array(rng)
    if kind < 0.75:
        return [value(rng, depth + 1) for _ in range(rng.randrange(0, 5))]
    d = {}
    for _ in range(rng.randrange(0, 6)):
        d[rng.choice(KEYS) if rng.random() < 0.9 else rng.choice(WORDS)] = value(rng, depth + 1)
    if rng.random() < 0.02:
        d[rng.choice(KEYS)] = d  # contains itself
    return d


def scene_like(rng):
    """A dict shaped like a scene, with random parts (most random dicts fail at the top)."""
    d = {"settings": {"xres": rng.choice([4, 8, 0, -1, 10 ** 400, 2.5]), "yres": 4,
                      "mode": rng.choice(["spectral_mcpt", "rt", "x"])},
         "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0]},
         "objects": [value(rng, 2) if rng.random() < 0.5 else
                     {"shape": rng.choice(["sphere", "plane", "mesh", "box"]),
                      "center": [0, 0, 0], "radius": number(rng), "material": "matte",
                      rng.choice(KEYS): value(rng, 3)} for _ in range(rng.randrange(0, 3))]}
    if rng.random() < 0.3:
        d[rng.choice(KEYS)] = value(rng, 1)
    return d


def fuzz_dict(rng, run):
    d = scene_like(rng) if rng.random() < 0.7 else value(rng, 0)
    try:
        scene = nxrender.Scene.from_dict(d)
    except ALLOWED:
        return
    text = scene.to_text()
    assert nxrender.Scene.from_dict(scene.to_dict()).to_text() == text, f"run {run}: to_dict"
    assert nxrender.Scene.from_text(text).to_text() == text, f"run {run}: to_text"


def small_scene(index):
    return {"settings": {"xres": 6, "yres": 4, "mode": "spectral_mcpt", "sampl": 2,
                         "bands": "400:700:100"},
            "camera": {"position": [0, 1, -4], "look_at": [0, 0, 0]},
            "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.5 + 0.1 * index,
                         "material": "matte", "reflectance": 0.5}],
            "lights": [{"type": "point", "position": [0, 3, -2], "color": [1, 1, 1]}]}


class ItemTarget:
    def __init__(self, folder):
        self.out = os.path.join(folder, "d")
        nds.generate(small_scene, 2, self.out, aovs=["components", "ids", "depth"],
                     log=lambda text: None)
        self.path = nds.item_path(self.out, 0)
        self.original = open(self.path, "rb").read()
        self.data = nds.Dataset(self.out)  # (it reads each item anew at every access)
        self.good = self.data[0]

    def forged(self, rng):
        """The item with its record changed and its checksum made valid again."""
        data = self.original
        head = len(nds._MAGIC) + 8
        n = int.from_bytes(data[len(nds._MAGIC):head], "little")
        meta = json.loads(data[head:head + n])
        name = rng.choice(list(meta["arrays"]))
        field = rng.choice(["shape", "kind", "bytes", "frames", "k", "chunk", "nibbles"])
        meta["arrays"][name][field] = value(rng, 30) if rng.random() < 0.5 else rng.choice(
            [[8192, 8192, 4], [4, 6, 4000], "float64", -1, 10 ** 12, [1, 2], 0, True, 64])
        if rng.random() < 0.3:
            meta[rng.choice(["scene", "wavelengths", "derived", "index"])] = value(rng, 30)
        text = json.dumps(meta, default=str).encode()
        return (nds._MAGIC + len(text).to_bytes(8, "little") + text +
                zlib.crc32(text).to_bytes(4, "little") + data[head + n + 4:])

    def mutated(self, rng):
        data = bytearray(self.original)
        how = rng.random()
        if how < 0.4:
            for _ in range(rng.randrange(1, 4)):
                bit = rng.randrange(8 * len(data))
                data[bit // 8] ^= 1 << (bit % 8)
        elif how < 0.55:
            at = rng.randrange(len(data))
            data[at:at + rng.randrange(1, 16)] = bytes(rng.randrange(256) for _ in range(8))
        elif how < 0.7:
            del data[rng.randrange(len(data)):]
        elif how < 0.75:
            data += bytes(rng.randrange(256) for _ in range(rng.randrange(1, 64)))
        else:
            return self.forged(rng)
        return bytes(data)

    def run(self, rng, run):
        data = self.mutated(rng)
        with open(self.path, "wb") as f:
            f.write(data)
        for read in (lambda d: d[0], lambda d: {k: v[0] for k, v in d[[0, 1]].items()}):
            try:
                item = read(self.data)
            except ALLOWED:
                continue
            for key, want in self.good.items():
                got = item[key]
                assert np.array_equal(np.asarray(got), np.asarray(want)), \
                    f"run {run}: {key} read changed, not refused"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--kind", choices=["dict", "item"], required=True)
    parser.add_argument("--runs", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    start = time.monotonic()
    with tempfile.TemporaryDirectory() as folder:
        target = ItemTarget(folder) if args.kind == "item" else None
        for run in range(args.runs):
            rng = random.Random(f"{args.seed}:{run}")
            try:
                if target:
                    target.run(rng, run)
                else:
                    fuzz_dict(rng, run)
            except AssertionError:
                raise
            except ALLOWED:
                pass
            except Exception as e:  # a finding
                print(f"FINDING: run {run} (seed {args.seed}): {type(e).__name__}: {e}")
                return 1
            if (run + 1) % 100000 == 0:
                print(f"{args.kind}: {run + 1} runs in {time.monotonic() - start:.0f} s",
                      flush=True)
    seconds = time.monotonic() - start
    print(f"{args.kind}: {args.runs} runs in {seconds:.1f} s, no findings")
    return 0


if __name__ == "__main__":
    sys.exit(main())
