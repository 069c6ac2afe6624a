"""nxrender.torch: a render as a differentiable PyTorch operation (docs/python.md, "PyTorch").

    import torch, nxrender, nxrender.torch
    scene = nxrender.Scene("scene.scn")
    q = torch.tensor(0.5, dtype=torch.float64, requires_grad=True)
    image = nxrender.torch.render(scene, {"objects[1].fluorescence.quantum_yield": q}, spp=64)
    loss = ((image - target) ** 2).mean()
    loss.backward()  # q.grad, by nxrender.backward with d loss / d image as the adjoint

Each tensor gives a parameter's numbers (Scene.numbers shows their shape: () for a number,
(n,) for a table's values or a colour, (excitation, emission) for a matrix, (height, width)
for a concentration map, (height, width, bands) for a texture). The radiance comes back as a
float32 tensor (height, width, bands). Its backward calls reverse mode with the incoming
gradient as the adjoint, on another seed than the image (grad_seed, default seed + 1): a loss
computed from the image and a gradient from the same samples would correlate their noise
(docs/inverse.md).
"""

_function = None


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
        values.append(v)
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
