#!/usr/bin/env python3
"""Fits a fluorescent dye's quantum yield to a hyperspectral capture with the nxrender module
(the last step of docs/worked-example.md).

    build/nxpython apps/python/fit_dye_yield.py SCENE.scn CAPTURE.exr --object "dye dome"

The scene's fluorescence (a model or an imported EEM) is linear in the yield Q: the radiance is
L(Q) = L0 + Q F, with L0 the render at Q = 0 and F = L1 - L0 the fluorescence at Q = 1 (light
re-radiated twice, Q^2, is neglected). The capture, in digital numbers with its black level
removed, is c_b = a_b L_b(Q) per band b, a_b the camera's unknown per-band response.

A render is noisy, and noise in a regressor biases a least-squares fit towards 0 (errors in
variables: the fit of this example read 0.42 for 0.45 from 64-sample renders). So the model is
rendered twice with independent seeds, m1 and m2, and the fit minimises the cross residual
J(Q) = sum_b w_b sum_p (c - a_b m1)(c - a_b m2), whose expectation does not hold the renders'
noise (Carroll et al., "Measurement Error in Nonlinear Models", the instrumental-variable idea),
with a_b = sum c (m1 + m2) / 2 / sum m1 m2 and w_b one pooled weight per band (1 / the mean
variance of the capture: weighting pixels by their own variance estimates is itself biased,
as a Monte Carlo value and its variance estimate are correlated). The standard error is the
delete-a-group jackknife's over 10 interleaved groups of pixels, so it holds the renders' noise
as well as the capture's.
"""

import argparse
import math
import sys

import numpy as np

import nxrender


def object_index(scene, key):
    """The index of the object named `key` (or given as a number)."""
    if key.isdigit():
        return int(key)
    names = [o.name for o in scene.objects]
    if key not in names:
        sys.exit(f"no object named {key!r} (names: {', '.join(str(n) for n in names)})")
    return names.index(key)


def cross_residual(q, model, c, w):
    """J(q) and the a_b for the two independent model renders (L0, F) in `model`."""
    (l0a, fa), (l0b, fb) = model
    m1, m2 = l0a + q * fa, l0b + q * fb
    a = (c * (m1 + m2) / 2).sum(axis=0) / (m1 * m2).sum(axis=0)
    return float((w * (c - a * m1) * (c - a * m2)).sum()), a


def fit(model, c, w, lo=0.0, hi=1.0):
    """Q in [lo, hi] minimising J (golden-section search), and J / dof there."""
    j = lambda q: cross_residual(q, model, c, w)[0]
    g = (math.sqrt(5) - 1) / 2
    a, b = lo, hi
    x1, x2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = j(x1), j(x2)
    for _ in range(60):
        if f1 < f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - g * (b - a)
            f1 = j(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + g * (b - a)
            f2 = j(x2)
    q = (a + b) / 2
    return q, j(q) / (c.size - c.shape[-1] - 1)


def jackknife(model, c, w, groups=10):
    """The fit and its delete-a-group jackknife standard error over interleaved pixel groups."""
    q, reduced = fit(model, c, w)
    pixels = np.arange(c.shape[0])
    qs = []
    for g in range(groups):
        keep = pixels % groups != g
        part = [(l0[keep], f[keep]) for l0, f in model]
        qs.append(fit(part, c[keep], w)[0])
    qs = np.array(qs)
    sigma = math.sqrt((groups - 1) / groups * ((qs - qs.mean()) ** 2).sum())
    return q, sigma, reduced


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("capture", help="spectral EXR of the capture (DN), with its variance")
    p.add_argument("--object", required=True, help="the fluorescent object: its name or index")
    p.add_argument("--black-level", type=float, default=0.0, help="DN to subtract first")
    p.add_argument("--spp", type=int, default=32)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--threads", type=int, default=None)
    p.add_argument("--check", type=float, default=None,
                   help="exit 1 unless the fit is within 4 standard errors (+0.01) of this")
    args = p.parse_args()

    scene = nxrender.Scene(args.scene)
    name = f"objects[{object_index(scene, args.object)}].fluorescence.quantum_yield"
    start = scene.get(name)
    capture = nxrender.read_exr(args.capture)
    c = np.asarray(capture.radiance, dtype=float) - args.black_level
    if capture.variance is None:
        sys.exit(f"{args.capture}: expected a capture with its variance (nxcamera writes it)")
    var_c = np.asarray(capture.variance, dtype=float)

    flat = lambda x: np.asarray(x, dtype=float).reshape(-1, c.shape[-1])
    keep = np.isfinite(c).all(axis=-1).reshape(-1)
    model = []
    for seed in (args.seed, args.seed + 1):  # two independent renders of the model
        r = []
        for q in (0.0, 1.0):
            scene.set(name, q)
            r.append(flat(nxrender.render(scene, spp=args.spp, seed=seed,
                                          threads=args.threads).radiance))
        if r[0].shape != flat(c).shape:
            sys.exit(f"{args.capture}: expected the render's size and bands, found {c.shape}")
        model.append((r[0][keep], (r[1] - r[0])[keep]))
    scene.set(name, start)
    cf, vf = flat(c)[keep], flat(var_c)[keep]
    w = 1.0 / vf.mean(axis=0)  # one pooled weight per band
    q, sigma, reduced = jackknife(model, cf, w)
    print(f"{name}: {q:.4f} +- {sigma:.4f} (scene: {start}); J / dof = {reduced:.3f} "
          f"over {int(keep.sum())} pixels x {c.shape[-1]} bands")
    if args.check is not None and not abs(q - args.check) <= 4 * sigma + 0.01:
        print(f"FAIL: expected {args.check} within 4 standard errors + 0.01")
        sys.exit(1)


if __name__ == "__main__":
    main()
