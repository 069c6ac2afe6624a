"""An example dataset generator: scenes for learning to separate reflected from fluoresced
light (docs/datasets.md). Each scene: 2-5 primitive objects resting on a floor, without
intersections, each with a smooth random reflectance and, with probability 1/2, a random dye;
lit by a random lamp (a built-in spectrum or a narrow LED) from above; seen from a random
orbit. Its targets are the `reflected` and `fluoresced` component layers.

    build/apps/nxdataset scenes/datasets/separation.py --count 100 -o separation --spp 64 \\
        --aov components,normals,albedo,fluorescence
"""

import numpy as np

import nxrender.dataset as ds

SIZE = 128


def scene(index):
    rng = np.random.default_rng([2026, index])  # the same scene for the same index
    objects = [{"shape": "plane", "normal": [0, 1, 0], "distance": 0, "material": "matte",
                "reflectance": ds.random_reflectance(rng, 0.05, 0.6)}]
    for shape in ds.place_on_plane(rng, int(rng.integers(2, 6))):
        shape.update(material="matte", reflectance=ds.random_reflectance(rng))
        if rng.uniform() < 0.5:
            shape["fluorescence"] = ds.random_dye(rng)
        objects.append(shape)
    lamp = ds.random_lamp(rng)
    light = {"type": "point", "position": [float(v) for v in rng.uniform([-2, 4, -2], [2, 6, 2])],
             "color": [1, 1, 1], "emission": lamp, "emission_scale": 2.0}
    return {
        "settings": {"xres": SIZE, "yres": SIZE, "mode": "spectral_mcpt", "sampl": 64},
        "camera": ds.orbit_camera(rng),
        "objects": objects,
        "lights": [light],
    }
