#!/usr/bin/env python3
"""Reads an ENVI cube written by nxrender --envi with its own header parser and numpy (no GDAL,
no nxrender code) and checks it against the EXR read by OpenImageIO: the same size, the
wavelengths and FWHMs of the EXR's sensor, and every band's pixels equal bit for bit.

    envi_readback.py CUBE.hdr CUBE.img RENDER.exr "W1,W2,..." "F1,F2,..."
"""
import re
import sys

import numpy as np
import OpenImageIO as oiio


def parse_header(path):
    text = open(path, encoding="ascii").read()
    if not text.startswith("ENVI"):
        sys.exit(f"{path}: does not start with ENVI")
    fields = {}
    for m in re.finditer(r"^\s*([^=\n]+?)\s*=\s*(\{[^}]*\}|[^\n]*)", text[4:], re.M):
        fields[m.group(1).strip().lower()] = m.group(2).strip()
    return fields


def as_list(value):
    return [v.strip() for v in value.strip("{}").split(",") if v.strip()]


def main():
    hdr, img, exr, wavelengths, fwhms = sys.argv[1:6]
    h = parse_header(hdr)
    samples, lines, bands = int(h["samples"]), int(h["lines"]), int(h["bands"])
    assert h["interleave"].lower() == "bsq", h["interleave"]
    assert int(h["data type"]) == 4, h["data type"]  # float32
    assert int(h["byte order"]) == 0, h["byte order"]  # little-endian
    assert int(h.get("header offset", "0")) == 0
    assert h["wavelength units"].lower() == "nanometers", h["wavelength units"]
    wl = [float(v) for v in as_list(h["wavelength"])]
    fw = [float(v) for v in as_list(h["fwhm"])]
    assert wl == [float(v) for v in wavelengths.split(",")], wl
    assert fw == [float(v) for v in fwhms.split(",")], fw
    cube = np.fromfile(img, dtype="<f4")
    assert cube.size == samples * lines * bands, (cube.size, samples, lines, bands)
    cube = cube.reshape(bands, lines, samples)

    buf = oiio.ImageBuf(exr)
    spec = buf.spec()
    assert (spec.width, spec.height) == (samples, lines), (spec.width, spec.height)
    pixels = buf.get_pixels(oiio.FLOAT)
    for b, w in enumerate(wl):
        name = "S0." + ("%.6f" % w).replace(".", ",") + "nm"
        channel = spec.channelnames.index(name)
        expected = pixels[:, :, channel]
        if not np.array_equal(cube[b], expected):
            sys.exit(f"band {b} ({w} nm): ENVI and EXR differ, max |d| = "
                     f"{np.abs(cube[b] - expected).max()}")
        if not expected.max() > 0:
            sys.exit(f"band {b} ({w} nm) is black: the test scene must light every band")
    print(f"ENVI cube {samples}x{lines}x{bands} matches the EXR band for band")


if __name__ == "__main__":
    main()
