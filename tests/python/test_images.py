"""read_exr / write_exr / write_envi: nxrender's files, other files of the Fichet et al.
layout, and images made from numpy arrays."""

import numpy as np
import OpenImageIO as oiio
import pytest

import nxrender


def write_with_oiio(path, channels, pixels, attributes=None):
    """An EXR written by an independent writer: float channels `channels` (names)."""
    h, w, n = pixels.shape
    spec = oiio.ImageSpec(w, h, n, oiio.FLOAT)
    spec.channelnames = tuple(channels)
    for k, v in (attributes or {}).items():
        spec.attribute(k, v)
    out = oiio.ImageOutput.create(str(path))
    assert out.open(str(path), spec)
    assert out.write_image(pixels.astype(np.float32))
    out.close()


def test_reads_command_line_file(run_cli, scenes, tmp_path):
    assert run_cli("--spp", "4", "--seed", "9", "-o", tmp_path / "r.exr",
                   scenes / "white_floor.scn")[0] == 0
    image = nxrender.read_exr(tmp_path / "r.exr")
    assert image.radiance.shape == (90, 160, 60) and image.radiance.dtype == np.float32
    np.testing.assert_allclose(image.wavelengths, np.arange(405, 1000, 10))
    np.testing.assert_allclose(image.fwhm, 10)
    assert image.bands == "405:995:10"
    assert image.variance.shape == image.radiance.shape
    assert image.sample_count.shape == (90, 160) and (image.sample_count == 4).all()
    assert image.attributes["nxrender.seed"] == "9"
    # an independent reader sees the same values
    buf = oiio.ImageBuf(str(tmp_path / "r.exr"))
    names = buf.spec().channelnames
    pixels = buf.get_pixels(oiio.FLOAT)
    for b, nm in enumerate(image.wavelengths):
        name = "S0.%snm" % ("%.6f" % nm).replace(".", ",")
        assert np.array_equal(pixels[..., names.index(name)], image.radiance[..., b])


def test_foreign_file_units_and_order(tmp_path):
    """Channels in other units and orders (nm, um with a comma, THz) are bands sorted by
    wavelength; a file without RGB gets its colour from the bands."""
    c = 299792458.0
    names = ["S0.600nm", "S0.0,5um", "S0.%sTHz" % ("%.9f" % (c / 550e-9 / 1e12)).replace(".", ","),
             "Variance.S0.600nm", "S1.500nm"]
    rng = np.random.default_rng(1)
    pixels = rng.uniform(0.1, 1.0, size=(3, 4, len(names)))
    write_with_oiio(tmp_path / "f.exr", names, pixels)
    image = nxrender.read_exr(tmp_path / "f.exr")
    np.testing.assert_allclose(image.wavelengths, [500, 550, 600], atol=1e-6)
    np.testing.assert_array_equal(image.radiance[..., 0], pixels[..., 1].astype(np.float32))
    np.testing.assert_array_equal(image.radiance[..., 1], pixels[..., 2].astype(np.float32))
    np.testing.assert_array_equal(image.radiance[..., 2], pixels[..., 0].astype(np.float32))
    assert image.attributes["nxrender.spectralChannels"] == "S0"
    assert image.rgb.shape == (3, 4, 3) and (image.rgb.sum(axis=2) > 0).all()


def test_foreign_reflective_uneven_file(tmp_path):
    """Reflective (T) channels at uneven wavelengths: Gaussian bands as wide as the spacing."""
    nms = [450, 500, 520, 600]
    pixels = np.linspace(0.1, 0.9, 2 * 2 * 4).reshape(2, 2, 4)
    write_with_oiio(tmp_path / "t.exr", ["T.%dnm" % n for n in nms], pixels)
    image = nxrender.read_exr(tmp_path / "t.exr")
    np.testing.assert_allclose(image.wavelengths, nms, atol=1e-3)
    np.testing.assert_allclose(image.fwhm, [50, 35, 50, 80], atol=1e-6)
    assert image.bands.startswith("gaussian:")
    assert image.attributes["nxrender.spectralChannels"] == "T"
    np.testing.assert_array_equal(image.radiance, pixels.astype(np.float32))


def test_file_without_spectral_channels(tmp_path):
    write_with_oiio(tmp_path / "rgb.exr", ["R", "G", "B"], np.ones((2, 2, 3)))
    with pytest.raises(nxrender.Error, match=r"rgb\.exr: expected spectral channels"):
        nxrender.read_exr(tmp_path / "rgb.exr")


def test_numpy_image_round_trip(tmp_path):
    rng = np.random.default_rng(2)
    radiance = rng.uniform(0, 2, size=(5, 7, 4))
    variance = rng.uniform(0, 0.1, size=(5, 7, 4))
    image = nxrender.Image(radiance, wavelengths=[450, 500, 550, 600], variance=variance,
                           attributes={"lab.capture": "chart 3"})
    assert image.radiance.dtype == np.float32
    nxrender.write_exr(tmp_path / "a.exr", image)
    back = nxrender.read_exr(tmp_path / "a.exr")
    np.testing.assert_array_equal(back.radiance, radiance.astype(np.float32))
    np.testing.assert_array_equal(back.variance, variance.astype(np.float32))
    np.testing.assert_array_equal(back.rgb, image.rgb)
    assert back.attributes["lab.capture"] == "chart 3"
    assert back.bands == "450:600:50"
    spec = oiio.ImageBuf(str(tmp_path / "a.exr")).spec()
    assert "S0.450,000000nm" in spec.channelnames and "R" in spec.channelnames
    assert spec.get_string_attribute("spectralLayoutVersion") == "1.0"


def test_colour_of_a_flat_spectrum():
    """XYZ of bands read as a spectrum linear between them, normalised as the renderer's: a
    flat spectrum of 1 over 360-830 nm has Y = 1 and the chromaticity of illuminant E."""
    nms = np.arange(360, 831, 10.0)
    image = nxrender.Image(np.ones((1, 1, len(nms))), wavelengths=nms)
    x, y, z = image.xyz[0, 0]
    assert y == pytest.approx(1.0, rel=1e-4)
    assert x / (x + y + z) == pytest.approx(1 / 3, abs=2e-4)
    assert y / (x + y + z) == pytest.approx(1 / 3, abs=2e-4)


def test_views_share_the_image():
    image = nxrender.Image(np.zeros((2, 3, 2)), wavelengths=[500, 600])
    view = image.radiance
    view[1, 2, 0] = 7
    assert image.radiance[1, 2, 0] == 7
    del image
    assert view[1, 2, 0] == 7  # the view keeps the image alive


def test_envi_export(tmp_path):
    radiance = np.arange(2 * 3 * 4, dtype=np.float32).reshape(2, 3, 4)
    image = nxrender.Image(radiance, wavelengths=[400, 410, 420, 430])
    header = nxrender.write_envi(tmp_path / "c.img", image)
    text = open(header).read()
    assert "wavelength" in text and "430" in text
    data = np.fromfile(tmp_path / "c.img", dtype=np.float32).reshape(4, 2, 3)  # BSQ
    np.testing.assert_array_equal(np.moveaxis(data, 0, 2), radiance)


def test_half_float_write(tmp_path):
    image = nxrender.Image(np.full((1, 2, 2), 0.5), wavelengths=[500, 600])
    nxrender.write_exr(tmp_path / "h.exr", image, half=True)
    assert oiio.ImageBuf(str(tmp_path / "h.exr")).spec().format == oiio.HALF
    big = nxrender.Image(np.full((1, 2, 2), 1e6), wavelengths=[500, 600])
    with pytest.raises(nxrender.Error):
        nxrender.write_exr(tmp_path / "h2.exr", big, half=True)
    assert not (tmp_path / "h2.exr").exists()


def test_read_cube_envi_and_png_stack(tmp_path):
    """Captures as nxcompare reads them: an ENVI cube written by write_envi comes back with its
    wavelengths and FWHM; a directory of 16-bit PNGs with the wavelengths given."""
    radiance = np.random.default_rng(3).uniform(0, 1, size=(4, 5, 3)).astype(np.float32)
    image = nxrender.Image(radiance, bands="gaussian:450,550,650@20")
    nxrender.write_envi(tmp_path / "cap.img", image)
    cube = nxrender.read_cube(tmp_path / "cap.hdr")
    np.testing.assert_array_equal(cube.radiance, radiance)
    np.testing.assert_allclose(cube.wavelengths, [450, 550, 650], atol=1e-6)
    np.testing.assert_allclose(cube.fwhm, 20, atol=1e-6)
    assert "ENVI" in cube.attributes["nxrender.cubeFormat"]

    stack = tmp_path / "stack"
    stack.mkdir()
    stored = (radiance * 60000).astype(np.uint16)
    for b in range(3):
        buf = oiio.ImageBuf(oiio.ImageSpec(5, 4, 1, oiio.UINT16))
        buf.set_pixels(oiio.ROI(), stored[..., b:b + 1])
        assert buf.write(str(stack / f"band_{b + 1}.png"))
    cube = nxrender.read_cube(stack, wavelengths=[500, 600, 700], fwhm=10)
    np.testing.assert_array_equal(cube.radiance, stored.astype(np.float32))
    np.testing.assert_allclose(cube.wavelengths, [500, 600, 700], atol=1e-6)
    with pytest.raises(nxrender.Error, match="wavelength"):
        nxrender.read_cube(stack)


def test_write_exr_takes_the_command_lines_compression(scenes, tmp_path):
    image = nxrender.render(str(scenes / "thesis.scn"), spp=2, aovs=["components"])
    sizes = {}
    for compression in (None, "zip", "piz"):
        path = tmp_path / f"{compression}.exr"
        nxrender.write_exr(path, image, half=True, compression=compression, zip_level=6)
        back = nxrender.read_exr(path)
        # lossless: the half floats come back as written
        np.testing.assert_array_equal(back.radiance, image.radiance.astype(np.float16))
        sizes[compression] = path.stat().st_size
    assert sizes["zip"] < sizes[None]
    with pytest.raises(ValueError, match="zipp"):
        nxrender.write_exr(tmp_path / "x.exr", image, compression="zipp")
    with pytest.raises(ValueError, match="zip_level"):
        nxrender.write_exr(tmp_path / "x.exr", image, compression="zip", zip_level=10)
