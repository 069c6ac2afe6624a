#!/usr/bin/env python3
"""Writes the synthetic lab files of the worked example (docs/worked-example.md): an OpenCV
calibration, a vendor SRF with side lobes and a noise floor, a lamp measured as irradiance at
500 mm with dark-subtraction noise, a spectrofluorometer EEM in counts with Rayleigh and Raman
lines, and a PLY scan. Every value is made up (fixed seeds); run it again to get the same files:

    python3 tests/data/lab/make_lab_files.py tests/data/lab
"""

import math
import sys
from pathlib import Path

import numpy as np


def calibration(out):
    # A 160 x 120 camera looking along +z from the origin (OpenCV: x right, y down), in metres.
    fx, fy, cx, cy = 210.0, 208.5, 79.5, 60.25
    dist = [-0.12, 0.03, 0.0008, -0.0005, 0.0]
    rvec, tvec = [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]

    def matrix(rows, cols, data):
        values = ", ".join(repr(float(v)) for v in data)
        return f"!!opencv-matrix\n   rows: {rows}\n   cols: {cols}\n   dt: d\n   data: [ {values} ]\n"

    text = "%YAML:1.0\n---\n"
    text += "image_width: 160\nimage_height: 120\n"
    text += "camera_matrix: " + matrix(3, 3, [fx, 0, cx, 0, fy, cy, 0, 0, 1])
    text += "distortion_coefficients: " + matrix(1, 5, dist)
    text += "rvecs: " + matrix(1, 3, rvec)
    text += "tvecs: " + matrix(1, 3, tvec)
    (out / "calib.yml").write_text(text)


def srf(out):
    # 16 bands named by nominal centre, 600-975 nm: Gaussian main lobes (FWHM 22 nm), a side lobe
    # 3% high 70 nm to the red, and a noise floor of 0.002 over the measured range.
    rng = np.random.default_rng(1)
    nm = np.arange(560.0, 1051.0, 1.0)
    centres = np.arange(600.0, 976.0, 25.0)
    sigma = 22.0 / (2 * math.sqrt(2 * math.log(2)))
    cols = []
    for c in centres:
        r = np.exp(-0.5 * ((nm - c) / sigma) ** 2) + 0.03 * np.exp(-0.5 * ((nm - c - 70) / 8) ** 2)
        r += 0.002 * rng.random(nm.size)
        cols.append(r)
    lines = ["nm," + ",".join(f"{c:g}" for c in centres)]
    for i, x in enumerate(nm):
        lines.append(f"{x:g}," + ",".join(f"{col[i]:.6f}" for col in cols))
    (out / "vendor_srf.csv").write_text("\n".join(lines) + "\n")


def lamp(out):
    # A 3000 K halogen panel behind a UV-cut diffuser (edge at 420 nm): its spectral irradiance
    # on its axis at 500 mm (W m^-2 nm^-1), 1 nm steps, dark-subtracted: noise of 0.003 around
    # an offset of -0.002 (negatives where the lamp gives almost nothing).
    rng = np.random.default_rng(2)
    nm = np.arange(350.0, 1051.0, 1.0)
    h, c, k = 6.62607015e-34, 2.99792458e8, 1.380649e-23
    lam = nm * 1e-9
    planck = 1 / (lam**5 * (np.exp(h * c / (lam * k * 3000.0)) - 1))
    cut = 1 / (1 + np.exp(-(nm - 420) / 8))
    e = 0.8 * cut * planck / planck.max() - 0.002 + 0.003 * rng.standard_normal(nm.size)
    lines = ["# 3000 K panel, irradiance on its axis at 500 mm, W m^-2 nm^-1 (synthetic)", "nm,E"]
    lines += [f"{x:g},{v:.6f}" for x, v in zip(nm, e)]
    (out / "lamp_irradiance_500mm.csv").write_text("\n".join(lines) + "\n")


def skew_cauchy(x, loc, width, skew):
    return width / (math.pi * (width**2 + (x - loc) ** 2)) * (np.arctan(skew * (x - loc) / width) / math.pi + 0.5)


def eem(out):
    # A red dye (absorption peak 560 nm, emission near 660 nm) in an instrument's grids:
    # excitation 250-600 nm in 5 nm steps, emission 300-800 nm in 2 nm steps, photon counts
    # (scale arbitrary) with first- and second-order Rayleigh lines, water Raman, Poisson noise.
    rng = np.random.default_rng(3)
    ex = np.arange(250.0, 601.0, 5.0)
    em = np.arange(300.0, 801.0, 2.0)
    a = skew_cauchy(ex, 560, 20, -10)
    a /= a.max()
    e = skew_cauchy(em, 660, 20, 10)
    e /= e.sum() * 2
    X, M = np.meshgrid(ex, em, indexing="ij")
    counts = 4e6 * a[:, None] * e[None, :]
    line = lambda centre, s: np.exp(-0.5 * ((M - centre) / s) ** 2)
    counts += 2e5 * line(X, 1.2) + 1e4 * line(2 * X, 1.2)
    counts += 800 * line(1 / (1 / X - 3400e-7), 1.5)
    counts = rng.poisson(counts).astype(float) - 5.0  # dark counts subtracted
    lines = ["ex\\em," + ",".join(f"{m:g}" for m in em)]
    for i, x in enumerate(ex):
        lines.append(f"{x:g}," + ",".join(f"{v:g}" for v in counts[i]))
    (out / "dye_eem.csv").write_text("\n".join(lines) + "\n")


def ply(out):
    # A scanned dome: a hemisphere of radius 0.08 m at (0, 0, 0.6) bulging towards the camera
    # (-z), 24 x 12 facets, with 0.5 mm of scanner noise on the radius.
    rng = np.random.default_rng(4)
    n_az, n_el = 24, 12
    verts = [(0.0, 0.0, 0.6 - 0.08)]
    for j in range(1, n_el + 1):
        el = (math.pi / 2) * j / n_el
        for i in range(n_az):
            az = 2 * math.pi * i / n_az
            r = 0.08 + (0.0005 * rng.standard_normal() if j < n_el else 0.0)
            verts.append((r * math.sin(el) * math.cos(az), r * math.sin(el) * math.sin(az),
                          0.6 - r * math.cos(el)))
    faces = [(0, 1 + (i + 1) % n_az, 1 + i) for i in range(n_az)]
    for j in range(n_el - 1):
        for i in range(n_az):
            a, b = 1 + j * n_az + i, 1 + j * n_az + (i + 1) % n_az
            c, d = a + n_az, b + n_az
            faces += [(a, b, d), (a, d, c)]
    text = "ply\nformat ascii 1.0\ncomment synthetic scan (docs/worked-example.md)\n"
    text += f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
    text += f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    text += "".join(f"{x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in verts)
    text += "".join(f"3 {a} {b} {c}\n" for a, b, c in faces)
    (out / "scan.ply").write_text(text)


if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).parent)
    for make in (calibration, srf, lamp, eem, ply):
        make(out)
