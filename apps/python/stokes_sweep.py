#!/usr/bin/env python3
"""A parameter sweep with the nxrender Python module: render a fluorescent sphere at a range
of Stokes shifts into a small dataset of spectral EXRs (with an index CSV), then read the
dataset back and measure where each sphere's light peaks.

    PYTHONPATH=build/python python3 apps/python/stokes_sweep.py --out sweep

The sphere (objects[1] of scenes/blacklight.scn: a dark matte sphere whose coating absorbs at
370 nm) is lit by an ultraviolet lamp, so nearly all the light it sends to the camera is
fluorescence: its peak should move with the Stokes shift, one nanometre per nanometre.
--check turns that expectation into an exit status (used by the test suite).
"""

import argparse
import csv
import pathlib
import sys

import numpy as np

import nxrender


def parse_range(text):
    start, end, step = (float(x) for x in text.split(":"))
    return list(np.arange(start, end + step / 2, step))


def render_dataset(args):
    """Renders one image per Stokes shift; returns the index rows."""
    scene = nxrender.Scene(args.scene)
    sphere = scene.objects[args.object]
    fluorescence = sphere.material.fluorescence
    if fluorescence is None:
        sys.exit(f"objects[{args.object}] of {args.scene} is not fluorescent")
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for shift in parse_range(args.shifts):
        fluorescence.stokes_nm = shift
        image = nxrender.render(scene, spp=args.spp, seed=args.seed, threads=args.threads,
                                bands=args.bands, aovs=["ids"])
        name = f"stokes_{shift:05.1f}nm.exr"
        nxrender.write_exr(out / name, image)
        rows.append({"file": name, "stokes_nm": shift, "object_id": args.object + 1})
        print(f"rendered {name}: {image.attributes['nxrender.renderSeconds']} s", flush=True)
    with open(out / "index.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=["file", "stokes_nm", "object_id"])
        writer.writeheader()
        writer.writerows(rows)
    return out


def analyse_dataset(out):
    """Reads the dataset back: the sphere's mean spectrum per image and its peak."""
    results = []
    with open(out / "index.csv", newline="") as f:
        for row in csv.DictReader(f):
            image = nxrender.read_exr(out / row["file"])
            mask = image.object_id == int(row["object_id"])
            spectrum = image.radiance[mask].mean(axis=0)
            wavelengths = image.wavelengths
            peak = wavelengths[int(np.argmax(spectrum))]
            # centroid of the emission band: the bands above half the maximum
            strong = spectrum >= 0.5 * spectrum.max()
            centroid = float((wavelengths[strong] * spectrum[strong]).sum() / spectrum[strong].sum())
            results.append((float(row["stokes_nm"]), peak, centroid, int(mask.sum())))
    print(f"{'stokes nm':>10} {'peak nm':>8} {'centroid nm':>12} {'pixels':>7}")
    for stokes, peak, centroid, pixels in results:
        print(f"{stokes:10.1f} {peak:8.1f} {centroid:12.1f} {pixels:7d}")
    shifts = np.array([r[0] for r in results])
    centroids = np.array([r[2] for r in results])
    slope, intercept = np.polyfit(shifts, centroids, 1)
    print(f"emission centroid = {slope:.3f} x Stokes shift + {intercept:.1f} nm")
    return slope, intercept


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    root = pathlib.Path(__file__).resolve().parents[2]
    parser.add_argument("--scene", default=str(root / "scenes" / "blacklight.scn"))
    parser.add_argument("--object", type=int, default=1, help="index of the fluorescent object")
    parser.add_argument("--shifts", default="60:220:20", help="Stokes shifts START:END:STEP (nm)")
    parser.add_argument("--spp", type=int, default=32)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--threads", type=int, default=None)
    parser.add_argument("--bands", default="400:700:10")
    parser.add_argument("--out", default="stokes_sweep")
    parser.add_argument("--check", action="store_true",
                        help="exit 1 unless the emission moves 0.8-1.2 nm per nm of shift")
    args = parser.parse_args()
    slope, _ = analyse_dataset(render_dataset(args))
    if args.check and not 0.8 <= slope <= 1.2:
        print(f"expected a slope near 1, found {slope:.3f}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
