#!/usr/bin/env python3
"""Recovers a fluorescent box's pose (its transform: a translation and a rotation) from a
simulated capture with shape gradients (docs/inverse.md, "Worked fits").

    build/nxpython apps/python/fit_transform.py [--spp 64] [--steps 10] [--check]

The capture is a render at the true pose with many samples: a fluorescent box on a floor
under a point lamp and a small blue sphere lamp, turned 30 degrees about the vertical and
tilted 10 degrees about x. The fit starts 0.06 to the side, 0.05 higher and turned 8 degrees
less (from 0.12 and 15 degrees off it was still 3 cm and 15 degrees away after 8 steps). Its six numbers (translation t, axis-angle w) give the transform's rows through
nxrender.torch.affine; each Gauss-Newton step (Levenberg-Marquardt damping) takes two
forward-mode renders of the 12 rows' derivatives on independent seeds (the box's outline, its
edges and its shadows included; J1^T J2 is the unbiased estimate of J^T J) and chains them
with d rows / d (t, w) from torch, and a third render for the residual. Printed: the error per step, the
pose found against the truth, renders and seconds.
"""

import argparse
import sys
import time

import numpy as np
import torch

import nxrender
import nxrender.torch as nxt
from fit_pose import Damped

NAME = "objects[1].transform"
TRUTH = np.array([0.1, 0.45, 0.1, np.radians(10), np.radians(30), 0.0])
START = np.array([0.16, 0.5, 0.1, np.radians(10), np.radians(22), 0.0])


def rows(pose):
    """The transform's rows [m | t] for pose (t, w): turned by R(w), then moved by t."""
    p = torch.as_tensor(pose, dtype=torch.float64)
    return nxt.affine(p[:3], p[3:])


def scene_at(pose):
    return nxrender.Scene.from_dict({
        "settings": {"xres": 64, "yres": 48, "mode": "spectral_mcpt", "depth": 4, "sampl": 32,
                     "bands": "400:700:20"},
        "camera": {"position": [0, 0.9, -2.6], "look_at": [0, 0.5, 0], "fov": 40},
        "objects": [
            {"shape": "plane", "normal": [0, 1, 0], "distance": 0, "material": "matte",
             "reflectance": 0.5},
            {"shape": "box", "center": [0, 0, 0], "size": [0.5, 0.5, 0.5],
             "transform": rows(pose).numpy(), "material": "matte", "reflectance": 0.3,
             "fluorescence": {"absorption": 460, "stokes": 90, "width": 25, "yield": 0.8}},
            {"shape": "sphere", "center": [-1.2, 2.2, -1.6], "radius": 0.2, "material": "matte",
             "reflectance": 0, "emission": ([380, 480, 520, 800], [1, 1, 0.05, 0.05]),
             "emission_scale": 0.3},
        ],
        "lights": [{"position": [1, 3, -2], "color": [1, 1, 1], "emission": "D65",
                    "emission_scale": 0.02}],
    })


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless the translation is found within 0.01 and the angles "
                         "within 1 degree")
    args = ap.parse_args()
    capture = nxrender.render(scene_at(TRUTH), spp=32 * args.spp, seed=999,
                              threads=2).radiance.astype(np.float64)
    x = START.copy()
    damped, renders = Damped(), 0
    start = time.perf_counter()
    for step in range(args.steps):
        s = scene_at(x)
        # Two Jacobians on independent seeds: J1^T J2 is unbiased for J^T J, where one noisy
        # render's J^T J holds its noise's variance too (a flat mesh's edges make the per-pixel
        # derivatives noisy), which shrank every step.
        chain = torch.autograd.functional.jacobian(rows, torch.as_tensor(x)).numpy()  # (3, 4, 6)
        Js = []
        for seed in (3 * step + 1, 3 * step + 2):
            image = nxrender.render(s, spp=args.spp, seed=seed, gradients=[NAME], threads=2)
            d_rows = np.asarray(image.gradients[NAME], dtype=np.float64).reshape(12, -1)
            Js.append(d_rows.T @ chain.reshape(12, 6))
        J = 0.5 * (Js[0] + Js[1])
        r = (nxrender.render(s, spp=args.spp, seed=3 * step + 3, threads=2).radiance
             - capture).reshape(-1)
        renders += 3
        cost = float(r @ r)
        x = damped.step(x, 0.5 * (Js[0].T @ Js[1] + Js[1].T @ Js[0]), J.T @ r, cost)
        print(f"step {step}  squared error {cost:.3e}  translation error "
              f"{np.abs(x[:3] - TRUTH[:3]).max():.4f}  angle error "
              f"{np.degrees(np.abs(x[3:] - TRUTH[3:]).max()):.2f} deg")
    seconds = time.perf_counter() - start
    t_error = float(np.abs(x[:3] - TRUTH[:3]).max())
    w_error = float(np.degrees(np.abs(x[3:] - TRUTH[3:]).max()))
    print(f"translation {np.round(x[:3], 4)} (truth {TRUTH[:3]}), axis-angle "
          f"{np.round(np.degrees(x[3:]), 2)} deg (truth {np.degrees(TRUTH[3:])})")
    print(f"translation error {t_error:.4f}, angle error {w_error:.2f} deg; {renders} renders, "
          f"{seconds:.1f} s")
    return 0 if (t_error < 0.01 and w_error < 1) or not args.check else 1


if __name__ == "__main__":
    sys.exit(main())
