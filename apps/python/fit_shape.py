#!/usr/bin/env python3
"""Recovers a mesh's shape from simulated images of a fluorescent object under several lamps
and views, with shape gradients through nxrender.torch (docs/inverse.md, "Shape from
fluorescence").

    build/nxpython apps/python/fit_shape.py [--level 4] [--steps 200] [--case all]
                                            [--figure docs/inverse-shape.png] [--check]

The object is a bumpy, non-convex blob: an icosphere (level 4: 2,562 vertices, 5,120 faces)
whose radius varies by up to +-20%; the fit starts from the round sphere of the same mesh.
It is seen from 4 views around it under 3 blue LED lamps, one at a time (12 images of 48 x 48
pixels), against a dim uniform background; the captures are renders of the true shape with
64 spp. Each step renders the 12 images at 8 spp through nxrender.torch.render (the
vertices' gradient by reverse mode, the mesh's outlines and shadows included) and takes an Adam
step (its rate falling to a tenth over the fit) on the large-steps parameterisation
u = (I + lambda L) x of the vertices (Nicolet, Jacobson and Jakob 2021: L the mesh's uniform
graph Laplacian; the system's inverse made once in torch), which smooths each step's update
instead of adding a penalty.

Cases (--case):
  dye       the object fluoresces (a dye absorbing at 455 nm, emitting around 545 nm) and the
            camera sees through a long-pass filter (bands 500-700 nm): what fluorescence
            imaging does, so that the lamps' own light is not seen;
  filtered  the same object without its dye, through the same filter: it reflects nothing the
            filter passes, so only its outline against the background is seen;
  reflected the same object without its dye, unfiltered (400-700 nm): its blue reflection.
Printed: per case the mean radial distance of the vertices from the true surface, every 20
steps, and the seconds taken.
"""

import argparse
import sys
import time

import numpy as np
import torch

import nxrender
import nxrender.torch as nxt

LED = ([430, 445, 455, 465, 480], [0, 0.5, 1, 0.5, 0])  # a blue LED, relative power
VIEWS = [(0, 0.6, -2.8), (2.8, 0.6, 0), (0, 0.6, 2.8), (-2.8, 0.6, 0)]
LAMPS = [(1.5, 2.5, -2.5), (-2.5, 1.5, -1.5), (0, -2.5, -2)]
DYE = {"absorption": 455, "stokes": 90, "width": 25, "yield": 0.8}
CASES = {"dye": (True, "500:700:50"), "filtered": (False, "500:700:50"),
         "reflected": (False, "400:700:50")}


def icosphere(level):
    """The unit icosphere: an icosahedron's faces split in four `level` times, the new
    vertices pushed onto the sphere. Returns (vertices (N, 3), faces (M, 3))."""
    t = (1 + 5 ** 0.5) / 2
    v = [np.array(p, float) / np.linalg.norm(p) for p in
         [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t),
          (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
         (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        middle = {}

        def split(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = v[a] + v[b]
                v.append(p / np.linalg.norm(p))
                middle[key] = len(v) - 1
            return middle[key]

        f = [face for a, b, c in f for face in
             ((a, split(a, b), split(c, a)), (b, split(b, c), split(a, b)),
              (c, split(c, a), split(b, c)), (split(a, b), split(b, c), split(c, a)))]
    return np.array(v), np.array(f)


def true_radius(d):
    """The blob's radius in unit direction d (rows): 0.5 with bumps of up to +-20%."""
    return 0.5 * (1 + 0.12 * np.sin(4 * d[:, 0]) * np.sin(4 * d[:, 1]) + 0.08 * np.cos(5 * d[:, 2]))


def radial_error(x):
    """Mean distance along the radius of the vertices x (N, 3) from the true surface."""
    x = np.asarray(x, float)
    r = np.linalg.norm(x, axis=1)
    return float(np.abs(r - true_radius(x / r[:, None])).mean())


def scene(vertices, faces, view, lamp, dye, bands, size=48):
    """One image's scene: the mesh seen from `view` under the lamp at `lamp`."""
    material = {"shape": "mesh", "vertices": vertices.astype(np.float32), "faces": faces,
                "material": "matte", "reflectance": 0.3}
    if dye:
        material["fluorescence"] = DYE
    return nxrender.Scene.from_dict({
        "settings": {"xres": size, "yres": size, "mode": "spectral_mcpt", "depth": 2,
                     "sampl": 8, "bands": bands, "background": 0.02},
        "camera": {"position": list(view), "look_at": [0, 0, 0], "fov": 28},
        "objects": [material],
        "lights": [{"position": list(lamp), "color": [1, 1, 1], "emission": LED,
                    "emission_scale": 2}],
    })


def laplacian(n, faces):
    """The mesh's uniform graph Laplacian D - A, dense (n, n)."""
    a = np.zeros((n, n))
    for i, j in ((0, 1), (1, 2), (2, 0)):
        a[faces[:, i], faces[:, j]] = a[faces[:, j], faces[:, i]] = 1
    return np.diag(a.sum(axis=1)) - a


def fit(case, level, steps, lam, lr, size=48, log=print):
    """Fits the vertices in `case`; returns (the found vertices, the error per 20 steps)."""
    dye, bands = CASES[case]
    unit, faces = icosphere(level)
    truth, start = unit * true_radius(unit)[:, None], 0.5 * unit
    name = "objects[0].vertices"
    scenes, captures = [], []
    for view in VIEWS:
        for lamp in LAMPS:
            scenes.append(scene(start, faces, view, lamp, dye, bands, size))
            capture = nxrender.render(scene(truth, faces, view, lamp, dye, bands, size), spp=64,
                                      seed=999, threads=2)
            captures.append(torch.from_numpy(np.array(capture.radiance, dtype=np.float64)))
    scale = float(torch.stack(captures).mean())
    m = torch.from_numpy(np.eye(len(unit)) + lam * laplacian(len(unit), faces))
    # x = (I + lambda L)^-1 u by the inverse, made once from its Cholesky factor (torch's
    # cholesky_solve differentiated through costs n^3 per step: 8 s at 2,562 vertices)
    inverse = torch.cholesky_inverse(torch.linalg.cholesky(m))
    u = (m @ torch.from_numpy(start)).clone().requires_grad_(True)
    opt = torch.optim.Adam([u], lr=lr)
    # the learning rate falls to a tenth over the fit (the images' noise then moves it less)
    decay = torch.optim.lr_scheduler.LambdaLR(opt, lambda k: 0.1 ** (k / steps))
    errors = [radial_error(start)]
    t0 = time.time()
    for step in range(steps):
        opt.zero_grad()
        x = inverse @ u
        loss = 0
        for k, (s, capture) in enumerate(zip(scenes, captures)):
            image = nxt.render(s, {name: x}, spp=8, seed=1000 * step + 2 * k, threads=2)
            loss = loss + (((image.double() - capture) / scale) ** 2).mean()
        loss.backward()
        opt.step()
        decay.step()
        if (step + 1) % 20 == 0 or step + 1 == steps:
            errors.append(radial_error((inverse @ u).detach().numpy()))
            log(f"{case:9s} step {step + 1:4d}: loss {loss.item():8.3f}, radial error "
                f"{errors[-1]:.4f} ({time.time() - t0:.0f} s)")
    return (inverse @ u).detach().numpy(), faces, truth, errors


def preview(vertices, faces, size=128):
    """A grey image of the mesh on black from a view between two of the fit's, under a white
    lamp to its upper left."""
    s = nxrender.Scene.from_dict({
        "settings": {"xres": size, "yres": size, "mode": "spectral_mcpt", "depth": 2,
                     "sampl": 128, "bands": "400:700:100"},
        "camera": {"position": [2.0, 1.4, -2.0], "look_at": [0, 0, 0], "fov": 26},
        "objects": [{"shape": "mesh", "vertices": vertices.astype(np.float32), "faces": faces,
                     "material": "matte", "reflectance": 0.6}],
        "lights": [{"position": [-1, 3, -3], "color": [1, 1, 1], "emission": "D65",
                    "emission_scale": 0.3}],
    })
    r = np.asarray(nxrender.render(s, threads=2).radiance).mean(axis=2)
    return np.clip(r / (np.percentile(r[r > 0], 99) if np.any(r > 0) else 1), 0, 1) ** (1 / 2.2)


def write_figure(path, tiles):
    """Previews side by side (the truth, the start, each case's result), 8 bits."""
    import OpenImageIO as oiio
    gap = 4
    h, w = tiles[0].shape
    big = np.ones((h, len(tiles) * (w + gap) - gap))
    for i, t in enumerate(tiles):
        big[:, i * (w + gap):i * (w + gap) + w] = t
    pixels = np.ascontiguousarray(np.round(255 * big).astype(np.uint8)[:, :, None])
    out = oiio.ImageOutput.create(path)
    if out is None or not out.open(path, oiio.ImageSpec(big.shape[1], big.shape[0], 1, "uint8")):
        raise OSError(f"{path}: cannot write the figure ({oiio.geterror()})")
    if not out.write_image(pixels):
        raise OSError(f"{path}: cannot write the figure ({out.geterror()})")
    out.close()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--level", type=int, default=4, help="icosphere level (4: 2,562 vertices)")
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--size", type=int, default=48, help="the images' width and height")
    ap.add_argument("--case", choices=["all"] + list(CASES), default="all")
    ap.add_argument("--lambda", dest="lam", type=float, default=10,
                    help="the large-steps parameterisation's lambda")
    ap.add_argument("--lr", type=float, default=0.03, help="Adam's learning rate")
    ap.add_argument("--figure", help="write previews: the truth, the start, each case's fit")
    ap.add_argument("--save", help="write the true, start and found vertices and the faces "
                                   "(.npz)")
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless the dye case's error falls to half its start")
    args = ap.parse_args()
    cases = list(CASES) if args.case == "all" else [args.case]
    previews, results, meshes = [], {}, {}
    for case in cases:
        found, faces, truth, errors = fit(case, args.level, args.steps, args.lam, args.lr,
                                          args.size)
        results[case] = errors
        meshes.update(faces=faces, truth=truth, start=0.5 * icosphere(args.level)[0])
        meshes[case] = found
        if args.figure:
            if not previews:
                previews = [preview(truth, faces), preview(0.5 * icosphere(args.level)[0], faces)]
            previews.append(preview(found, faces))
    print("radial error, start -> end:")
    for case, errors in results.items():
        print(f"  {case:9s} {errors[0]:.4f} -> {errors[-1]:.4f} ({errors[-1] / errors[0]:.0%})")
    if args.figure:
        write_figure(args.figure, previews)
    if args.save:
        np.savez(args.save, **meshes)
    if args.check and "dye" in results and not results["dye"][-1] < 0.5 * results["dye"][0]:
        print("check failed: the dye case did not halve its error", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
