"""Differentiated renders from Python: render(gradients=[names]) gives d radiance / d parameter
per name (a number, or one image per knot or channel) agreeing with a central difference of
renders with the same seed; backward(scene, adjoint, names) gives the adjoint-weighted sum of
those images; what is not differentiated is refused by name."""

import numpy as np
import pytest

import nxrender

SCENE = """<scene><settings><xres>24</xres><yres>20</yres><mode>spectral_mcpt</mode>
<depth>8</depth><sampl>64</sampl><bands>400:700:50</bands></settings>
<camera><position>0,0.9,-2.6</position><look_at>0,0.5,0</look_at><fov>40</fov></camera>
<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>
<reflectance>300:0.3, 550:0.5, 1100:0.8</reflectance></plane>
<sphere><center>0,0.7,0</center><radius>0.7</radius><material>matte</material>
<reflectance>0.4</reflectance><fluorescence><absorption>460</absorption><stokes>90</stokes>
<width>25</width><yield>0.8</yield></fluorescence></sphere>
<sphere><center>1.3,0.4,0.5</center><radius>0.4</radius><material>interface</material>
<medium><sigma_a>0.5</sigma_a><sigma_s>1</sigma_s></medium></sphere>
<sphere><center>-1.5,2.5,-1</center><radius>0.5</radius><material>matte</material>
<reflectance>0</reflectance>
<emission scale="5e-3" extrapolate="hold">380:1, 480:1, 520:0.1, 800:0.1</emission></sphere>
<light><position>1,3,-2</position><color>1,1,1</color><emission scale="0.02">D65</emission></light>
</scene>"""


@pytest.fixture(scope="module")
def scene():
    return nxrender.Scene.from_text(SCENE, "t.scn")


def difference(scene, name, value, step, spp=64, seed=5):
    """(I(value + step) - I(value - step)) / (2 step), same seed."""
    images = []
    for v in (value + step, value - step):
        s = scene.copy()
        s.set(name, v)
        images.append(nxrender.render(s, spp=spp, seed=seed, threads=2).radiance.astype(np.float64))
    return (images[0] - images[1]) / (2 * step)


def expect_agrees(gradient, fd, power=0.05):
    """Per band: the mean over pixels of gradient - difference within 5 standard errors, and
    the strongest band resolved to `power` of its gradient."""
    d = (gradient.astype(np.float64) - fd).reshape(-1, gradient.shape[-1])
    g = gradient.reshape(-1, gradient.shape[-1]).mean(axis=0)
    se = d.std(axis=0, ddof=1) / np.sqrt(d.shape[0])
    rounding = 1e-5 * np.abs(fd).reshape(-1, fd.shape[-1]).mean(axis=0)
    assert np.all(np.abs(d.mean(axis=0)) <= 5 * se + rounding), (d.mean(axis=0), se, g)
    k = int(np.argmax(np.abs(g)))
    assert se[k] < power * abs(g[k]), (se[k], g[k])


@pytest.mark.parametrize(
    "name, value, step, spp",
    [
        ("objects[1].fluorescence.quantum_yield", 0.8, 0.15, 256),
        ("objects[3].emission_scale", 5e-3, 5e-4, 64),
        ("lights[0].emission_scale", 0.02, 0.002, 64),
        ("objects[2].medium.sigma_a", 0.5, 0.05, 64),
    ],
)
def test_forward_matches_difference(scene, name, value, step, spp):
    image = nxrender.render(scene, spp=spp, seed=5, threads=2, gradients=[name])
    g = image.gradients[name]
    assert g.shape == image.radiance.shape and g.dtype == np.float32
    assert image.gradient_variances[name].shape == g.shape
    expect_agrees(g, difference(scene, name, value, step, spp))
    assert "gradient.0=" + name in image.attributes["nxrender.gradients"]
    assert not image.components  # gradients are not component layers


def test_spectrum_knots(scene):
    # A tabulated reflectance: one gradient image per knot (a hat function each).
    name = "objects[0].reflectance"
    image = nxrender.render(scene, spp=64, seed=5, threads=2, gradients=[name])
    g = image.gradients[name]
    assert g.shape == (3,) + image.radiance.shape
    nm, values = scene.get(name)
    for j in (1, 2):
        s_plus, s_minus = scene.copy(), scene.copy()
        v = np.array(values, dtype=float)
        v[j] += 0.02
        s_plus.set(name, (nm, v))
        v[j] -= 0.04
        s_minus.set(name, (nm, v))
        fd = (
            nxrender.render(s_plus, spp=64, seed=5, threads=2).radiance.astype(np.float64)
            - nxrender.render(s_minus, spp=64, seed=5, threads=2).radiance
        ) / 0.04
        expect_agrees(g[j], fd)


def held_table(values):
    """The scene with the floor's table held beyond its ends (extrapolate="hold")."""
    table = ", ".join(f"{nm}:{v!r}" for nm, v in zip((400, 550, 700), values))
    return nxrender.Scene.from_text(SCENE.replace(
        "<reflectance>300:0.3, 550:0.5, 1100:0.8",
        f'<reflectance extrapolate="hold">{table}'), "t.scn")


def test_held_table_knots_keep_their_extrapolation():
    # A table's numbers are moved in place: extrapolate="hold" stays, so the derivative is the
    # held table's (the end knot's hat extends over the held range), against differences of
    # the held scene written as text.
    name = "objects[0].reflectance"
    image = nxrender.render(held_table((0.3, 0.5, 0.8)), spp=64, seed=5, threads=2,
                            gradients=[name])
    g = image.gradients[name]
    assert g.shape == (3,) + image.radiance.shape
    for j in (0, 2):
        plus, minus = [0.3, 0.5, 0.8], [0.3, 0.5, 0.8]
        plus[j] += 0.02
        minus[j] -= 0.02
        fd = (
            nxrender.render(held_table(plus), spp=64, seed=5, threads=2).radiance.astype(np.float64)
            - nxrender.render(held_table(minus), spp=64, seed=5, threads=2).radiance
        ) / 0.04
        expect_agrees(g[j], fd)


DYE_SPECTRA = SCENE.replace(
    "<fluorescence><absorption>460</absorption><stokes>90</stokes>\n<width>25</width>"
    "<yield>0.8</yield></fluorescence>",
    "<fluorescence><absorptance>400:0.1, 450:0.8, 500:0.1</absorptance>"
    "<emission>480:0, 540:1, 600:0.3, 700:0</emission><yield>0.8</yield></fluorescence>")


@pytest.mark.parametrize("name, j", [("objects[1].fluorescence.emission", 2),
                                     ("objects[1].fluorescence.absorptance", 1)])
def test_dye_spectra_knots(name, j):
    # A dye given by its absorptance and emission spectra (the separable form): one gradient
    # image per knot of either spectrum, against differences of renders with the knot moved.
    scene = nxrender.Scene.from_text(DYE_SPECTRA, "t.scn")
    assert DYE_SPECTRA != SCENE
    image = nxrender.render(scene, spp=256, seed=5, threads=2, gradients=[name])
    g = image.gradients[name]
    nm, values = scene.get(name)
    assert g.shape == (len(values),) + image.radiance.shape
    renders = []
    for step in (0.05, -0.05):
        s = scene.copy()
        v = np.array(values, dtype=float)
        v[j] += step
        s.set(name, (nm, v))
        renders.append(nxrender.render(s, spp=256, seed=5, threads=2).radiance.astype(np.float64))
    expect_agrees(g[j], (renders[0] - renders[1]) / 0.1, power=0.05)


def test_backward_is_the_adjoint_weighted_forward_sum(scene):
    names = ["objects[1].fluorescence.stokes_nm", "objects[0].reflectance"]
    image = nxrender.render(scene, spp=16, seed=9, threads=2, gradients=names)
    rng = np.random.default_rng(1)
    adjoint = rng.normal(size=image.radiance.shape).astype(np.float32)
    grads, variances = nxrender.backward(scene, adjoint, names, spp=16, seed=9, threads=2)
    for name in names:
        expected = np.tensordot(image.gradients[name].astype(np.float64), adjoint, axes=3)
        assert np.allclose(grads[name], expected, rtol=2e-4, atol=0), (name, grads[name], expected)
        assert np.all(np.asarray(variances[name]) > 0)
    assert isinstance(grads[names[0]], float) and grads[names[1]].shape == (3,)
    # the thread count does not change it
    again, _ = nxrender.backward(scene, adjoint, names, spp=16, seed=9, threads=1)
    assert again[names[0]] == grads[names[0]]


def test_refusals(scene):
    with pytest.raises(ValueError, match=r"objects\[0\].normal: not differentiated"):
        nxrender.render(scene, spp=1, gradients=["objects[0].normal"])
    with pytest.raises(ValueError, match=r"objects\[1\].radius: derivatives with respect to "
                                         r"shape do not cover a scene with media"):
        nxrender.render(scene, spp=1, gradients=["objects[1].radius"])
    with pytest.raises(ValueError, match=r"camera.up: not differentiated"):
        nxrender.render(scene, spp=1, gradients=["camera.up"])
    with pytest.raises(KeyError, match="no scene parameter named"):
        nxrender.render(scene, spp=1, gradients=["objects[9].reflectance"])
    with pytest.raises(ValueError, match="lights\\[0\\].emission: not differentiable as given"):
        nxrender.render(scene, spp=1, gradients=["lights[0].emission"])  # a named spectrum
    with pytest.raises(ValueError, match="adjoint: expected shape \\(20, 24, 7\\), found \\(3, 3, 7\\)"):
        nxrender.backward(scene, np.zeros((3, 3, 7)), ["objects[1].reflectance"], spp=1)
    # The adjoint as image arrays are taken: real numbers float32 keeps, or refused (complex
    # lost its imaginary part; str, bool and object arrays were cast; 1e-50 became 0; 1e39 was
    # "not finite").
    names = ["objects[1].reflectance"]
    ones = np.ones((20, 24, 7))
    for bad, error, pattern in (
            (ones * (1 + 1j), TypeError, "adjoint: expected an array of real numbers, found complex"),
            (ones.astype(str), TypeError, "adjoint: expected an array of numbers, found"),
            (ones.astype(bool), TypeError, "adjoint: expected an array of numbers, found"),
            (ones.astype(object), TypeError, "adjoint: expected an array of numbers, found"),
            (np.where(np.arange(20 * 24 * 7).reshape(20, 24, 7) == 8, 1e-50, 1.0), ValueError,
             r"adjoint: expected 0 or a magnitude of at least 1.4e-45 \(what float32 stores\), "
             r"found 1e-50 at row 0, column 1"),
            (ones * 1e39, ValueError, r"adjoint: expected finite numbers in \[-3.40282\d*e\+38, "
             r"3.40282\d*e\+38\].*found 1e\+39 at row 0, column 0")):
        with pytest.raises(error, match=pattern):
            nxrender.backward(scene, bad, names, spp=1)
    with pytest.raises(ValueError, match=r"adjoint: only with gradients=\[names\]"):
        nxrender.render(scene, spp=1, adjoint=ones)
    with pytest.raises(Exception, match="gradients cannot be combined"):
        nxrender.render(scene, spp=1, gradients=["objects[1].reflectance"], aovs=["components"])
    # a rough dielectric's roughness is refused by the scene's tables; a rough metal's is not
    for material, refused in (("<material>glass</material><alpha>0.2</alpha>", True),
                              ("<material>conductor</material><metal>gold</metal><alpha>0.2</alpha>", False)):
        s = nxrender.Scene.from_text(
            SCENE.replace("<material>interface</material>", material).replace(
                "<medium><sigma_a>0.5</sigma_a><sigma_s>1</sigma_s></medium>", ""), "t.scn")
        if refused:
            with pytest.raises(ValueError, match="roughness of a dielectric"):
                nxrender.render(s, spp=1, gradients=["objects[2].alpha"])
        else:
            image = nxrender.render(s, spp=4, gradients=["objects[2].alpha"])
            assert np.any(image.gradients["objects[2].alpha"] != 0)


CARD = """<scene><settings><xres>24</xres><yres>20</yres><mode>spectral_mcpt</mode>
<depth>5</depth><sampl>32</sampl><bands>400:700:50</bands></settings>
<camera><position>0,0.5,-2.4</position><look_at>0,0.5,0</look_at><fov>40</fov></camera>
<quad><origin>-0.6,0,0</origin><edge_u>1.2,0,0</edge_u><edge_v>0,1.2,0</edge_v>
<material>matte</material><reflectance>0.5</reflectance></quad>
<sphere><center>-1.5,2.5,-1</center><radius>0.5</radius><material>matte</material>
<reflectance>0</reflectance>
<emission scale="5e-3" extrapolate="hold">380:1, 480:1, 520:0.1, 800:0.1</emission></sphere>
</scene>"""


def test_texture_texels():
    # A spectral texture's every value (texel x band): bilinear in space, linear between bands.
    s = nxrender.Scene.from_text(CARD, "t.scn")
    rng = np.random.default_rng(3)
    texels = rng.uniform(0.2, 0.8, size=(4, 4, 3))
    nm = np.array([400.0, 550, 700])
    name = "objects[0].reflectance"
    s.set(name, (nm, texels))
    image = nxrender.render(s, spp=32, seed=4, threads=2, gradients=[name])
    g = image.gradients[name]
    assert g.shape == (4, 4, 3) + image.radiance.shape
    for ty, tx, b in [(1, 2, 1), (3, 0, 0), (0, 3, 2)]:
        images = []
        for d in (0.02, -0.02):
            t = texels.copy()
            t[ty, tx, b] += d
            s2 = s.copy()
            s2.set(name, (nm, t))
            images.append(nxrender.render(s2, spp=32, seed=4, threads=2).radiance.astype(np.float64))
        expect_agrees(g[ty, tx, b], (images[0] - images[1]) / 0.04)
    adjoint = rng.normal(size=image.radiance.shape).astype(np.float32)
    grads, _ = nxrender.backward(s, adjoint, [name], spp=32, seed=4, threads=2)
    expected = np.tensordot(g.astype(np.float64), adjoint, axes=([3, 4, 5], [0, 1, 2]))
    assert grads[name].shape == (4, 4, 3)
    assert np.allclose(grads[name], expected, rtol=1e-4, atol=1e-6 * np.abs(expected).max())


def test_concentration_map():
    # A surface dye's concentration map: set and read as numbers, checked, recorded; its
    # gradient (one value per texel) by reverse mode equals the adjoint-weighted forward images.
    text = CARD.replace(
        "<reflectance>0.5</reflectance></quad>",
        "<reflectance>0.4</reflectance><fluorescence><absorption>460</absorption><stokes>90"
        "</stokes><yield>0.8</yield></fluorescence></quad>")
    s = nxrender.Scene.from_text(text, "t.scn")
    name = "objects[0].fluorescence.concentration"
    assert name in s.parameters() and s.get(name) is None
    k = np.linspace(0.1, 0.9, 12).reshape(3, 4)
    s.set(name, k)
    assert np.allclose(s.get(name), k) and s.get(name).dtype == np.float32
    assert any(e.startswith(name + " = <map 3x4") for e in s.edits)
    with pytest.raises(ValueError, match=r"expected concentrations in \[0, 1\].*found 1.5 at row 0, column 1"):
        s.set(name, [[0.5, 1.5]])
    with pytest.raises(ValueError, match="expected values\\[height, width\\]"):
        s.set(name, [0.5, 0.5])
    image = nxrender.render(s, spp=8, seed=2, threads=2, gradients=[name])
    g = image.gradients[name]
    assert g.shape == (3, 4) + image.radiance.shape
    rng = np.random.default_rng(5)
    adjoint = rng.normal(size=image.radiance.shape).astype(np.float32)
    grads, _ = nxrender.backward(s, adjoint, [name], spp=8, seed=2, threads=2)
    expected = np.tensordot(g.astype(np.float64), adjoint, axes=([2, 3, 4], [0, 1, 2]))
    assert np.allclose(grads[name], expected, rtol=1e-4, atol=1e-6 * np.abs(expected).max())
    s.set(name, None)
    assert s.get(name) is None


def test_measured_matrix_cells(scene):
    # A measured Donaldson matrix's cells (its diagonal: the elastic reflectance; above it:
    # re-radiation), each resampled bilinearly onto the 5 nm grid: sparse tangents per cell.
    s = scene.copy()
    ex = np.array([400.0, 430, 460, 490])
    em = np.array([400.0, 430, 460, 490, 520, 550, 580, 610])
    v = np.zeros((4, 8))
    for i in range(4):
        v[i, i] = 0.3
        v[i, i + 1:] = 0.02 * np.exp(-((em[i + 1:] - ex[i] - 90) / 40) ** 2)
    s.objects[1].material.set_fluorescence_matrix(ex, em, v)
    name = "objects[1].fluorescence.matrix"
    image = nxrender.render(s, spp=64, seed=5, threads=2, gradients=[name])
    g = image.gradients[name]
    assert g.shape == (4, 8) + image.radiance.shape
    for i, j in [(1, 5), (2, 2)]:
        images = []
        for d in (0.005, -0.005):
            v2 = v.copy()
            v2[i, j] += d
            s2 = s.copy()
            s2.objects[1].material.set_fluorescence_matrix(ex, em, v2)
            images.append(nxrender.render(s2, spp=64, seed=5, threads=2).radiance.astype(np.float64))
        expect_agrees(g[i, j], (images[0] - images[1]) / 0.01)


def test_the_declarations_say_which_parameters_are_differentiable(scenes):
    """parameters() reports each parameter's declared `differentiable`, and a gradient request
    follows it: appearance parameters, a sphere's centre and radius and the camera's pose and
    field of view are; other geometry and settings are not (yet)."""
    scene = nxrender.Scene(str(scenes / "blacklight.scn"))
    params = scene.parameters()
    assert all(isinstance(p["differentiable"], bool) for p in params.values())
    assert params["objects[1].fluorescence.stokes_nm"]["differentiable"]
    assert params["background"]["differentiable"] is (params["background"]["type"] == "spectrum")
    for name in ("camera.fov", "camera.position", "camera.look_at"):
        assert params[name]["differentiable"], name
    for name in ("spp", "camera.up", "objects[0].normal"):
        assert not params[name]["differentiable"], name
        with pytest.raises(ValueError, match="not differentiated"):
            nxrender.render(scene, spp=1, gradients=[name])


SHAPE = """<scene><settings><xres>24</xres><yres>20</yres><mode>spectral_mcpt</mode>
<depth>4</depth><sampl>64</sampl><bands>400:700:50</bands></settings>
<camera><position>0,0.9,-2.6</position><look_at>0,0.5,0</look_at><fov>40</fov></camera>
<plane><normal>0,1,0</normal><distance>0</distance><material>matte</material>
<reflectance>0.5</reflectance></plane>
<sphere><center>0.1,0.7,0</center><radius>0.5</radius><material>matte</material>
<reflectance>0.4</reflectance><fluorescence><absorption>460</absorption><stokes>90</stokes>
<width>25</width><yield>0.8</yield></fluorescence></sphere>
<light><position>0.8,3,-2.5</position><color>1,1,1</color><emission scale="0.02">D65</emission></light>
</scene>"""


def test_sphere_centre_and_radius():
    # A fluorescent sphere on a floor under a point light: its centre's gradient has the vector
    # on a leading axis, (3, H, W, bands); each component and the radius agree with central
    # differences over the image (its outline and its shadow's edge are sampled); backward is
    # the adjoint-weighted sum of the forward images.
    scene = nxrender.Scene.from_text(SHAPE, "t.scn")
    names = ["objects[1].center", "objects[1].radius"]
    image = nxrender.render(scene, spp=256, seed=5, threads=2, gradients=names)
    centre = image.gradients[names[0]]
    assert centre.shape == (3,) + image.radiance.shape
    assert image.gradients[names[1]].shape == image.radiance.shape
    c = scene.numbers(names[0])
    h, w = image.radiance.shape[:2]
    # (sideways and up, the outline gains on one side what it loses on the other: the half it
    # moves towards)
    halves = [np.arange(w)[None, :] >= w // 2 + np.zeros((h, 1), bool),
              np.arange(h)[:, None] < h // 2 + np.zeros((1, w), bool), None]
    for k in range(3):
        expect_agrees_over_seeds(scene, names[0], c, np.eye(3)[k], 0.01, mask=halves[k])
    expect_agrees_over_seeds(scene, names[1], scene.numbers(names[1]), np.array(1.0), 0.01)
    adjoint = np.random.default_rng(2).normal(size=image.radiance.shape).astype(np.float32)
    grads, _ = nxrender.backward(scene, adjoint, names, spp=256, seed=5, threads=2)
    assert grads[names[0]].shape == (3,)
    expected = np.tensordot(centre.astype(np.float64), adjoint, axes=([1, 2, 3], [0, 1, 2]))
    assert np.allclose(grads[names[0]], expected, rtol=1e-3, atol=1e-9), (grads[names[0]], expected)


def test_mesh_vertices_reverse_mode():
    # A mesh given as rows: its vertices' numbers are (N, 3); backward gives one derivative per
    # coordinate, the adjoint-weighted sum of the forward images, and a coordinate's agrees
    # with differences of renders.
    rows = SHAPE.replace(
        "<sphere><center>0.1,0.7,0</center><radius>0.5</radius>",
        "<mesh><vertices>0.55 0.6 0, -0.45 0.6 0, 0.05 1.1 0, 0.05 0.1 0, 0.05 0.6 0.5, "
        "0.05 0.6 -0.5</vertices><faces>0 2 4, 2 1 4, 1 3 4, 3 0 4, 2 0 5, 1 2 5, 3 1 5, "
        "0 3 5</faces>").replace("</fluorescence></sphere>", "</fluorescence></mesh>")
    scene = nxrender.Scene.from_text(rows, "t.scn")
    name = "objects[1].vertices"
    assert scene.numbers(name).shape == (6, 3)
    image = nxrender.render(scene, spp=64, seed=5, threads=2, gradients=[name])
    assert image.gradients[name].shape == (6, 3) + image.radiance.shape
    adjoint = np.random.default_rng(3).normal(size=image.radiance.shape).astype(np.float32)
    grads, _ = nxrender.backward(scene, adjoint, [name], spp=64, seed=5, threads=2)
    assert grads[name].shape == (6, 3)
    expected = np.tensordot(image.gradients[name].astype(np.float64), adjoint, axes=3)
    assert np.allclose(grads[name], expected, rtol=1e-3, atol=1e-9)
    # the top vertex's height against differences
    direction = np.zeros((6, 3))
    direction[2, 1] = 1
    expect_agrees_over_seeds(scene, name, scene.numbers(name), direction, 0.01, spp=64, power=0.1)


BOXED = SHAPE.replace(
    "<sphere><center>0.1,0.7,0</center><radius>0.5</radius>",
    "<box><center>0,0,0</center><size>0.6,0.6,0.6</size><transform><rotate>0,1,0,25</rotate>"
    "<translate>0.1,0.6,0</translate></transform>").replace(
    "</fluorescence></sphere>", "</fluorescence></box>").replace(
    "<reflectance>0.4</reflectance><fluorescence>", "<reflectance>0.05</reflectance><fluorescence>")
# (dark but for its dye: its outline's moves change the image's sum)


def expect_agrees_over_seeds(scene, name, numbers, direction, step, seeds=8, spp=32,
                             power=0.05, mask=None):
    """The gradient of `name` along `direction` (an array of its numbers' shape) summed over
    the image (or its pixels where `mask`), against central differences of renders along it (same seed), over `seeds`
    seeds: per band, the mean difference within 5 standard errors of the seeds' spread, and
    the strongest band resolved to `power`. (Not the pixels' spread: where an edge moves, the
    difference is + in one pixel and - in the next.)"""
    g, f = [], []
    for seed in range(seeds):
        image = nxrender.render(scene, spp=spp, seed=seed, threads=2, gradients=[name])
        grad = np.tensordot(direction, image.gradients[name].astype(np.float64),
                            axes=direction.ndim)
        keep = np.ones(grad.shape[:2], bool) if mask is None else mask
        g.append(grad[keep].sum(axis=0))
        images = []
        for sign in (1, -1):
            s = scene.copy()
            s.set_numbers(name, numbers + sign * step * direction)
            images.append(nxrender.render(s, spp=spp, seed=seed, threads=2).radiance.astype(np.float64))
        f.append(((images[0] - images[1]) / (2 * step))[keep].sum(axis=0))
    g, f = np.array(g), np.array(f)
    se = (g - f).std(axis=0, ddof=1) / np.sqrt(seeds)
    assert np.all(np.abs((g - f).mean(axis=0)) <= 5 * se), (g.mean(axis=0), f.mean(axis=0), se)
    k = int(np.argmax(np.abs(f.mean(axis=0))))
    assert se[k] < power * abs(f.mean(axis=0)[k]), (se[k], f.mean(axis=0)[k])
    return g.mean(axis=0)


def test_object_transform():
    # A box's transform: its numbers are the rows [m | t], (3, 4); forward mode puts them on
    # leading axes, reverse mode gives (3, 4), the adjoint-weighted sum of the forward images;
    # moving it back (t's z: it shrinks in the image) agrees with differences of renders.
    scene = nxrender.Scene.from_text(BOXED, "t.scn")
    name = "objects[1].transform"
    rows = scene.numbers(name)
    assert rows.shape == (3, 4)
    assert rows[1, 3] == pytest.approx(0.6) and rows[0, 2] == pytest.approx(np.sin(np.radians(25)))
    image = nxrender.render(scene, spp=32, seed=5, threads=2, gradients=[name])
    g = image.gradients[name]
    assert g.shape == (3, 4) + image.radiance.shape
    adjoint = np.random.default_rng(4).normal(size=image.radiance.shape).astype(np.float32)
    grads, _ = nxrender.backward(scene, adjoint, [name], spp=32, seed=5, threads=2)
    assert grads[name].shape == (3, 4)
    expected = np.tensordot(g.astype(np.float64), adjoint, axes=3)
    assert np.allclose(grads[name], expected, rtol=1e-3, atol=1e-9)
    moved = rows.copy()
    moved[2, 3] += 1
    expect_agrees_over_seeds(scene, name, rows, moved - rows, 0.02)
    # a singular transform is refused, naming the parameter
    with pytest.raises(ValueError, match="transform"):
        scene.copy().set_numbers(name, np.zeros((3, 4)))
