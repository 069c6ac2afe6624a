"""Ground-truth layers from Python: aovs=["normals", "position", "uv", "albedo",
"fluorescence", ...] gives them by name as arrays lined up with the radiance, write_exr and
read_exr keep them, and names nxrender does not make are refused."""

import numpy as np
import pytest

import nxrender


def sphere_scene():
    return nxrender.Scene.from_dict({
        "settings": {"xres": 32, "yres": 24, "mode": "spectral_mcpt", "sampl": 16,
                     "bands": "400:700:50"},
        "camera": {"position": [0, 0, -4], "look_at": [0, 0, 0], "fov": 30},
        "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1.0,
                     "material": "matte", "reflectance": 0.4,
                     "fluorescence": {"absorptance": "360:0, 380:0, 425:0.8, 470:0, 830:0",
                                      "emission": "360:0, 500:0, 575:1, 650:0, 830:0", "yield": 0.6}}],
        "lights": [{"type": "point", "position": [1, 2, -3], "color": [1, 1, 1]}],
    })


def test_layers_are_arrays_lined_up_with_the_radiance(tmp_path):
    image = nxrender.render(sphere_scene(), aovs=["normals", "position", "uv", "albedo",
                                                  "fluorescence", "geometric_normals"])
    h, w, bands = image.radiance.shape
    layers = image.aovs
    assert set(layers) == {"normals", "geometric_normals", "position", "uv", "albedo",
                           "fluorescence.absorption", "fluorescence.emission"}
    assert layers["normals"].shape == (h, w, 3) and layers["uv"].shape == (h, w, 2)
    assert layers["albedo"].shape == (h, w, bands)
    # the centre pixel sees the sphere's front: its normal faces the camera, its position on it
    n = layers["normals"][h // 2, w // 2]
    assert n[2] < -0.99 and abs(np.linalg.norm(n) - 1) < 1e-3
    assert abs(np.linalg.norm(layers["position"][h // 2, w // 2]) - 1) < 1e-3
    # beyond the dye's absorption the matte reflects its reflectance; within it, less
    np.testing.assert_allclose(layers["albedo"][h // 2, w // 2, 3:], 0.4, rtol=1e-5)
    assert layers["albedo"][h // 2, w // 2, 0] < 0.35
    # the dye absorbs in the blue (band 400-450) and emits in the green (500-550, 550-600)
    assert layers["fluorescence.absorption"][h // 2, w // 2, 0] > 0.1
    assert layers["fluorescence.emission"][h // 2, w // 2, 0] == 0
    assert layers["fluorescence.emission"][h // 2, w // 2, 3] > 0
    # a corner sees nothing: zeros
    assert not layers["normals"][0, 0].any()
    nxrender.write_exr(tmp_path / "a.exr", image)
    back = nxrender.read_exr(tmp_path / "a.exr")
    assert set(back.aovs) == set(layers)
    for name in layers:
        np.testing.assert_array_equal(back.aovs[name], layers[name])


def test_unknown_layer_is_refused():
    with pytest.raises(ValueError, match="'normal'"):
        nxrender.render(sphere_scene(), aovs=["normal"])
