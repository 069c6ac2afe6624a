#!/usr/bin/env python3
"""Recovers a fluorescent sphere's position and size from a simulated capture with shape
gradients (docs/inverse.md, "Worked fits").

    build/nxpython apps/python/fit_pose.py [--spp 32] [--steps 10] [--check]

The capture is a render at the true pose with many samples: a fluorescent sphere on a floor
under a point lamp and a small blue sphere lamp. The fit starts from the sphere 0.15 to the
side, 0.1 lower, 0.2 further and 20% larger. The fit minimises
the squared difference of the images by Gauss-Newton with Levenberg-Marquardt damping; each
step's Jacobian is one forward-mode render of the four numbers' derivatives, the sphere's
outline, its shadows and its light on the floor included (docs/inverse.md, "Shape and camera").
Printed: the error per step, the values found against the truth, renders and seconds.
"""

import argparse
import sys
import time

import numpy as np

import nxrender

SCENE = """<scene><settings><xres>64</xres><yres>48</yres><mode>spectral_mcpt</mode>
<depth>4</depth><sampl>32</sampl><bands>400:700:20</bands></settings>
<camera><position>0,0.9,-2.6</position><look_at>0,0.5,0</look_at><fov>40</fov></camera>
<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>
<reflectance>0.5</reflectance></plane>
<sphere><center>0.1,0.55,0.1</center><radius>0.45</radius><material>matte</material>
<reflectance>0.3</reflectance><fluorescence><absorption>460</absorption><stokes>90</stokes>
<width>25</width><yield>0.8</yield></fluorescence></sphere>
<sphere><center>-1.2,2.2,-1.6</center><radius>0.2</radius><material>matte</material>
<reflectance>0</reflectance><emission scale="0.3" extrapolate="hold">380:1, 480:1, 520:0.05, 800:0.05</emission></sphere>
<light><position>1,3,-2</position><color>1,1,1</color><emission scale="0.02">D65</emission></light>
</scene>"""

NAMES = ["objects[1].center", "objects[1].radius"]
TRUTH = {"objects[1].center": [0.1, 0.55, 0.1], "objects[1].radius": 0.45}
START = {"objects[1].center": [0.25, 0.45, 0.3], "objects[1].radius": 0.54}


def pose_error(values):
    """The largest distance of the centre's coordinates and the radius from the truth."""
    return max(float(np.max(np.abs(np.asarray(values[n]) - np.asarray(TRUTH[n])))) for n in NAMES)


def numbers(values):
    """The pose as one vector, in NAMES' order."""
    return np.concatenate([np.atleast_1d(np.asarray(values[n], dtype=float)) for n in NAMES])


def pose_of(x):
    """The vector back as {name: value}."""
    return {"objects[1].center": x[0:3], "objects[1].radius": float(x[3])}


def at(scene, x):
    s = scene.copy()
    for name, v in pose_of(x).items():
        s.set(name, tuple(float(c) for c in v) if np.ndim(v) else float(v))
    return s


class Damped:
    """Gauss-Newton steps with Levenberg-Marquardt damping: the damping grows tenfold after a
    step that raised the cost and falls threefold otherwise."""

    def __init__(self):
        self.damping, self.cost = 1e-3, None

    def step(self, x, A, g, cost):
        """x minus the damped solution of A dx = g, A the Gauss-Newton matrix, g = J^T r."""
        if self.cost is not None and cost > self.cost:
            self.damping *= 10
        else:
            self.damping = max(self.damping / 3, 1e-6)
        self.cost = cost
        return x - np.linalg.solve(A + self.damping * np.diag(np.diag(A)), g)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless the pose is found within 0.02 scene units")
    args = ap.parse_args()
    truth = nxrender.Scene.from_text(SCENE, "pose.scn")
    capture = nxrender.render(truth, spp=32 * args.spp, seed=999).radiance.astype(np.float64)
    x = numbers(START)
    damped, renders = Damped(), 0
    start = time.perf_counter()
    for step in range(args.steps):
        # the Jacobian: one forward-mode render (all four d I / d theta); the residual: a second
        # render with another seed (a Jacobian and a residual sharing samples bias the step)
        s = at(truth, x)
        image = nxrender.render(s, spp=args.spp, seed=2 * step + 1, gradients=NAMES, threads=2)
        J = np.concatenate([np.asarray(image.gradients[n], dtype=np.float64).reshape(
            -1 if n == "objects[1].radius" else 3, capture.size).T.reshape(capture.size, -1)
            for n in NAMES], axis=1)
        r = (nxrender.render(s, spp=args.spp, seed=2 * step + 2, threads=2).radiance
             - capture).reshape(-1)
        renders += 2
        cost = float(r @ r)
        x = damped.step(x, J.T @ J, J.T @ r, cost)
        print(f"step {step}  squared error {cost:.3e}  pose error {pose_error(pose_of(x)):.4f}")
    seconds = time.perf_counter() - start
    found = pose_of(x)
    for n in NAMES:
        print(f"{n:20s} {np.round(found[n], 4)}  (truth {TRUTH[n]})")
    error = pose_error(found)
    print(f"pose error {error:.4f} scene units; {renders} renders, {seconds:.1f} s")
    return 0 if error < 0.02 or not args.check else 1


if __name__ == "__main__":
    sys.exit(main())
