"""Scene.parameters(): every parameter of every example scene by name, each settable to a new
valid value (checked and recorded as its attribute is) and rendering; a measured matrix given
as numpy arrays renders as the same matrix from its CSV file."""

import numpy as np
import pytest

import nxrender
from conftest import SCENES


def new_value(name, info):
    """A valid value different from the current one, from the parameter's type and range."""
    v, t, r = info["value"], info["type"], info["range"]
    if t == "transform":  # rows [m | t]: moved a little (from the identity when absent)
        rows = v or ((1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0))
        return tuple(tuple(row[:3]) + (row[3] + 0.01,) for row in rows)
    if v is None and name.endswith("_scale"):
        v = float(info["default"])  # a factor not given: moved from its default, 1
    if v is None or t == "fluorescence":
        return None
    if t == "number":
        if r is None:
            return v + 0.01
        lo, hi = r
        mid = (lo + min(hi, lo + 10.0)) / 2
        return 0.95 * v + 0.05 * mid if v != mid else 0.9 * v + 0.1 * lo
    if t == "integer":
        return v + 1
    if t == "integers":
        return (3, 2)
    if t in ("point", "vector"):
        return (v[0] + 0.01, v[1], v[2])
    if t == "points":
        return tuple((p[0] + 0.01, p[1], p[2]) for p in v)
    if t in ("spectrum", "spectrum or texture"):
        if isinstance(v, float):
            return v * 0.9 if v > 0 else 0.1
        if isinstance(v, tuple):
            return (v[0], [x * 0.9 for x in v[1]])
        return v  # a name or a file: the same, set again
    if t == "rgb":
        return tuple(x * 0.9 for x in v)
    if t == "ior":
        return v * 0.99 if isinstance(v, float) and v * 0.99 >= 1 else v
    if t == "coating":
        return (v[0] * 0.9, v[1])
    if t == "numbers":
        if len(v) == 2:  # thin_lens
            return (v[0] * 0.9, v[1])
        return v
    if t == "matrix":
        return (v[0], v[1], v[2] * 0.9)
    return v  # text (bands), names


def small(scene):
    scene.resolution = (3, 2)
    scene.spp = 1
    return scene


@pytest.mark.parametrize("path", sorted(SCENES.glob("*.scn")), ids=lambda p: p.stem)
def test_every_parameter_is_settable_by_name_and_renders(path):
    scene = small(nxrender.Scene(path))
    parameters = scene.parameters()
    assert parameters, "a scene has parameters"
    changed = 0
    for name, info in parameters.items():
        assert set(info) == {"value", "type", "unit", "range", "default", "doc", "differentiable"}
        assert info["doc"], name
        value = new_value(name, info)
        if value is None:
            continue
        edited = scene.copy()
        before = len(edited.edits)
        edited.set(name, value)
        assert len(edited.edits) == before + 1, name
        assert name.replace("'", "") in edited.edits[-1].replace("'", "")
        if info["type"] == "number":
            assert edited.get(name) == pytest.approx(value), name
        image = nxrender.render(edited, threads=1)
        assert np.isfinite(np.asarray(image.radiance)).all(), name
        changed += 1
    assert changed >= 5


@pytest.mark.parametrize("path", sorted(SCENES.glob("*.scn")), ids=lambda p: p.stem)
def test_values_of_the_wrong_kind_are_refused_by_type(path):
    # A mapping is no sequence (a dict gave "KeyError: 0"), whatever it holds; each parameter
    # refuses it with TypeError or ValueError naming it, and nothing is recorded.
    scene = nxrender.Scene(path)
    for name in scene.parameters():
        for bad in ({0: 1.0, 1: 2.0, 2: 3.0}, {"a": 1}):
            with pytest.raises((TypeError, ValueError)) as info:
                scene.set(name, bad)
            assert not isinstance(info.value, KeyError), (name, info.value)
            assert name.split(".")[-1].split("[")[0] in str(info.value) or "dict" in str(info.value), (name, info.value)
    assert scene.edits == []


def test_shape_parameters_come_from_the_kinds_and_are_checked_like_the_file(tmp_path):
    scene = nxrender.Scene(SCENES / "lab_bench.scn")
    params = scene.parameters()
    mesh = next(i for i, o in enumerate(scene.objects) if o.shape == "mesh")
    label = f"objects[{mesh}]"
    assert params[label + ".file"]["type"] == "file"
    assert params[label + ".transform"]["type"] == "transform"
    rows = scene.get(label + ".transform")
    assert len(rows) == 3 and rows[0][0] == pytest.approx(0.45) and rows[0][3] == pytest.approx(-0.5)
    # A transform from numpy, a singular one refused (the file's message), the scene unchanged.
    moved = scene.copy()
    moved.set(label + ".transform", np.array([[0.5, 0, 0, 0], [0, 0.5, 0, 0], [0, 0, 0.5, 0]]))
    assert moved.get(label + ".transform")[1][1] == 0.5
    with pytest.raises(ValueError, match=r"keeps volume \(non-zero determinant\), found determinant 0"):
        moved.set(label + ".transform", np.zeros((3, 4)))
    assert moved.get(label + ".transform")[1][1] == 0.5
    # The mesh file can be replaced; a missing one is refused when the scene is built.
    moved.set(label + ".file", str(SCENES / "data" / "vase.ply"))
    assert np.isfinite(np.asarray(nxrender.render(small(moved), threads=1).radiance)).all()
    moved.set(label + ".file", str(tmp_path / "none.ply"))
    with pytest.raises(Exception, match="none.ply"):
        nxrender.render(moved, threads=1)
    # Checks of a kind: a zero plane normal, collinear triangle vertices.
    thesis = nxrender.Scene(SCENES / "thesis.scn")
    plane = next(i for i, o in enumerate(thesis.objects) if o.shape == "plane")
    with pytest.raises(ValueError, match=r"expected a non-zero plane normal, found 0, 0, 0"):
        thesis.set(f"objects[{plane}].normal", (0, 0, 0))
    with pytest.raises(ValueError, match=r"a plane takes no vA \(a triangle does\)"):
        thesis.objects[plane].vA = (0, 0, 0)
    assert thesis.edits == []


def test_unknown_names_and_bad_values_are_refused():
    scene = nxrender.Scene(SCENES / "thesis.scn")
    with pytest.raises(KeyError, match="no scene parameter named 'objects\\[99\\].radius'"):
        scene.set("objects[99].radius", 1)
    with pytest.raises(KeyError):
        scene.get("camera..fov")
    with pytest.raises(ValueError, match=r"^objects\[2\]\.radius: expected a radius in \(0"):
        scene.set("objects[2].radius", -1)
    with pytest.raises(ValueError, match=r"^objects\[2\]\.alpha: expected a GGX roughness"):
        scene.set("objects[2].alpha", 3)
    # A parameter the kind does not take is refused as the loader refuses it.
    with pytest.raises(ValueError, match=r"^objects\[0\]\.alpha: expected only <color>"):
        scene.objects[0].material.alpha = 0.2
    assert scene.edits == []


def csv_matrix(path):
    """A Donaldson matrix CSV read with numpy alone: (excitation_nm, emission_nm, values)."""
    rows = [line.split(",") for line in path.read_text().splitlines()
            if line.strip() and not line.startswith("#")]
    emission = np.array([float(x) for x in rows[0][1:]])
    body = np.array([[float(x) for x in r] for r in rows[1:]])
    return body[:, 0], emission, body[:, 1:]


def test_matrix_from_numpy_renders_like_the_csv():
    path = SCENES / "measured.scn"
    scene = small(nxrender.Scene(path))
    names = [n for n in scene.parameters() if n.endswith(".fluorescence.matrix")]
    assert names, "measured.scn has a measured matrix"
    name = names[0]
    reference = nxrender.render(scene, threads=1, spp=8, seed=3)
    excitation, emission, values = csv_matrix(SCENES / "data" / "orange_sheet_donaldson.csv")
    got = scene.get(name)
    np.testing.assert_array_equal(got[0], excitation)
    np.testing.assert_array_equal(got[2], values)
    edited = scene.copy()
    edited.set(name, (excitation, emission, values))
    assert "digest" in edited.edits[-1]
    same = nxrender.render(edited, threads=1, spp=8, seed=3)
    np.testing.assert_array_equal(np.asarray(same.radiance), np.asarray(reference.radiance))
    # A different matrix renders differently; a malformed one is refused naming the parameter.
    edited.set(name, (excitation, emission, values * 0.5))
    other = nxrender.render(edited, threads=1, spp=8, seed=3)
    assert not np.array_equal(np.asarray(other.radiance), np.asarray(reference.radiance))
    with pytest.raises(ValueError, match=r"fluorescence\.matrix: expected matrix values in \[0, 1\]"):
        edited.set(name, (excitation, emission, values + 2))
    with pytest.raises(ValueError, match=r"fluorescence\.matrix\[2\]: expected shape"):
        edited.set(name, (excitation, emission, values[:, :-1]))


def test_texture_from_numpy_renders_like_the_same_texture_from_its_file(tmp_path):
    """A reflectance texture given as (wavelengths, values[h, w, bands]) renders exactly as the
    same texels written to a spectral EXR and named by texture="..."; bad arrays are refused."""
    rng = np.random.default_rng(5)
    wavelengths = np.arange(380.0, 781.0, 20.0)
    values = rng.uniform(0.05, 0.95, size=(6, 8, wavelengths.size)).astype(np.float32)
    path = tmp_path / "texels.exr"
    nxrender.write_exr(path, nxrender.Image(values, wavelengths=wavelengths))
    scene = small(nxrender.Scene(SCENES / "lab_bench.scn"))
    scene.resolution = (16, 9)
    chart = next(i for i, o in enumerate(scene.objects)
                 if o.material.reflectance == "texture:colorchecker")
    name = f"objects[{chart}].reflectance"
    from_file, from_numpy = scene.copy(), scene.copy()
    from_file.set(name, f"texture:{path}")
    from_numpy.set(name, (wavelengths, values))
    got = from_numpy.get(name)
    np.testing.assert_array_equal(got[0], wavelengths)
    np.testing.assert_array_equal(got[1], values)
    a = nxrender.render(from_file, threads=1, spp=4, seed=2)
    b = nxrender.render(from_numpy, threads=1, spp=4, seed=2)
    np.testing.assert_array_equal(np.asarray(a.radiance), np.asarray(b.radiance))
    # The edit is recorded with the texture's content (a digest), so two textures differ.
    other = from_numpy.copy()
    other.set(name, (wavelengths, values * 0.5))
    assert other.edits[-1] != from_numpy.edits[-1] and "digest" in other.edits[-1]
    assert nxrender.render(other, threads=1, spp=4, seed=2).radiance.mean() < b.radiance.mean()
    before = list(scene.edits)
    # Refused: reflectances beyond [0, 1] (the texel named), a band count other than the
    # wavelengths', complex values; a texture where a spectrum is expected.
    with pytest.raises(ValueError, match=r"in \[0, 1\], found 1\.5 at row 2, column 3"):
        bad = values.copy()
        bad[2, 3, 0] = 1.5
        scene.set(name, (wavelengths, bad))
    with pytest.raises(ValueError, match="one wavelength per band"):
        scene.set(name, (wavelengths[:-1], values))
    with pytest.raises(TypeError, match="complex"):
        scene.set(name, (wavelengths, values.astype(np.complex64)))
    lights = [n for n, i in scene.parameters().items() if n.startswith("lights[") and i["type"] == "spectrum"]
    if lights:
        with pytest.raises(ValueError, match="expected a spectrum, found a texture"):
            scene.set(lights[0], (wavelengths, values))
    assert scene.edits == before


def test_settings_mode_path_and_named_spectra_are_parameters():
    scene = small(nxrender.Scene(SCENES / "extensions.scn"))
    params = scene.parameters()
    for name in ("mode", "path", "spectra['paint'].value", "spectra['lamp'].value"):
        assert name in params, name
    assert scene.get("mode") == "spectral_mcpt"
    with pytest.raises(ValueError, match="mode: expected rt, mcpt or spectral_mcpt, found 'fast'"):
        scene.set("mode", "fast")
    # A named spectrum set to a constant renders as its users set to that constant.
    users = [i for i, o in enumerate(scene.objects) if o.material.reflectance == "paint"]
    assert users
    by_name, by_users = scene.copy(), scene.copy()
    by_name.set("spectra['paint'].value", 0.3)
    for i in users:
        by_users.objects[i].material.reflectance = 0.3
    a = nxrender.render(by_name, threads=1, spp=2, seed=4)
    b = nxrender.render(by_users, threads=1, spp=2, seed=4)
    np.testing.assert_array_equal(np.asarray(a.radiance), np.asarray(b.radiance))
    with pytest.raises(ValueError, match="a named spectrum is defined by values"):
        scene.set("spectra['paint'].value", "red")
    # Another mode renders with its own light transport.
    rt = scene.copy()
    rt.set("mode", "mcpt")
    assert rt.get("mode") == "mcpt" and rt.edits[-1] == "mode = 'mcpt'"
    assert np.isfinite(np.asarray(nxrender.render(rt, threads=1).radiance)).all()


def test_dye_spectra_from_python():
    # A dye as a datasheet gives it: set from Python, read back, refused where it is not one,
    # written back through to_dict, and rendered as the same dye written in scene text.
    base = {"settings": {"xres": 8, "yres": 6, "mode": "spectral_mcpt", "sampl": 16},
            "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0]},
            "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1,
                         "material": "matte", "reflectance": 0.5,
                         "emission": 0.2}]}
    scene = nxrender.Scene.from_dict(base)
    material = scene.objects[0].material
    absorptance = ([400, 450, 500], [0.1, 0.8, 0.1])
    emission = ([480, 540, 600, 700], [0, 1, 0.3, 0])
    f = material.set_fluorescence_spectra(absorptance, emission, quantum_yield=0.7)
    nm, values = f.emission
    assert list(nm) == [480, 540, 600, 700] and list(values) == [0, 1, 0.3, 0]
    assert f.quantum_yield == 0.7 and f.stokes_nm is None
    assert "objects[0].fluorescence.absorptance" in scene.parameters()
    assert scene.parameters()["objects[0].fluorescence.emission"]["differentiable"]
    with pytest.raises(ValueError, match=r"^objects\[0\]\.fluorescence\.stokes_nm: the "
                                         r"fluorescence is given by its <absorptance>"):
        f.stokes_nm = 80
    f.emission = ([480, 560, 700], [0, 1, 0])
    assert list(scene.get("objects[0].fluorescence.emission")[1]) == [0, 1, 0]
    d = scene.to_dict()
    assert d["objects"][0]["fluorescence"]["yield"] == 0.7
    again = nxrender.Scene.from_dict(d)
    text = nxrender.Scene.from_text(scene.to_text(), "t.scn")
    a = nxrender.render(again, seed=3, threads=1).radiance
    b = nxrender.render(text, seed=3, threads=1).radiance
    assert np.array_equal(a, b)
    # A model fluorescence has no spectra to set.
    model = nxrender.Scene.from_dict(base)
    g = model.objects[0].material.set_fluorescence(460, 80)
    assert g.emission is None
    with pytest.raises(ValueError, match="not given by spectra"):
        g.emission = emission
