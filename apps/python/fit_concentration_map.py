#!/usr/bin/env python3
"""Recovers a fluorescent dye's concentration map (32 x 32 values on a card) from a simulated
hyperspectral capture with reverse-mode gradients (docs/inverse.md).

    build/nxpython apps/python/fit_concentration_map.py [--iterations 60] [--check]

The card fluoresces (the parametric model) with a concentration map k(u, v) in [0, 1] scaling
its dye's absorptance; the capture is a render with the true map (a disc and a bar on a faint
background) at many samples. The fit minimises the squared difference of renders and capture
over pixels and bands by Adam (Kingma & Ba 2015) on the 1024 values, clipped to [0, 1]. Each
iteration is two renders: the image (for the residual) and nxrender.backward with the
adjoint 2 (image - capture) and another seed, whose gradient is then unbiased for the
noise-free loss's (the image's noise is independent of the gradient's). By differences the
same gradient needs two renders per value: 2048 per iteration. Printed: the map's RMS error
against the truth as the fit goes, renders and seconds, and the difference route's estimate.
"""

import argparse
import sys
import time

import numpy as np

import nxrender

SCENE = """<scene><settings><xres>64</xres><yres>64</yres><mode>spectral_mcpt</mode>
<depth>3</depth><sampl>16</sampl><bands>400:700:50</bands></settings>
<camera><position>0,0.5,-1.65</position><look_at>0,0.5,0</look_at><fov>40</fov></camera>
<quad><origin>-0.6,-0.1,0</origin><edge_u>1.2,0,0</edge_u><edge_v>0,1.2,0</edge_v>
<material>matte</material><reflectance>0.4</reflectance><fluorescence><absorption>460</absorption>
<stokes>90</stokes><width>25</width><yield>0.8</yield></fluorescence></quad>
<sphere><center>-0.6,1.6,-1.4</center><radius>0.35</radius><material>matte</material>
<reflectance>0</reflectance>
<emission scale="5e-2" extrapolate="hold">380:1, 480:1, 520:0.1, 800:0.1</emission></sphere>
</scene>"""

NAME = "objects[0].fluorescence.concentration"


def true_map(n=32):
    """A disc and a bar on a faint background."""
    y, x = np.mgrid[0:n, 0:n] / (n - 1.0)
    k = np.full((n, n), 0.1)
    k[(x - 0.35) ** 2 + (y - 0.4) ** 2 < 0.2 ** 2] = 0.9
    k[(x > 0.6) & (x < 0.85) & (y > 0.2) & (y < 0.85)] = 0.6
    return k


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--iterations", type=int, default=60)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--figure", help="write the true and the recovered map side by side (PNG)")
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless the map's RMS error falls below a third of the start's")
    args = ap.parse_args()
    scene = nxrender.Scene.from_text(SCENE, "card.scn")
    truth = true_map()
    scene.set(NAME, truth)
    capture = nxrender.render(scene, spp=32 * args.spp, seed=999).radiance.astype(np.float64)
    k = np.full_like(truth, 0.5)
    m, v = np.zeros_like(k), np.zeros_like(k)
    rate, beta1, beta2 = 0.03, 0.9, 0.999
    renders, seconds = 0, 0.0
    start_error = float(np.sqrt(np.mean((k - truth) ** 2)))
    print(f"start: RMS error of the map {start_error:.4f}")
    plain_seconds = None
    for it in range(1, args.iterations + 1):
        scene.set(NAME, k)
        t = time.perf_counter()
        image = nxrender.render(scene, spp=args.spp, seed=2 * it).radiance.astype(np.float64)
        t_render = time.perf_counter() - t
        plain_seconds = t_render if plain_seconds is None else min(plain_seconds, t_render)
        adjoint = 2 * (image - capture)
        grads, _ = nxrender.backward(scene, adjoint.astype(np.float32), [NAME], spp=args.spp,
                                     seed=2 * it + 1)
        seconds += time.perf_counter() - t
        renders += 2
        g = grads[NAME]
        m = beta1 * m + (1 - beta1) * g
        v = beta2 * v + (1 - beta2) * g * g
        step = rate * (m / (1 - beta1 ** it)) / (np.sqrt(v / (1 - beta2 ** it)) + 1e-12)
        k = np.clip(k - step, 0.0, 1.0)
        if it % 10 == 0 or it == args.iterations:
            error = float(np.sqrt(np.mean((k - truth) ** 2)))
            print(f"iteration {it:3d}: RMS error of the map {error:.4f}  ({renders} renders, "
                  f"{seconds:.1f} s)")
    error = float(np.sqrt(np.mean((k - truth) ** 2)))
    print(f"gradients: {renders} renders, {seconds:.1f} s; by differences the same iterations "
          f"would take {2 * k.size * args.iterations + args.iterations} renders, about "
          f"{(2 * k.size + 1) * args.iterations * plain_seconds / 3600:.1f} h")
    if args.figure:
        import OpenImageIO as oiio
        side = np.concatenate([truth, np.ones((truth.shape[0], 2)), k], axis=1)
        big = np.kron(side, np.ones((6, 6)))
        out = oiio.ImageOutput.create(args.figure)
        out.open(args.figure, oiio.ImageSpec(big.shape[1], big.shape[0], 1, "uint8"))
        out.write_image(np.ascontiguousarray(np.round(255 * big).astype(np.uint8)[:, :, None]))
        out.close()
    return 0 if (error < start_error / 3 or not args.check) else 1


if __name__ == "__main__":
    sys.exit(main())
