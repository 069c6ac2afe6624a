"""nxrender.torch: a render as a differentiable PyTorch operation (docs/python.md, "PyTorch").

    import torch, nxrender, nxrender.torch
    scene = nxrender.Scene("scene.scn")
    q = torch.tensor(0.5, dtype=torch.float64, requires_grad=True)
    image = nxrender.torch.render(scene, {"objects[1].fluorescence.quantum_yield": q}, spp=64)
    loss = ((image - target) ** 2).mean()
    loss.backward()  # q.grad, by nxrender.backward with d loss / d image as the adjoint

Each tensor gives a parameter's numbers (Scene.numbers shows their shape: () for a number,
(n,) for a table's values or a colour, (excitation, emission) for a matrix, (height, width)
for a concentration map, (height, width, bands) for a texture, (3,) for a point, (N, 3) for a
mesh's vertices, (3, 4) for an object's transform; affine() makes the last from a
translation, a rotation and a scale). The radiance comes back as a
float32 tensor (height, width, bands). Its backward calls reverse mode with the incoming
gradient as the adjoint, on another seed than the image (grad_seed, default seed + 1): a loss
computed from the image and a gradient from the same samples would correlate their noise
(docs/inverse.md).
"""

_function = None


def affine(translation, rotation=None, scale=None):
    """An object's transform as nxrender takes it (Scene.numbers of "objects[i].transform"):
    the (3, 4) rows [m | t] of p -> m p + t, with m = R diag(scale), made from tensors so that
    the gradient reaches them. translation: (3,); rotation: an axis-angle vector (3,) in
    radians (its direction the axis, its length the angle; Rodrigues' formula), None for
    none; scale: a number or (3,), None for 1. Scaled first, then turned, then moved, as
    <scale>, <rotate>, <translate> written in that order."""
    import torch

    t = torch.as_tensor(translation)
    dtype = t.dtype if t.is_floating_point() else torch.float64
    t = t.to(dtype).reshape(3)
    eye = torch.eye(3, dtype=dtype, device=t.device)
    r = eye
    if rotation is not None:
        w = torch.as_tensor(rotation).to(dtype).reshape(3)
        zero = torch.zeros((), dtype=dtype, device=t.device)
        W = torch.stack([torch.stack([zero, -w[2], w[1]]), torch.stack([w[2], zero, -w[0]]),
                         torch.stack([-w[1], w[0], zero])])
        # R = I + (sin a / a) W + ((1 - cos a) / a^2) W^2, a = |w|; near 0 by their series
        # (the other branch kept finite there, so that no NaN reaches the gradient).
        a2 = (w * w).sum()
        small = a2 < 1e-8
        a = torch.sqrt(torch.where(small, torch.ones_like(a2), a2))
        first = torch.where(small, 1 - a2 / 6, torch.sin(a) / a)
        second = torch.where(small, 0.5 - a2 / 24, (1 - torch.cos(a)) / (a * a))
        r = eye + first * W + second * (W @ W)
    m = r
    if scale is not None:
        s = torch.as_tensor(scale).to(dtype)
        m = r * (s.reshape(1, 3) if s.numel() == 3 else s.reshape(1, 1))
    return torch.cat([m, t.reshape(3, 1)], dim=1)


def render(scene, parameters, spp=None, seed=0, grad_spp=None, grad_seed=None, **options):
    """The radiance of `scene` with `parameters` ({name: tensor}) set, differentiable with
    respect to each tensor. `options` are nxrender.render's and nxrender.backward's (threads,
    bands, sensor, crop, sampler, light_sampling, light_selection, wavelength_density,
    fluorescence); grad_spp and grad_seed: the reverse pass's (default: spp, seed + 1)."""
    import torch

    if not isinstance(parameters, dict) or not parameters:
        raise TypeError("parameters: expected a dict {name: tensor} with at least one entry, "
                        f"found {type(parameters).__name__}")
    names = list(parameters)
    values = []
    for name in names:
        v = parameters[name]
        if not isinstance(v, torch.Tensor):
            raise TypeError(f"{name}: expected a torch.Tensor, found {type(v).__name__}")
        if v.is_complex():  # (its imaginary part would be dropped)
            raise TypeError(f"{name}: expected a real tensor, found {v.dtype}")
        values.append(v)
    # A tensor that asks for a gradient must name a differentiable parameter: refused here,
    # not first in backward after the forward render.
    wanted = [name for name, v in zip(names, values) if v.requires_grad]
    if wanted:
        listed = scene.parameters()
        for name in wanted:
            info = listed.get(name)
            if info is not None and not info["differentiable"]:
                raise ValueError(f"{name}: not differentiated: its declaration does not say "
                                 "differentiable (scene.parameters() marks those that are; "
                                 "docs/inverse.md); pass it without requires_grad")
    forward = {"spp": spp, "seed": seed, **options}
    backward = {"spp": grad_spp if grad_spp is not None else spp,
                "seed": grad_seed if grad_seed is not None else seed + 1, **options}
    return _render_function().apply(scene, names, forward, backward, *values)


def _render_function():
    """The autograd Function (made at first use, so that importing nxrender needs no torch)."""
    global _function
    if _function is not None:
        return _function
    import numpy as np
    import torch

    import nxrender

    class Render(torch.autograd.Function):
        @staticmethod
        def forward(ctx, scene, names, forward, backward, *values):
            edited = scene.copy()
            for name, v in zip(names, values):
                expected = edited.numbers(name).shape
                if tuple(v.shape) != expected:
                    raise ValueError(f"{name}: expected a tensor of shape {expected}, found "
                                     f"{tuple(v.shape)}")
                edited.set_numbers(name, v.detach().cpu().double().numpy())
            image = nxrender.render(edited, **forward)
            ctx.scene, ctx.names, ctx.backward = edited, names, backward
            ctx.like = [(v.shape, v.dtype, v.device) for v in values]
            device = values[0].device
            return torch.from_numpy(np.array(image.radiance, dtype=np.float32)).to(device)

        @staticmethod
        def backward(ctx, grad):
            adjoint = grad.detach().cpu().double().numpy()
            grads, _ = nxrender.backward(ctx.scene, adjoint, ctx.names, **ctx.backward)
            out = [None, None, None, None]
            for name, (shape, dtype, device) in zip(ctx.names, ctx.like):
                g = torch.as_tensor(np.asarray(grads[name], dtype=np.float64)).reshape(shape)
                out.append(g.to(dtype=dtype, device=device))
            return tuple(out)

    _function = Render
    return _function
