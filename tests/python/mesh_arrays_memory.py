"""A mesh from arrays whose size exceeds the memory the process may use is refused with the
figures before it is built, as a mesh file is (it ended in Embree's out-of-memory error): 6M
vertices and 6M faces under the address-space limit the calling test sets (ulimit -v)."""

import sys

import numpy as np

import nxrender

n = 6_000_000
V = np.zeros((n, 3), np.float32)
V[:, 0] = np.arange(n, dtype=np.float32) * 1e-6
V[:, 1] = (np.arange(n) % 2).astype(np.float32)
F = np.stack([np.arange(n), (np.arange(n) + 1) % n, (np.arange(n) + 2) % n], 1).astype(np.uint32)
scene = nxrender.Scene.from_dict({
    "settings": {"xres": 8, "yres": 6, "mode": "spectral_mcpt", "sampl": 1},
    "camera": {"position": [0, 0, -5], "look_at": [0, 0, 0]},
    "objects": [{"shape": "mesh", "vertices": V, "faces": F, "material": "matte",
                 "reflectance": 0.5}]})
try:
    nxrender.render(scene, spp=1)
except nxrender.Error as e:
    message = str(e)
    want = ("mesh of <vertices> and <faces>: expected a mesh whose buffers fit in memory, found "
            "6000000 vertices and 6000000 faces (needs ")
    if want in message and "address-space limit" in message:
        print("refused with figures:", message)
        sys.exit(0)
    print("refused with another message:", message)
    sys.exit(1)
print("rendered a mesh that should not fit")
sys.exit(1)
