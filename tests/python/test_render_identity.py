"""nxrender.render gives the command line's image bit for bit, for every option that changes
which samples are taken or what is recorded."""

import numpy as np
import pytest

import nxrender


def assert_same_pixels(a, b):
    """Every stored channel identical (not close: the same float bits)."""
    assert a.radiance.shape == b.radiance.shape
    np.testing.assert_array_equal(a.wavelengths, b.wavelengths)
    for name in ("radiance", "variance", "y_variance", "xyz", "rgb", "sample_count", "white",
                 "object_id", "material_id", "depth"):
        x, y = getattr(a, name), getattr(b, name)
        assert (x is None) == (y is None), name
        if x is not None:
            assert x.dtype == y.dtype, name
            assert np.array_equal(x.view(np.uint8), y.view(np.uint8)), name
    assert a.origin == b.origin and a.full_size == b.full_size
    for field in ("components", "component_variances"):
        x, y = getattr(a, field), getattr(b, field)
        assert list(x) == list(y), field
        for name in x:
            assert np.array_equal(x[name].view(np.uint8), y[name].view(np.uint8)), (field, name)


@pytest.mark.parametrize("cli_args, py_args", [
    (["--spp", "8", "--seed", "5"], dict(spp=8, seed=5)),
    (["--spp-range", "3:9", "--crop", "40,10,130,70"], dict(spp_range=(3, 9), crop=(40, 10, 130, 70))),
    (["--spp", "4", "--bands", "420:680:20", "--aov", "ids,depth,white"],
     dict(spp=4, bands="420:680:20", aovs=["ids", "depth", "white"])),
    (["--spp", "4", "--sensor", "gaussian:450,530,610@25", "--sampler", "independent",
      "--light-sampling", "nee", "--light-selection", "power"],
     dict(spp=4, sensor="gaussian:450,530,610@25", sampler="independent",
          light_sampling="nee", light_selection="power")),
    (["--spp", "4", "--aov", "components,lightgroups"],
     dict(spp=4, aovs=["components", "lightgroups"])),
    (["--spp", "4", "--no-fluorescence", "--wavelength-density", "visible"],
     dict(spp=4, fluorescence=False, wavelength_density="visible")),
])
def test_render_matches_command_line(run_cli, scenes, tmp_path, cli_args, py_args):
    scene = scenes / "blacklight.scn"
    code, err = run_cli("--threads", "2", *cli_args, "-o", tmp_path / "cli.exr", scene)
    assert code == 0, err
    cli = nxrender.read_exr(tmp_path / "cli.exr")
    # another thread count than the command line's: the image must not depend on it
    image = nxrender.render(str(scene), threads=1, **py_args)
    assert_same_pixels(image, cli)
    for key in ("nxrender.renderKey", "nxrender.seed", "nxrender.bands", "nxrender.sampleRange",
                "nxrender.sampler", "nxrender.lightSampling", "nxrender.fluorescence"):
        assert image.attributes[key] == cli.attributes[key], key


def test_written_file_matches_command_line_file(run_cli, scenes, tmp_path):
    """write_exr of a render stores the same channels and values as the command line's EXR,
    read by an independent reader (OpenImageIO)."""
    import OpenImageIO as oiio
    scene = scenes / "white_floor.scn"
    assert run_cli("--spp", "4", "-o", tmp_path / "cli.exr", scene)[0] == 0
    nxrender.write_exr(tmp_path / "py.exr", nxrender.render(scene, spp=4))
    a, b = oiio.ImageBuf(str(tmp_path / "cli.exr")), oiio.ImageBuf(str(tmp_path / "py.exr"))
    assert a.spec().channelnames == b.spec().channelnames
    # (read once as floats: OpenImageIO 2.4 crashes reading mixed float/uint files in their
    # native types; the counts are small integers, exact as floats)
    pa, pb = a.get_pixels(oiio.FLOAT), b.get_pixels(oiio.FLOAT)
    assert pa.shape == pb.shape
    for i, name in enumerate(a.spec().channelnames):
        assert np.array_equal(pa[..., i], pb[..., i]), name


def test_scene_object_without_edits_matches_file(scenes):
    path = scenes / "thesis.scn"
    a = nxrender.render(nxrender.Scene(path), spp=2, seed=1)
    b = nxrender.render(path, spp=2, seed=1)
    assert_same_pixels(a, b)
    assert a.attributes["nxrender.renderKey"] == b.attributes["nxrender.renderKey"]
    assert "nxrender.sceneEdits" not in a.attributes


def test_scene_text_matches_file(scenes):
    path = scenes / "blacklight.scn"
    a = nxrender.render(path.read_text(), spp=2)
    b = nxrender.render(path, spp=2)
    assert_same_pixels(a, b)


def test_edits_equal_the_edited_file(scenes):
    """Changing parameters from Python renders what the same change in the file renders."""
    path = scenes / "blacklight.scn"
    text = path.read_text()
    edited = (text.replace("<stokes>150</stokes>", "<stokes>95.5</stokes>")
                  .replace("<reflectance>0.9</reflectance>", "<reflectance>0.4</reflectance>")
                  .replace("<position>0, 2, -7</position>", "<position>0.5, 2, -6</position>")
                  .replace("<fov>55</fov>", "<fov>48</fov>")
                  .replace('<emission scale="4">', '<emission scale="2.5">'))
    assert edited.count("95.5") == 1
    reference = nxrender.render(nxrender.Scene.from_text(edited, str(path)), spp=4)

    scene = nxrender.Scene(path)
    scene.objects[1].material.fluorescence.stokes_nm = 95.5
    scene.objects[3].material.reflectance = 0.4
    scene.camera.position = (0.5, 2, -6)
    scene.camera.fov = 48
    scene.objects[4].emission_scale = 2.5
    image = nxrender.render(scene, spp=4)
    assert_same_pixels(image, reference)
    assert "stokes_nm = 95.5" in image.attributes["nxrender.sceneEdits"]
    # the edits change the render key: a resume or a merge cannot mix the two scenes
    plain = nxrender.render(path, spp=1)
    assert image.attributes["nxrender.renderKey"] != plain.attributes["nxrender.renderKey"]


def test_render_key_follows_the_state(scenes):
    """The render key is made from the scene's state, not its edit log: a no-op edit or
    0.4 -> 0.3 -> 0.4 keeps the file's key (nxmerge and --resume refused equal scenes), a scene
    edited into another file's state takes that file's key, and two textures differing in one
    texel (their repr the same) have different keys."""
    path = scenes / "blacklight.scn"
    key = lambda image: image.attributes["nxrender.renderKey"]
    plain = key(nxrender.render(path, spp=1))
    scene = nxrender.Scene(path)
    scene.camera.fov = scene.camera.fov
    assert key(nxrender.render(scene, spp=1)) == plain
    for value in (0.4, 0.3, 0.9):
        scene.objects[3].material.reflectance = value
    assert scene.edits and key(nxrender.render(scene, spp=1)) == plain
    scene.objects[3].material.reflectance = 0.4
    edited = path.read_text().replace("<reflectance>0.9</reflectance>", "<reflectance>0.4</reflectance>")
    other = nxrender.Scene.from_text(edited, str(path))
    assert key(nxrender.render(scene, spp=1)) == key(nxrender.render(other, spp=1)) != plain
    texels = np.full((64, 64, 3), 0.5)
    nm = np.array([400.0, 550, 700])
    scene.set("objects[3].reflectance", (nm, texels))
    first = key(nxrender.render(scene, spp=1))
    texels[30, 30, 1] = 0.25
    assert repr(texels) == repr(np.full((64, 64, 3), 0.5))  # the log's text could not tell
    scene.set("objects[3].reflectance", (nm, texels))
    assert key(nxrender.render(scene, spp=1)) != first


def test_set_fluorescence_equals_file(scenes):
    path = scenes / "blacklight.scn"
    text = path.read_text().replace(
        "<reflectance>0.9</reflectance>",
        "<reflectance>0.9</reflectance><fluorescence><absorption>380</absorption>"
        "<stokes>120</stokes><yield>0.5</yield></fluorescence>")
    reference = nxrender.render(nxrender.Scene.from_text(text, str(path)), spp=4)
    scene = nxrender.Scene(path)
    scene.objects[3].material.set_fluorescence(absorption_nm=380, stokes_nm=120, quantum_yield=0.5)
    assert_same_pixels(nxrender.render(scene, spp=4), reference)
    scene.objects[3].material.fluorescence = None
    assert scene.objects[3].material.fluorescence is None


def test_medium_edits_equal_the_edited_file(scenes):
    """Media edited from Python render what the same media written in the file render."""
    path = scenes / "tonic_water.scn"
    water = ('<medium><sigma_a scale="0.01">water:absorption</sigma_a>'
             '<sigma_s scale="0.01">water:scattering</sigma_s></medium>')
    text = path.read_text()
    assert text.count(water) == 1
    edited = (text.replace(water, '<medium><sigma_a scale="0.02">water:absorption</sigma_a>'
                                  '<sigma_s>400:0.05, 700:0.01</sigma_s><g>0.5</g>'
                                  '<emission>0.3</emission></medium>')
                  .replace("<peak>3.4</peak>", "<peak>2</peak>")
                  .replace('<material>matte</material><reflectance>0.9</reflectance></sphere>',
                           '<material>matte</material><reflectance>0.9</reflectance><medium>'
                           '<sigma_a>0.1</sigma_a><sigma_s>0.2</sigma_s><g>0.1</g></medium>'
                           '</sphere>'))
    reference = nxrender.render(nxrender.Scene.from_text(edited, str(path)), spp=2,
                                crop=(100, 60, 140, 100))

    scene = nxrender.Scene(path)
    liquid = scene.objects[3].medium
    assert liquid.sigma_a == "water:absorption" and liquid.sigma_a_scale == 0.01
    liquid.sigma_a_scale = 0.02
    liquid.sigma_s = ([400, 700], [0.05, 0.01])
    assert liquid.sigma_s_scale is None  # a new coefficient stands alone (default scale 1)
    liquid.g = 0.5
    liquid.emission = 0.3
    scene.objects[2].medium.dye_peak = 2
    scene.objects[4].set_medium(0.1, 0.2, g=0.1)
    image = nxrender.render(scene, spp=2, crop=(100, 60, 140, 100))
    assert_same_pixels(image, reference)
    assert "medium.g = 0.5" in image.attributes["nxrender.sceneEdits"]

    with pytest.raises(ValueError, match=r"objects\[3\].medium.g: expected"):
        liquid.g = 1
    with pytest.raises(ValueError, match="set_medium: expected a sphere or a closed mesh"):
        scene.objects[0].set_medium(0.1, 0.1)
    with pytest.raises(ValueError, match="has no dye"):
        liquid.dye_peak = 1
    liquid.set_dye(absorption_nm=420, stokes_nm=60, peak=1.5)
    assert liquid.dye_peak == 1.5
    liquid.remove_dye()
    assert liquid.dye_peak is None
    scene.objects[3].medium = None
    assert scene.objects[3].medium is None


def test_material_edits_equal_the_edited_file(scenes):
    """Conductor, rough-glass and coating edits render what the same edits in the file render."""
    path = scenes / "metals.scn"
    text = path.read_text()
    replacements = [
        ("<metal>gold</metal><alpha>0.15</alpha>", "<metal>gold</metal><alpha>0.3</alpha>"),
        ("<alpha_u>0.03</alpha_u><alpha_v>0.35</alpha_v>",
         "<alpha_u>0.2</alpha_u><alpha_v>0.05</alpha_v>"),
        ("<metal>copper</metal>", "<eta>300:1.2, 1100:0.3</eta><k>3.5</k>"),
        ("<thickness>150</thickness><ior>2.3</ior>", "<thickness>90</thickness><ior>2.1</ior>"),
        ("<ior>bk7</ior><alpha>0.25</alpha>", "<ior>bk7</ior><alpha>0.4</alpha>"),
    ]
    edited = text
    for old, new in replacements:
        assert edited.count(old) == 1, old
        edited = edited.replace(old, new)
    reference = nxrender.render(nxrender.Scene.from_text(edited, str(path)), spp=2,
                                crop=(0, 40, 480, 120))

    scene = nxrender.Scene(path)
    gold, aluminium, copper, titanium, frosted = (scene.objects[i].material for i in range(2, 7))
    assert gold.metal == "gold" and gold.alpha == 0.15
    gold.alpha = 0.3
    assert aluminium.alpha_uv == (0.03, 0.35)
    aluminium.alpha_uv = (0.2, 0.05)
    copper.eta = ([300, 1100], [1.2, 0.3])
    copper.k = 3.5
    assert copper.metal is None
    assert titanium.coating == (150, 2.3)
    titanium.coating = (90, 2.1)
    frosted.alpha = 0.4
    image = nxrender.render(scene, spp=2, crop=(0, 40, 480, 120))
    assert_same_pixels(image, reference)

    with pytest.raises(ValueError, match=r"alpha: expected a GGX roughness alpha"):
        gold.alpha = 2
    with pytest.raises(ValueError, match=r"coating\[0\]: expected a coating thickness"):
        titanium.coating = (-1, 1.5)
    titanium.coating = None
    assert titanium.coating is None
    gold.metal = "platinum"  # checked when the scene is built
    with pytest.raises(nxrender.Error, match="expected a metal name"):
        nxrender.render(scene, spp=1)


def test_copy_is_independent(scenes):
    a = nxrender.Scene(scenes / "blacklight.scn")
    b = a.copy()
    b.objects[1].material.fluorescence.stokes_nm = 40
    assert a.objects[1].material.fluorescence.stokes_nm == 150
    assert a.edits == [] and len(b.edits) == 1
