"""The worked example of docs/worked-example.md, end to end, from the lab's own files in
tests/data/lab (an OpenCV calibration, a vendor SRF, a lamp's irradiance at 500 mm, an
instrument EEM with Rayleigh and Raman lines, a PLY scan; all synthetic): render, a simulated
capture through nxcamera of a dye whose yield differs from the datasheet's, nxcompare (bands
paired by identity, regions by object name), and the yield fitted from Python."""

import csv
import pathlib
import subprocess
import sys

import nxrender
from conftest import SOURCE_DIR, nxrender_cli

LAB = SOURCE_DIR / "tests" / "data" / "lab"
SCENE = LAB / "lab_chain.scn"
TRUE_YIELD = 0.45  # the scene file says 0.6 (the datasheet)


def tool(name):
    """A program built beside nxrender."""
    return str(pathlib.Path(nxrender_cli()).parent / name)


def run(*args, cwd):
    proc = subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc


def test_from_the_lab_files_to_a_fitted_yield(tmp_path):
    # 1. The forward render, straight from the lab's files.
    p = run(nxrender_cli(), "--threads", "2", "--spp", "16", "--aov", "ids", "-o", "render.exr",
            SCENE, cwd=tmp_path)
    assert "note: the EEM" in p.stderr and "quantum yield 0.6" in p.stderr, p.stderr
    assert "36 of 701 values of" in p.stderr, p.stderr  # the lamp's dark-subtraction noise
    render = nxrender.read_exr(tmp_path / "render.exr")
    assert (render.width, render.height) == (160, 120)  # from calib.yml
    assert render.band_names == [str(nm) for nm in range(600, 976, 25)]  # the SRF's band list
    assert list(render.channel_wavelengths) == list(range(600, 976, 25))
    assert abs(render.wavelengths[0] - 600) > 3  # the side lobes pull the centroids

    # 2. The "capture": the dye at its true yield, through the camera model (black level 64).
    scene = nxrender.Scene(SCENE)
    dome = [o.name for o in scene.objects].index("dye dome")
    scene.set(f"objects[{dome}].fluorescence.quantum_yield", TRUE_YIELD)
    nxrender.write_exr(tmp_path / "truth.exr", nxrender.render(scene, spp=64, seed=11, threads=2))
    run(tool("nxcamera"), "truth.exr", "-o", "capture.exr", "--envi", "capture.img",
        "--exposure", "0.001", "--seed", "3", cwd=tmp_path)

    # 3. The comparison: the camera's ENVI cube lists the SRF's nominal centres, so bands pair
    # by identity; regions are named after the objects.
    p = run(tool("nxcompare"), "render.exr", "capture.hdr", "--scale", "band", "--labels",
            "--black-level", "64", "--region-csv", "regions.csv", "--csv", "bands.csv",
            "--plot", "compare.png", cwd=tmp_path)
    assert "paired by identity (the render's band list" in p.stdout, p.stdout
    regions = {row["region"] for row in csv.DictReader(open(tmp_path / "regions.csv"))}
    assert {"wall", "dye dome"} <= regions, regions
    bands = [row["band"] for row in csv.DictReader(open(tmp_path / "bands.csv"))]
    assert bands == render.band_names
    # The EXR capture carries the render's own sensor: paired by identity too.
    p = run(tool("nxcompare"), "render.exr", "capture.exr", "--scale", "band",
            "--black-level", "64", cwd=tmp_path)
    assert "paired by identity (the render's own sensor)" in p.stdout, p.stdout

    # 4. The fit: the true yield within its jackknife error (the scene's 0.6 far outside it).
    p = run(sys.executable, SOURCE_DIR / "apps" / "python" / "fit_dye_yield.py", SCENE,
            "capture.exr", "--object", "dye dome", "--black-level", "64", "--spp", "32",
            "--threads", "2", "--check", TRUE_YIELD, cwd=tmp_path)
    q, sigma = (float(x) for x in p.stdout.split(": ")[1].split(" (")[0].split(" +- "))
    assert abs(q - 0.6) > 10 * sigma + 0.05, p.stdout
