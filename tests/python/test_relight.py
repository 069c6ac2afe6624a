"""Relighting from Python: render(..., relightable=True) keeps the transport per light group,
Image.relight({group: spectrum}) takes a CSV file, (wavelengths, values) or a number, gives
the same image as the nxrelight command, and refuses what it cannot relight by name."""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import nxrender

SCENE = """<scene><settings><xres>12</xres><yres>10</yres><mode>spectral_mcpt</mode>
<depth>3</depth><sampl>8</sampl><bands>400:700:20</bands></settings>
<camera><position>0,1,-5</position><look_at>0,0.5,0</look_at><fov>40</fov></camera>
<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>
<reflectance>0.6</reflectance></plane>
<sphere><center>0,0.7,0</center><radius>0.7</radius><material>matte</material>
<reflectance>0.5</reflectance><fluorescence><absorption>blue</absorption><stokes>100</stokes>
</fluorescence></sphere>
<sphere group="lamp"><center>-1.5,2.5,-1</center><radius>0.5</radius><material>matte</material>
<reflectance>0</reflectance><emission scale="2">400:1, 700:0.5</emission></sphere>
<light group="spot"><position>2,3,-2</position><color>1,1,1</color><emission>30</emission></light>
</scene>"""

LED = (np.array([380.0, 450, 500, 560, 650, 800]), np.array([0.2, 3, 0.5, 2, 1, 0.1]))


@pytest.fixture(scope="module")
def relightable():
    return nxrender.render(SCENE, relightable=True, seed=3)


def test_groups_and_the_forms_of_a_spectrum(relightable, tmp_path):
    assert relightable.relight_groups == ["lamp", "spot"]
    csv = tmp_path / "led.csv"
    csv.write_text("nm,value\n" + "".join(f"{a},{b}\n" for a, b in zip(*LED)))
    by_file = relightable.relight({"lamp": csv})
    by_table = relightable.relight({"lamp": LED})
    np.testing.assert_array_equal(by_file.radiance, by_table.radiance)
    # a flat spectrum of 0 takes the group out; the two groups' images sum to the whole
    spot_only = relightable.relight({"lamp": 0})
    lamp_only = relightable.relight({"spot": 0})
    both = relightable.relight()
    np.testing.assert_allclose(spot_only.radiance + lamp_only.radiance, both.radiance,
                               rtol=1e-5, atol=1e-12)
    assert spot_only.radiance.sum() > 0 and lamp_only.radiance.sum() > 0
    # relit to its own spectra: the render, to the grid's approximation (linear spectra here)
    np.testing.assert_allclose(both.radiance, relightable.radiance, rtol=0.02, atol=1e-9)
    assert by_file.variance is not None and np.all(by_file.variance >= 0)
    assert by_file.relight_groups == []  # an ordinary image
    # a built-in emission name, as a scene's <emission> reads it
    d65 = relightable.relight({"lamp": "D65"})
    assert d65.attributes["nxrender.relit"] == "lamp=D65"
    assert not np.array_equal(d65.radiance, both.radiance)


def test_same_image_as_the_command_line(relightable, tmp_path):
    cli = Path(os.environ["NXRENDER_CLI"]).parent / "nxrelight"
    nxrender.write_exr(tmp_path / "in.exr", relightable)
    csv = tmp_path / "led.csv"
    csv.write_text("".join(f"{a},{b}\n" for a, b in zip(*LED)))
    subprocess.run([str(cli), str(tmp_path / "in.exr"), "--light", f"lamp={csv}", "-o",
                    str(tmp_path / "out.exr")], check=True, capture_output=True)
    from_cli = nxrender.read_exr(tmp_path / "out.exr")
    in_python = relightable.relight({"lamp": csv})
    np.testing.assert_array_equal(from_cli.radiance, in_python.radiance)
    np.testing.assert_array_equal(from_cli.variance, in_python.variance)
    assert (tmp_path / "out.png").exists()
    assert from_cli.attributes["nxrender.relit"] == f"lamp={csv}"


def test_refusals(relightable, tmp_path):
    with pytest.raises(ValueError, match=r"expected a light group of the image \(lamp, spot\), "
                                         r"found 'sky'"):
        relightable.relight({"sky": 1})
    with pytest.raises(ValueError, match="expected a CSV file .* or a built-in emission name"):
        relightable.relight({"lamp": "no-such-lamp"})
    with pytest.raises(ValueError, match="expected increasing wavelengths"):
        relightable.relight({"lamp": (np.array([500.0, 400]), np.array([1.0, 1]))})
    with pytest.raises(ValueError, match="expected values >= 0"):
        relightable.relight({"lamp": (np.array([400.0, 500]), np.array([1.0, -1]))})
    # The scene's emission limit (the relit image was returned with inf in it).
    with pytest.raises(ValueError, match=r"^lights\['lamp'\]: expected an emission within \[0, "
                                         r"1e\+12\] .* found 5e\+12 at 500 nm"):
        relightable.relight({"lamp": (np.array([400.0, 500, 600]), np.array([1.0, 5e12, 1]))})
    with pytest.raises(ValueError, match=r"blackbody:100: expected an emission within"):
        relightable.relight({"lamp": "blackbody:100"})
    plain = nxrender.render(SCENE, spp=2)
    with pytest.raises(ValueError, match="expected a relightable image"):
        plain.relight({"lamp": 1})
    with pytest.raises(ValueError, match="relight_step: expected a step in nm from 0.1 to 100 that divides 5"):
        nxrender.render(SCENE, relightable=True, relight_step=3)
    with pytest.raises(ValueError, match="relight_step: only with relightable=True"):
        nxrender.render(SCENE, relight_step=5)


def test_an_image_is_never_written_over_its_own_source(relightable, tmp_path):
    # image.relight(...) written over the relightable file it came from destroyed the transport.
    src = tmp_path / "in.exr"
    nxrender.write_exr(src, relightable)
    before = src.read_bytes()
    image = nxrender.read_exr(src)
    (tmp_path / "link.exr").symlink_to(src)
    os.link(src, tmp_path / "hard.exr")
    for target in (src, tmp_path / "link.exr", tmp_path / "hard.exr", tmp_path / "." / "in.exr"):
        for written in (image, image.relight({"lamp": "D65"})):
            with pytest.raises(nxrender.Error, match="expected an output other than the file the "
                                                     r"image was read from \(.*in\.exr\)"):
                nxrender.write_exr(target, written)
        with pytest.raises(nxrender.Error, match="expected an output other than the file"):
            nxrender.write_exr(target, image, half=True)
    assert src.read_bytes() == before
    # An ENVI cube read back is not written over its header or data file either.
    header = nxrender.write_envi(tmp_path / "cube.img", image)
    cube = nxrender.read_cube(header)
    with pytest.raises(nxrender.Error, match=r"expected an output other than the file the image "
                                             r"was read from \(.*cube\.hdr\)"):
        nxrender.write_envi(tmp_path / "cube.img", cube)
    assert not [p for p in os.listdir(tmp_path) if "nxtmp" in p]
    # Anywhere else it is written, and a fresh render may replace the file.
    nxrender.write_exr(tmp_path / "relit.exr", image.relight({"lamp": "D65"}))
    nxrender.write_exr(src, nxrender.render(SCENE, spp=1))


def test_relit_components_and_the_command_line(relightable, tmp_path):
    relit = relightable.relight({"lamp": LED})
    assert sorted(relit.components) == ["fluoresced", "reflected"]
    c = relit.components
    np.testing.assert_allclose(c["reflected"] + c["fluoresced"], relit.radiance,
                               rtol=1e-5, atol=1e-12)
    assert c["fluoresced"].sum() > 0 and c["reflected"].sum() > 0
    assert np.all(relit.component_variances["fluoresced"] >= 0)
    # the command line writes the same layers
    cli = Path(os.environ["NXRENDER_CLI"]).parent / "nxrelight"
    nxrender.write_exr(tmp_path / "in.exr", relightable)
    subprocess.run([str(cli), str(tmp_path / "in.exr"), "--light", "lamp=D65", "-o",
                    str(tmp_path / "out.exr")], check=True, capture_output=True)
    from_cli = nxrender.read_exr(tmp_path / "out.exr")
    np.testing.assert_array_equal(from_cli.components["fluoresced"],
                                  relightable.relight({"lamp": "D65"}).components["fluoresced"])


NARROW = (np.array([300.0, 430, 440, 460, 470, 1100]), np.array([0.0, 0, 5, 5, 0, 0]))


def test_relight_for_forms_and_the_warning(tmp_path):
    # without targets, a narrow lamp's relit image warns with its expected noise factor
    plain = nxrender.render(SCENE, relightable=True, seed=3)
    with pytest.warns(UserWarning, match=r"light group 'lamp' relit to a spectrum much narrower "
                                         r"than what the render drew for: expected about "
                                         r"[0-9.]+x as noisy .* relight_for="):
        plain.relight({"lamp": NARROW})
    csv = tmp_path / "narrow.csv"
    csv.write_text("".join(f"{a},{b}\n" for a, b in zip(*NARROW)))
    # the forms: one spectrum for every group, a list, a dict of a spectrum or a list
    images = [nxrender.render(SCENE, relightable=True, seed=3, relight_for=form)
              for form in (NARROW, [NARROW, "D65"], {"lamp": str(csv)}, {"lamp": [csv, 1.0]})]
    for image in images:
        import warnings
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # told its target: no warning
            image.relight({"lamp": NARROW})
    # the target is in the render key (it draws other samples) and in the attributes
    assert images[0].attributes["nxrender.renderKey"] != plain.attributes["nxrender.renderKey"]
    np.testing.assert_array_equal(images[2].radiance, nxrender.render(
        SCENE, relightable=True, seed=3, relight_for={"lamp": NARROW}).radiance)
    # the command line's --relight-for gives the Python image bit for bit
    cli = os.environ["NXRENDER_CLI"]
    scene = tmp_path / "s.scn"
    scene.write_text(SCENE)
    subprocess.run([cli, "--seed", "3", "--relightable", "--relight-for", f"lamp={csv}", "-o",
                    str(tmp_path / "t.exr"), str(scene)], check=True, capture_output=True)
    np.testing.assert_array_equal(nxrender.read_exr(tmp_path / "t.exr").radiance, images[2].radiance)
    # refusals
    with pytest.raises(ValueError, match="relight_for: only with relightable=True"):
        nxrender.render(SCENE, relight_for="D65")
    with pytest.raises(ValueError, match=r"^relight_for\['sky'\]: expected a light group of the "
                                         r"scene \(lamp, spot\), found 'sky'"):
        nxrender.render(SCENE, relightable=True, relight_for={"sky": "D65"})
    with pytest.raises(ValueError, match=r"^relight_for: expected at most 8 targets"):
        nxrender.render(SCENE, relightable=True, relight_for=["D65"] * 9)
    with pytest.raises(TypeError, match=r"relight_for\[0\]\[0\]: expected a number, found an "
                                        r"array of shape \(2,\)"):
        nxrender.render(SCENE, relightable=True, relight_for=(np.zeros((3, 2)), [1, 2, 3]))
    with pytest.raises(ValueError, match=r"relight_for\[1\]: expected a spectrum with light "
                                         r"somewhere in 300-1100 nm, found 0 everywhere"):
        nxrender.render(SCENE, relightable=True, relight_for=["D65", 0])
    with pytest.raises(ValueError, match="expected a CSV file .* or a built-in emission name"):
        nxrender.render(SCENE, relightable=True, relight_for="no-such-lamp")
    bad = subprocess.run([cli, "--relight-for", "D65", str(scene)], capture_output=True, text=True)
    assert bad.returncode != 0 and "--relight-for: only with --relightable" in bad.stderr
