"""nxrender.torch: a render as a differentiable PyTorch operation. Its gradients are reverse
mode's with torch's incoming gradient as the adjoint, they agree with central differences of
the loss through torch, and a loss written in torch trains a parameter through the renderer."""

import re

import numpy as np
import pytest
import torch

import nxrender
import nxrender.torch as nxt

from test_gradients import SCENE  # a fluorescent sphere, a tabulated floor, a lamp, a medium

YIELD = "objects[1].fluorescence.quantum_yield"
FLOOR = "objects[0].reflectance"


@pytest.fixture(scope="module")
def scene():
    return nxrender.Scene.from_text(SCENE, "t.scn")


def test_numbers_by_name(scene):
    assert scene.numbers(YIELD).shape == ()
    assert scene.numbers(FLOOR).tolist() == [0.3, 0.5, 0.8]
    edited = scene.copy()
    edited.set_numbers(FLOOR, [0.3, 0.6, 0.8])
    assert list(edited.get(FLOOR)[1]) == [0.3, 0.6, 0.8]
    assert edited.edits == [FLOOR + " = [0.3, 0.6, 0.8]"]
    with pytest.raises(ValueError, match=r"expected numbers of shape \(3,\), found \(2,\)"):
        edited.set_numbers(FLOOR, [0.1, 0.2])
    with pytest.raises(ValueError, match="a value outside what the parameter allows"):
        edited.set_numbers(YIELD, 2.0)
    edited.set("objects[2].emission", "D65")  # a name has no numbers
    with pytest.raises(nxrender.Error, match="not differentiable as given"):
        edited.numbers("objects[2].emission")


def test_gradient_is_reverse_mode_with_the_incoming_adjoint(scene):
    q = torch.tensor(0.8, dtype=torch.float64, requires_grad=True)
    floor = torch.tensor([0.3, 0.5, 0.8], dtype=torch.float64, requires_grad=True)
    image = nxt.render(scene, {YIELD: q, FLOOR: floor}, spp=32, seed=3, threads=2)
    assert image.dtype == torch.float32 and tuple(image.shape) == (20, 24, 7)
    plain = nxrender.render(scene, spp=32, seed=3, threads=2).radiance
    assert np.array_equal(image.detach().numpy(), plain)  # the same render
    weights = torch.linspace(0, 1, image.numel(), dtype=torch.float32).reshape(image.shape)
    (image * weights).sum().backward()
    grads, _ = nxrender.backward(scene, weights.numpy().astype(np.float64), [YIELD, FLOOR],
                                 spp=32, seed=4, threads=2)
    assert q.grad.item() == pytest.approx(grads[YIELD], rel=1e-12)
    assert np.allclose(floor.grad.numpy(), grads[FLOOR], rtol=1e-12)


@pytest.mark.parametrize("name, index, step", [(YIELD, None, 0.1), (FLOOR, 1, 0.05)])
def test_gradient_agrees_with_central_differences_through_torch(scene, name, index, step):
    # loss = sum(w * image): its gradient through torch against (loss(v + h) - loss(v - h)) / 2h
    # of renders with the same seed (the parameter is linear in the paths' weights: common
    # random numbers make the difference nearly exact), within 5 standard errors of reverse
    # mode plus 2% (the difference's own truncation and noise).
    value = torch.tensor(scene.numbers(name), dtype=torch.float64, requires_grad=True)
    rng = np.random.default_rng(1)
    w = torch.from_numpy(rng.uniform(0, 1, (20, 24, 7)).astype(np.float32))
    nxt.render(scene, {name: value}, spp=256, seed=5, grad_spp=256, threads=2).mul(w).sum().backward()
    g = value.grad.numpy() if index is None else value.grad.numpy()[index]
    _, variances = nxrender.backward(scene, w.numpy().astype(np.float64), [name], spp=256,
                                     seed=6, threads=2)
    sd = np.sqrt(variances[name] if index is None else variances[name][index])

    def loss(delta):
        v = scene.numbers(name).copy()
        if index is None:
            v = v + delta
        else:
            v[index] += delta
        with torch.no_grad():
            return nxt.render(scene, {name: torch.tensor(v)}, spp=256, seed=5,
                              threads=2).mul(w).sum().item()

    fd = (loss(step) - loss(-step)) / (2 * step)
    assert abs(g - fd) <= 5 * sd + 0.02 * abs(fd), (g, fd, sd)
    assert sd < 0.1 * abs(fd)  # the test has power: a gradient 50% off fails


def test_a_loss_in_torch_trains_the_yield_through_the_renderer(scene):
    target = torch.from_numpy(np.array(nxrender.render(scene, spp=64, seed=11, threads=2).radiance))
    q = torch.tensor(0.3, dtype=torch.float64, requires_grad=True)
    optimiser = torch.optim.Adam([q], lr=0.08)
    for step in range(25):
        optimiser.zero_grad()
        image = nxt.render(scene, {YIELD: q}, spp=16, seed=100 + 2 * step, threads=2)
        loss = (((image - target) / target.mean()) ** 2).mean()  # relative: Adam's eps is 1e-8
        loss.backward()
        optimiser.step()
        with torch.no_grad():
            q.clamp_(0.0, 1.0)
    assert abs(q.item() - 0.8) < 0.08, q.item()


def test_bad_parameters_are_refused(scene):
    with pytest.raises(TypeError, match="expected a dict"):
        nxt.render(scene, [YIELD])
    with pytest.raises(TypeError, match=r"quantum_yield: expected a torch.Tensor, found float"):
        nxt.render(scene, {YIELD: 0.5})
    with pytest.raises(ValueError, match=r"expected a tensor of shape \(3,\), found \(2,\)"):
        nxt.render(scene, {FLOOR: torch.zeros(2)})


def test_a_sphere_centre_and_radius_through_torch():
    # Shape parameters through the bridge: the centre's tensor (3,) and the radius' () get
    # reverse mode's gradient (the outline's terms included).
    from test_gradients import SHAPE
    scene = nxrender.Scene.from_text(SHAPE, "t.scn")
    centre = torch.tensor([0.1, 0.7, 0.0], dtype=torch.float64, requires_grad=True)
    radius = torch.tensor(0.5, dtype=torch.float64, requires_grad=True)
    names = ["objects[1].center", "objects[1].radius"]
    image = nxt.render(scene, {names[0]: centre, names[1]: radius}, spp=16, seed=3, threads=2)
    weights = torch.linspace(0, 1, image.numel(), dtype=torch.float32).reshape(image.shape)
    (image * weights).sum().backward()
    grads, _ = nxrender.backward(scene, weights.numpy().astype(np.float64), names, spp=16, seed=4,
                                 threads=2)
    assert np.allclose(centre.grad.numpy(), grads[names[0]], rtol=1e-12)
    assert radius.grad.item() == pytest.approx(grads[names[1]], rel=1e-12)
    assert radius.grad.item() != 0


def test_affine_is_the_scene_readers_transform_and_trains_a_rotation():
    # nxrender.torch.affine(translation, axis-angle, scale) gives the rows the scene reader
    # makes of <scale>, <rotate>, <translate>; a loss's gradient reaches the rotation angle
    # through it, and agrees with differences of renders.
    from test_gradients import BOXED, expect_agrees_over_seeds
    scene = nxrender.Scene.from_text(BOXED, "t.scn")
    name = "objects[1].transform"
    made = nxt.affine(torch.tensor([0.1, 0.6, 0.0], dtype=torch.float64),
                      torch.tensor([0.0, np.radians(25), 0.0], dtype=torch.float64))
    assert np.allclose(made.numpy(), scene.numbers(name), atol=1e-12)
    scaled = nxrender.Scene.from_text(BOXED.replace("<rotate>", "<scale>2,1,0.5</scale><rotate>"),
                                      "t.scn")
    made = nxt.affine(torch.tensor([0.1, 0.6, 0.0]), torch.tensor([0.0, np.radians(25), 0.0]),
                      torch.tensor([2.0, 1.0, 0.5]))
    assert np.allclose(made.numpy(), scaled.numbers(name), atol=1e-6)
    assert torch.allclose(nxt.affine([0, 0, 0], torch.zeros(3))[:, :3], torch.eye(3).double())
    angle = torch.tensor(np.radians(25), dtype=torch.float64, requires_grad=True)
    axis = torch.tensor([0.0, 1.0, 0.0], dtype=torch.float64)
    t = torch.tensor([0.1, 0.6, 0.0], dtype=torch.float64)
    image = nxt.render(scene, {name: nxt.affine(t, axis * angle)}, spp=32, seed=5, grad_seed=6,
                       threads=2)
    image.sum().backward()
    # the chain rule through affine: d rows / d angle . reverse mode's (3, 4)
    dm = torch.autograd.functional.jacobian(lambda a: nxt.affine(t, axis * a), angle.detach())
    grads, _ = nxrender.backward(scene, np.ones(image.shape), [name], spp=32, seed=6, threads=2)
    assert angle.grad.item() == pytest.approx(float((dm.numpy() * grads[name]).sum()), rel=1e-9)
    # and turning the box agrees with differences of renders turned by +-step
    expect_agrees_over_seeds(scene, name, scene.numbers(name), dm.numpy(), 0.05)


def test_complex_tensors_non_differentiable_names_and_huge_adjoints_are_refused(scene):
    with pytest.raises(TypeError, match=re.escape(YIELD) +
                       r": expected a real tensor, found torch.complex128"):
        nxt.render(scene, {YIELD: torch.tensor(0.8 + 0.1j, dtype=torch.complex128)}, spp=1)
    fixed = next(name for name, info in scene.parameters().items()
                 if not info["differentiable"])
    value = torch.tensor(1.0, dtype=torch.float64, requires_grad=True)
    calls = []
    with pytest.raises(ValueError, match="not differentiated"):
        nxt.render(scene, {fixed: value}, spp=1, progress=lambda d, t: calls.append(d))
    assert not calls  # refused before rendering
    floor = torch.tensor([0.3, 0.5, 0.8], dtype=torch.float64, requires_grad=True)
    image = nxt.render(scene, {FLOOR: floor}, spp=1)
    with pytest.raises(ValueError, match=r"adjoint: expected values whose products with the "
                       r"radiance stay finite.*largest magnitude is 3.4e\+38"):
        (image * 3.4e38).sum().backward()
