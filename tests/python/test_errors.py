"""Bad input gives Python exceptions: the command line's file:line messages for scenes,
TypeError / ValueError naming the parameter for wrong arguments; never a crash."""

import re

import numpy as np
import pytest

import nxrender

BAD_SCENES = [
    "<scene>\n  <settings>\n    <xres>abc</xres>\n  </settings>\n</scene>\n",
    "<scene>\n<settings><xres>4</xres><yres>4</yres></settings>\n<camera><position>0,0,0</position>"
    "<look_at>0,0,1</look_at></camera>\n<sphere><center>0,0,5</center><radius>-1</radius>"
    "<material>matte</material></sphere>\n</scene>\n",
    "<scene>\n<settings><xres>4</xres><yres>4</yres></settings>\n<unknown/>\n</scene>\n",
    "<scene><settings>",
]


@pytest.mark.parametrize("text", BAD_SCENES)
def test_bad_scene_same_message_as_command_line(run_cli, tmp_path, text):
    path = tmp_path / "bad.scn"
    path.write_text(text)
    code, err = run_cli(path)
    assert code == 1
    cli_message = re.search(r"nxrender: error: (.*)", err).group(1)
    with pytest.raises(nxrender.Error) as info:
        nxrender.render(str(path))
    assert str(info.value) == cli_message
    assert re.match(r".*bad\.scn:\d+: ", str(info.value))
    with pytest.raises(nxrender.Error) as info:
        nxrender.Scene(path)
    assert str(info.value) == cli_message


def test_scene_text_errors_name_the_string():
    with pytest.raises(nxrender.Error, match=r"^<string>:3: "):
        nxrender.render(BAD_SCENES[0])
    with pytest.raises(nxrender.Error, match=r"^lab\.scn:3: "):
        nxrender.Scene.from_text(BAD_SCENES[0], "lab.scn")


def test_error_is_a_value_error():
    assert issubclass(nxrender.Error, ValueError)


def test_missing_files(tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.scn"):
        nxrender.render(str(tmp_path / "nope.scn"))
    with pytest.raises(FileNotFoundError, match="nope.exr"):
        nxrender.read_exr(tmp_path / "nope.exr")
    (tmp_path / "junk.exr").write_bytes(b"not an exr at all")
    with pytest.raises(nxrender.Error, match="junk.exr"):
        nxrender.read_exr(tmp_path / "junk.exr")


@pytest.mark.parametrize("kwargs, error, pattern", [
    (dict(spp="8"), TypeError, "^spp: expected an int"),
    (dict(spp=8.0), TypeError, "^spp: expected an int"),
    (dict(spp=True), TypeError, "^spp: expected an int"),
    (dict(spp=0), ValueError, r"^spp: expected an int in \[1, "),
    (dict(seed=-1), ValueError, "^seed: "),
    (dict(threads=0), ValueError, "^threads: "),
    (dict(crop=(0, 0, 10)), ValueError, "^crop: expected 4 ints"),
    (dict(crop="0,0,4,4"), TypeError, "^crop: "),
    (dict(crop=(0, 0, 1000, 10)), ValueError, r"^crop: expected \(x0, y0, x1, y1\)"),
    (dict(spp_range=(5, 5)), ValueError, "^spp_range: "),
    (dict(spp=2, spp_range=(0, 2)), ValueError, "^spp, spp_range: "),
    (dict(bands="400:300:10"), nxrender.Error, ""),
    (dict(bands=(400, 700)), ValueError, "^bands: expected 3 numbers"),
    (dict(bands="400:700:10", sensor="gaussian:500@10"), ValueError, "^bands, sensor"),
    (dict(sampler="halton"), ValueError, "^sampler: expected one of 'stratified', 'sobol', 'independent'"),
    (dict(light_sampling=3), TypeError, "^light_sampling: expected a str"),
    (dict(aovs="ids"), TypeError, "^aovs: "),
    (dict(aovs=["normal"]), ValueError, "^aovs: "),
    (dict(progress=5), TypeError, "^progress: expected a callable"),
    (dict(target_error=float("nan")), ValueError, "^target_error: "),
    (dict(error_of="chroma"), ValueError, "^error_of: expected luminance, bands or bands:LO-HI"),
    (dict(error_of="bands:700-400"), ValueError, "^error_of: expected LO <= HI"),
])
def test_bad_arguments(scenes, kwargs, error, pattern):
    with pytest.raises(error, match=pattern):
        nxrender.render(scenes / "white_floor.scn", **kwargs)


def test_bad_scene_argument():
    with pytest.raises(TypeError, match="^scene: expected"):
        nxrender.render(42)


def test_bad_edits(scenes):
    scene = nxrender.Scene(scenes / "blacklight.scn")
    f = scene.objects[1].material.fluorescence
    with pytest.raises(ValueError, match=r"^objects\[1\]\.fluorescence\.stokes_nm: expected a "
                                         r"Stokes shift in nm in \[0.0, 1000.0\], found -5.0"):
        f.stokes_nm = -5
    with pytest.raises(TypeError, match=r"^objects\[1\]\.fluorescence\.quantum_yield: expected a "
                                        "number, found str"):
        f.quantum_yield = "high"
    with pytest.raises(ValueError, match=r"^objects\[0\]\.roughness: "):
        scene.objects[0].material.roughness = 2
    with pytest.raises(ValueError, match=r"^objects\[0\]\.radius: a plane takes no radius \(a sphere(, a \w+)* or a \w+ does\)"):
        scene.objects[0].radius = 1
    with pytest.raises(ValueError, match=r"^objects\[2\]\.radius: expected a radius in \(0.0"):
        scene.objects[2].radius = 0
    with pytest.raises(ValueError, match=r"^objects\[2\]\.center: expected 3 numbers"):
        scene.objects[2].center = (1, 2)
    with pytest.raises(ValueError, match=r"^objects\[2\]\.reflectance: expected increasing"):
        scene.objects[2].material.reflectance = ([500, 400], [0.1, 0.2])
    with pytest.raises(ValueError, match=r"^objects\[2\]\.emission_scale: the object emits"):
        scene.objects[2].emission_scale = 2
    with pytest.raises(ValueError, match=r"^camera\.fov: "):
        scene.camera.fov = 180
    with pytest.raises(ValueError, match=r"^resolution: "):
        scene.resolution = (0, 10)
    with pytest.raises(nxrender.Error, match="^bands"):
        scene.bands = "700:400:10"
    with pytest.raises(TypeError, match=r"fluorescence: expected None"):
        scene.objects[1].material.fluorescence = 3
    assert scene.edits == []  # refused edits change nothing


def test_required_fields_refuse_none(scenes, tmp_path):
    # None was recorded, then the build read an empty value: a stale Stokes shift, a yield of 0.
    scene = nxrender.Scene(scenes / "blacklight.scn")
    f = scene.objects[1].material.fluorescence
    f.stokes_nm = 200
    with pytest.raises(TypeError, match=r"^objects\[1\]\.fluorescence\.stokes_nm: expected a "
                                        r"number \(the model has no default\), found None"):
        f.stokes_nm = None
    with pytest.raises(TypeError, match=r"stokes_nm: expected a number"):
        scene.set("objects[1].fluorescence.stokes_nm", None)
    assert f.stokes_nm == 200
    f.quantum_yield = None  # the model's default: allowed
    assert len(scene.edits) == 2
    eem = tmp_path / "eem.csv"
    eem.write_text("ex\\em,400,450,500,550\n350,1,5,3,1\n400,0,2,6,2\n")
    text = ("<scene><settings><xres>4</xres><yres>4</yres><mode>spectral_mcpt</mode><sampl>1</sampl>"
            "</settings><camera><position>0,0,-1</position><look_at>0,0,0</look_at></camera>"
            "<quad><origin>-1,-1,0</origin><edge_u>2,0,0</edge_u><edge_v>0,2,0</edge_v>"
            "<material>matte</material><reflectance>0.2</reflectance><fluorescence>"
            f"<eem file=\"{eem}\" rayleigh_width=\"0\"/><yield>0.6</yield><peak>0.9</peak>"
            "</fluorescence></quad></scene>")
    scene = nxrender.Scene.from_text(text, "eem.scn")
    f = scene.objects[0].material.fluorescence
    for field in ("quantum_yield", "peak_absorptance"):
        with pytest.raises(TypeError, match=rf"^objects\[0\]\.fluorescence\.{field}: expected a "
                                            rf"number \(the EEM .*eem\.csv is made absolute with "
                                            r"it\), found None"):
            setattr(f, field, None)
    assert f.quantum_yield == 0.6 and f.peak_absorptance == 0.9
    assert scene.edits == []
    nxrender.render(scene, spp=1)


def test_scene_mappings_refuse_changes(scenes):
    # They were copies: a change succeeded and did nothing (a user lost time). scene.objects
    # and scene.lights are live lists now (tests/python/test_scene_data.py); the named
    # materials and spectra are read-only mappings.
    scene = nxrender.Scene(scenes / "lab_bench.scn")
    objects = scene.objects
    n = len(objects)
    assert n > 0 and objects[0].shape and [o.shape for o in objects] == [o.shape for o in scene.objects]
    refusals = [
        lambda: scene.materials.__setitem__("new", 1), lambda: scene.materials.pop("x", None),
        lambda: scene.spectra.update({}), lambda: scene.spectra.__delitem__("x"),
    ]
    for change in refusals:
        with pytest.raises(TypeError, match=r"^scene\.(materials|spectra)\.\w+: "
                                            r"scene\.\w+ cannot be changed from Python"):
            change()
    with pytest.raises(AttributeError):
        scene.objects = []
    with pytest.raises(AttributeError):
        objects.remove(objects[0])  # no value equality of views: del objects[i]
    assert len(scene.objects) == n and scene.edits == []
    # Reading them works as before: index, iterate, names, membership.
    assert list(scene.materials) == list(scene.materials.keys())
    assert scene.materials.get("no such id") is None
    with pytest.raises(KeyError, match="scene.materials has no item 'no such id'"):
        scene.materials["no such id"]


def test_unknown_spectrum_name_fails_at_render(scenes):
    scene = nxrender.Scene(scenes / "blacklight.scn")
    scene.objects[2].material.reflectance = "no_such_spectrum"
    with pytest.raises(nxrender.Error, match=r"blacklight\.scn:\d+: .*no_such_spectrum"):
        nxrender.render(scene, spp=1)


def test_bad_image_arrays():
    with pytest.raises(TypeError, match="^radiance: expected an array of numbers"):
        nxrender.Image("pixels", wavelengths=[500])
    with pytest.raises(ValueError, match=r"^radiance: expected a non-empty array of shape"):
        nxrender.Image(np.zeros((4, 4)), wavelengths=[500])
    with pytest.raises(ValueError, match="^radiance: expected 2 bands"):
        nxrender.Image(np.zeros((2, 2, 3)), wavelengths=[500, 600])
    with pytest.raises(ValueError, match=r"^variance: expected shape \(2, 2, 2\), found \(2, 2\)"):
        nxrender.Image(np.zeros((2, 2, 2)), wavelengths=[500, 600], variance=np.zeros((2, 2)))
    with pytest.raises(ValueError, match="^wavelengths, bands: expected one of them"):
        nxrender.Image(np.zeros((2, 2, 2)))
    with pytest.raises(nxrender.Error, match="increasing"):
        nxrender.Image(np.zeros((2, 2, 2)), wavelengths=[600, 500])
    with pytest.raises(TypeError, match="^attributes: "):
        nxrender.Image(np.zeros((1, 1, 1)), wavelengths=[500], attributes=["a"])
    with pytest.raises(TypeError, match="^path: expected a file name"):
        nxrender.write_exr(3, nxrender.Image(np.zeros((1, 1, 1)), wavelengths=[500]))
    with pytest.raises(TypeError):
        nxrender.write_exr("x.exr", "not an image")


def test_image_arrays_are_not_coerced(tmp_path):
    """Values a float32 or uint32 cannot hold as they are are refused, not coerced (complex lost
    its imaginary part, 1e300 became inf, -1 became 4294967295); NaN never reaches an EXR."""
    ones = np.ones((2, 2, 1))
    with pytest.raises(TypeError, match="^radiance: expected an array of real numbers, found complex"):
        nxrender.Image(ones * (1 + 2j), wavelengths=[500])
    with pytest.raises(ValueError, match=r"^radiance: expected finite numbers in .*found 1e\+300 at row 0, column 0"):
        nxrender.Image(ones * 1e300, wavelengths=[500])
    with pytest.raises(ValueError, match="^variance: expected finite numbers in"):
        nxrender.Image(ones, wavelengths=[500], variance=-ones)
    with pytest.raises(ValueError, match=r"^sample_count: expected whole numbers in \[0, 4294967295\], found -1"):
        nxrender.Image(ones, wavelengths=[500], sample_count=-np.ones((2, 2), dtype=np.int64))
    with pytest.raises(ValueError, match="^sample_count: expected whole numbers"):
        nxrender.Image(ones, wavelengths=[500], sample_count=np.full((2, 2), 1.5))
    nan = ones.copy()
    nan[1, 0, 0] = np.nan
    with pytest.raises(ValueError, match="found nan at row 1, column 0"):
        nxrender.Image(nan, wavelengths=[500])
    # A NaN written into an image's array view is refused by the writer, and nothing written.
    image = nxrender.Image(np.ones((2, 2, 2)), wavelengths=[500, 600])
    image.radiance[0, 1, 0] = np.nan
    with pytest.raises(nxrender.Error, match="expected finite values in the spectral channels, found nan at pixel 1,0"):
        nxrender.write_exr(str(tmp_path / "nan.exr"), image)
    assert not (tmp_path / "nan.exr").exists()
    # An EXR is never written under another format's name.
    with pytest.raises(nxrender.Error, match="expected an output name ending in .exr"):
        nxrender.write_exr(str(tmp_path / "x.png"), nxrender.Image(ones, wavelengths=[500]))
    assert not (tmp_path / "x.png").exists()
    with pytest.raises(TypeError, match="expected a real number, found complex"):
        nxrender.Image(ones, wavelengths=[500 + 1j])


def test_camera_edits_are_checked_like_the_file(scenes):
    """The camera setters apply the scene build's camera checks (camera.up = (0, 0, 0) was
    accepted although the scene reader refuses it); a refused edit changes nothing."""
    scene = nxrender.Scene(scenes / "blacklight.scn")
    up = scene.camera.up
    with pytest.raises(ValueError, match=r"^camera.up: .*expected a non-zero up direction, found 0, 0, 0"):
        scene.camera.up = (0, 0, 0)
    assert scene.camera.up == up
    position, look_at = scene.camera.position, scene.camera.look_at
    view = tuple(b - a for a, b in zip(position, look_at))
    with pytest.raises(ValueError, match="expected an up direction not parallel to the view direction"):
        scene.camera.up = view
    with pytest.raises(ValueError, match="expected a look_at point different from the camera position"):
        scene.camera.look_at = position
    with pytest.raises(ValueError, match="expected focal lengths fx, fy giving fields of view of at most 179"):
        scene.camera.intrinsics = (1e-300, 1e-300, 10, 10)
    with pytest.raises(ValueError, match=r"expected focal lengths fx, fy in \(0, 1e9\]"):
        scene.camera.intrinsics = (-5, 5, 10, 10)
    assert scene.camera.intrinsics is None
    assert not any("camera" in e for e in scene.edits)
