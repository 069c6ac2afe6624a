"""Component images from Python: aovs=["components", "lightgroups"] gives the layers by name,
each split summing to the radiance, and write_exr/read_exr keep them."""

import numpy as np

import nxrender


def test_components_split_the_radiance(scenes, tmp_path):
    image = nxrender.render(str(scenes / "blacklight.scn"), spp=8,
                            aovs=["components", "lightgroups"])
    layers = image.components
    assert list(layers)[:4] == ["reflected", "fluoresced", "direct", "indirect"]
    groups = [name for name in layers if name.startswith("light.")]
    assert groups, list(layers)
    total = image.radiance.astype(np.float64)
    scale = total.max()
    for split in (["reflected", "fluoresced"], ["direct", "indirect"], groups):
        parts = sum(layers[name].astype(np.float64) for name in split)
        assert np.max(np.abs(parts - total)) <= 1e-5 * scale, split
    # the black-light scene fluoresces: a real share of the image is re-radiated
    assert layers["fluoresced"].sum() > 0.05 * total.sum()
    for name, v in image.component_variances.items():
        assert v.shape == total.shape and np.all(v >= 0), name
    nxrender.write_exr(tmp_path / "c.exr", image)
    back = nxrender.read_exr(tmp_path / "c.exr")
    assert list(back.components) == list(layers)
    for name in layers:
        np.testing.assert_array_equal(back.components[name], layers[name])


def test_no_components_without_the_aov(scenes):
    assert nxrender.render(str(scenes / "white_floor.scn"), spp=1).components == {}
