"""Scenes as data: meshes from arrays, scenes from dicts, to_dict and to_text round trips, live
object and light lists. Images that must be the same are compared bit for bit (the same
samples of the same scene)."""

import pathlib
import warnings

import numpy as np
import pytest

import nxrender


def read_binary_ply(path):
    """Vertices (x y z [nx ny nz] [u v] as float32) and triangles of a little-endian binary
    PLY with a uchar-counted int face list: an independent reader for the comparison."""
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    vertex_count = face_count = 0
    props = []
    for line in header:
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            vertex_count, section = int(words[2]), "vertex"
        elif words[:2] == ["element", "face"]:
            face_count, section = int(words[2]), "face"
        elif words[:1] == ["property"] and section == "vertex":
            assert words[1] == "float"
            props.append(words[2])
    vertices = np.frombuffer(data, np.float32, vertex_count * len(props), end)
    vertices = vertices.reshape(vertex_count, len(props))
    faces = np.frombuffer(data, np.dtype([("n", "u1"), ("i", "<i4", 3)]), face_count,
                          end + vertices.nbytes)
    assert (faces["n"] == 3).all()
    col = {name: i for i, name in enumerate(props)}
    pick = lambda names: vertices[:, [col[n] for n in names]] if names[0] in col else None
    return (pick(["x", "y", "z"]), faces["i"].astype(np.uint32), pick(["nx", "ny", "nz"]),
            pick(["u", "v"]))


def same_bits(a, b):
    return a.radiance.tobytes() == b.radiance.tobytes()


def test_mesh_from_arrays_renders_as_its_ply(scenes):
    """The lab bench's vase from the PLY's own numbers (vertices, faces, normals, uv) renders
    bit for bit as the file; the arrays read back as given."""
    vertices, faces, normals, uv = read_binary_ply(scenes / "data" / "vase.ply")
    from_file = nxrender.Scene(str(scenes / "lab_bench.scn"))
    from_file.resolution = (48, 32)
    vase = next(i for i, o in enumerate(from_file.objects) if o.shape == "mesh")
    from_arrays = from_file.copy()
    o = from_arrays.objects[vase]
    with pytest.raises(ValueError, match="<vertices> and <faces> together on a mesh"):
        o.vertices = vertices  # alone it would leave a mesh without faces
    # any real dtype, kept as float32; setting the rows replaces the file
    o.update(vertices=vertices.astype(np.float64), faces=faces, normals=normals, uv=uv)
    assert o.file is None
    assert o.vertices.dtype == np.float32 and np.array_equal(o.vertices, vertices)
    assert o.faces.dtype == np.uint32 and np.array_equal(o.faces, faces)
    assert np.array_equal(o.normals, normals) and np.array_equal(o.uv, uv)
    a = nxrender.render(from_file, spp=2)
    b = nxrender.render(from_arrays, spp=2)
    assert same_bits(a, b)
    # and a changed vertex changes the image and the key
    moved = vertices.copy()
    moved[:, 1] += 0.05
    o.vertices = moved
    c = nxrender.render(from_arrays, spp=2)
    assert not same_bits(a, c)
    assert c.attributes["nxrender.renderKey"] != a.attributes["nxrender.renderKey"]


@pytest.mark.parametrize("name, value, message", [
    ("faces", np.array([[0, 1, 7]]), "face 0 refers to vertex 7"),
    ("faces", np.array([[0, 1, -1]]), "expected whole numbers in [0, 2^32), found -1.0 at [0, 2]"),
    ("faces", np.array([[0, 1.5, 2]]), "found 1.5 at [0, 1]"),
    ("vertices", np.array([[0, 0, np.nan], [1, 0, 0], [0, 1, 0]]), "finite"),
    ("vertices", np.zeros((3, 2)), "expected an array of shape (N, 3), found shape (3, 2)"),
    ("normals", np.ones((2, 3)), "one row of <normals> per vertex (3)"),
])
def test_mesh_arrays_are_checked(name, value, message):
    scene = nxrender.Scene.from_text(MESH_SCENE)
    with pytest.raises((ValueError, TypeError, nxrender.Error)) as e:
        setattr(scene.objects[0], name, value)
        nxrender.render(scene, spp=1)
    assert message in str(e.value)


MESH_SCENE = """<scene><settings><xres>8</xres><yres>8</yres><mode>spectral_mcpt</mode></settings>
<camera><position>0, 0, -3</position><look_at>0, 0, 0</look_at></camera>
<mesh><vertices>0 0 0, 1 0 0, 0 1 0</vertices><faces>0 1 2</faces>
<material>matte</material><reflectance>0.5</reflectance></mesh>
<light><position>0, 0, -2</position><color>1, 1, 1</color></light></scene>"""


def test_mesh_rows_in_scene_text_are_checked_at_their_line():
    bad = MESH_SCENE.replace("<faces>0 1 2</faces>", "<faces>0 1 2 3</faces>")
    with pytest.raises(nxrender.Error, match=r"<string>:3: <faces> \(three vertex indices per "
                       r"triangle\): expected rows of 3 numbers, found 4 numbers"):
        nxrender.Scene.from_text(bad)
    flat = MESH_SCENE.replace("0 1 0</vertices><faces>0 1 2", "0 1 0, 2 0 0</vertices><faces>0 1 2, 0 1 3")
    scene = nxrender.Scene.from_text(flat)
    with pytest.warns(UserWarning, match=r"<string>:3: warning: 1 of the mesh's 2 triangles have "
                      r"zero area \(they are never hit\)"):
        nxrender.render(scene, spp=1)


EXAMPLES = sorted((pathlib.Path(__file__).parents[2] / "scenes").glob("*.scn"))


def small(scene):
    scene.resolution = (20, 12)
    return scene


@pytest.mark.parametrize("path", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_scene_from_its_dict_and_text_renders_as_the_file(path):
    """Every example scene rebuilt from to_dict() (Scene.from_dict) and from to_text() renders
    bit for bit as the file, under the same render key."""
    from_file = small(nxrender.Scene(str(path)))
    from_dict = nxrender.Scene.from_dict(from_file.to_dict())
    from_text = nxrender.Scene.from_text(from_file.to_text(str(path)), str(path))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the examples' own notes (tables ending, ...)
        a = nxrender.render(from_file, spp=1)
        for other in (from_dict, from_text):
            b = nxrender.render(other, spp=1)
            assert same_bits(a, b)
            assert b.attributes["nxrender.renderKey"] == a.attributes["nxrender.renderKey"]


def test_the_issue_dict_renders_and_reads_back():
    """The documented dict form: settings, camera, a fluorescent sphere, a mesh from arrays,
    a lamp; to_dict gives the same names back (arrays as numpy, spectra as given)."""
    V = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], np.float32)
    F = np.array([[0, 2, 1], [0, 3, 2]])
    d = {"settings": {"xres": 32, "yres": 18, "mode": "spectral_mcpt", "sampl": 4},
         "camera": {"position": [0, 2, -6], "look_at": [0, 0.5, 0]},
         "objects": [{"shape": "sphere", "center": [0, 1, 0], "radius": 0.5,
                      "material": "matte", "reflectance": 0.6,
                      "fluorescence": {"absorption": "blue", "stokes": 80}},
                     {"shape": "mesh", "vertices": V, "faces": F, "material": "matte",
                      "reflectance": ([400, 550, 700], [0.2, 0.5, 0.8])}],
         "lights": [{"type": "point", "position": [0, 3, -2], "color": [1, 1, 1]}]}
    scene = nxrender.Scene.from_dict(d)
    back = scene.to_dict()
    assert back["settings"]["xres"] == 32 and back["camera"]["look_at"] == [0, 0.5, 0]
    sphere, mesh = back["objects"]
    assert sphere["shape"] == "sphere" and sphere["fluorescence"] == {"absorption": "blue",
                                                                     "stokes": 80}
    assert mesh["vertices"].dtype == np.float32 and np.array_equal(mesh["vertices"], V)
    assert np.array_equal(mesh["faces"], F)
    assert mesh["reflectance"] == [[400, 550, 700], [0.2, 0.5, 0.8]]
    assert back["lights"][0]["type"] == "point"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = nxrender.render(scene, spp=2)
        b = nxrender.render(nxrender.Scene.from_dict(back), spp=2)
    assert a.radiance.mean() > 0 and same_bits(a, b)


@pytest.mark.parametrize("change, message", [
    (lambda d: d["objects"][1].update(faces=np.array([[0, 1, 9]])),
     "objects[1]: expected face indices below the vertex count (3), found face 0 refers to "
     "vertex 9"),
    (lambda d: d["objects"][0].update(radius=-1),
     "objects[0].radius: expected a radius in (0, 1e+12], found '-1'"),
    (lambda d: d["objects"][0].pop("shape"),
     "objects[0]: expected a \"shape\" (sphere, plane, mesh, ...), found none"),
    (lambda d: d["objects"][1].update(vertices=np.zeros((3, 2))),
     "objects[1].vertices: <vertices> (x, y, z per vertex): expected rows of 3 numbers "
     "separated by commas, found 2 numbers in row 0"),
    (lambda d: d["settings"].update(mode="pbr"),
     "settings.mode: expected a mode rt, mcpt or spectral_mcpt, found 'pbr'"),
    (lambda d: d.update(lamps=[]), "lamps: expected one of the sections"),
    (lambda d: d["objects"][0].update(center=object()), "objects[0].center: expected a number"),
    # Keys that are no element names: an empty key whose value is a dict once took every
    # sibling as its attributes, recursing until memory ran out (found by the dict fuzzer).
    (lambda d: d["objects"][0].update({"fluorescence": {"": {"x": 1}}}),
     "objects[0].fluorescence.: expected a parameter name (letters, digits and _), found ''"),
    (lambda d: d["objects"][0].update({"": 1}),
     "objects[0].: expected a parameter name (letters, digits and _), found ''"),
    (lambda d: d["settings"].update({"a<b": 1}),
     "settings.a<b: expected a parameter name (letters, digits and _), found 'a<b'"),
])
def test_dict_errors_name_the_path(change, message):
    d = {"settings": {"xres": 8, "yres": 8, "mode": "spectral_mcpt"},
         "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0]},
         "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1, "material": "matte"},
                     {"shape": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                      "faces": [[0, 1, 2]], "material": "matte"}]}
    nxrender.Scene.from_dict(d)  # valid as it is
    change(d)
    with pytest.raises((nxrender.Error, ValueError, TypeError)) as e:
        nxrender.Scene.from_dict(d)
    assert message in str(e.value)


def lit_floor():
    return nxrender.Scene.from_dict({
        "settings": {"xres": 24, "yres": 16, "mode": "spectral_mcpt", "sampl": 2},
        "camera": {"position": [0, 1.5, -4], "look_at": [0, 0.5, 0]},
        "objects": [{"shape": "plane", "normal": [0, 1, 0], "distance": 0,
                     "material": "matte", "reflectance": 0.5}],
        "lights": [{"type": "point", "position": [0, 3, -1], "color": [2, 2, 2]}]})


def key_and_bits(scene):
    image = nxrender.render(scene, spp=2)
    return image.attributes["nxrender.renderKey"], image.radiance.tobytes()


def test_appending_removing_and_readding_an_object_restores_key_and_image():
    """objects.append of a sphere changes the image; del restores the original key and image;
    adding it again (from the popped dict or as a view) gives the appended state back."""
    scene = lit_floor()
    original = key_and_bits(scene)
    sphere = {"shape": "sphere", "center": [0, 0.5, 0], "radius": 0.5, "material": "matte",
              "reflectance": 0.8}
    scene.objects.append(sphere)
    assert len(scene.objects) == 2 and scene.objects[1].radius == 0.5
    with_sphere = key_and_bits(scene)
    assert with_sphere[0] != original[0] and with_sphere[1] != original[1]
    del scene.objects[1]
    assert key_and_bits(scene) == original
    scene.objects.append(sphere)
    assert key_and_bits(scene) == with_sphere
    popped = scene.objects.pop()
    assert popped["shape"] == "sphere" and popped["radius"] == 0.5
    assert key_and_bits(scene) == original
    scene.objects.insert(0, popped)
    other = nxrender.Scene.from_dict(scene.to_dict())
    assert key_and_bits(other) == key_and_bits(scene)
    assert scene.edits[:2] == ["objects.insert(1, " + repr(sphere) + ")", "del objects[1]"]


def test_views_and_dicts_assign_and_views_of_replaced_items_refuse_edits():
    scene = lit_floor()
    scene.objects.append({"shape": "sphere", "center": [0, 0.5, 0], "radius": 0.5,
                          "material": "matte", "reflectance": 0.8})
    ball = scene.objects[1]
    floor = scene.objects[0]
    copy = lit_floor()
    copy.objects.append(ball)  # a view of another scene: its description is copied
    assert key_and_bits(copy) == key_and_bits(scene)
    scene.objects[0] = {"shape": "plane", "normal": [0, 1, 0], "distance": -0.1,
                        "material": "matte", "reflectance": 0.2}
    ball.radius = 0.3  # the ball is still objects[1]: its view follows it
    assert scene.objects[1].radius == 0.3
    with pytest.raises(ValueError, match=r"objects\[0\]: this object is no longer in the scene "
                       r"\(objects\[0\] = \{.*\}\); take scene.objects\[...\] again"):
        floor.distance = 0.5
    scene.objects.append(floor)  # copied as it was when it left
    assert scene.objects[2].distance == 0
    del scene.objects[2]
    with pytest.raises(IndexError, match="objects index 5 out of range"):
        del scene.objects[5]
    with pytest.raises(nxrender.Error, match=r"objects\[2\].radius: expected a radius"):
        scene.objects.append({"shape": "sphere", "center": [0, 0, 0], "radius": 0,
                              "material": "matte"})
    with pytest.raises(TypeError, match=r"objects\[2\]: expected a dict or an nxrender.Object"):
        scene.objects.append(42)
    assert len(scene.objects) == 2  # refused changes leave the list as it was
    scene.lights.append({"type": "spot", "position": [0, 3, 0], "look_at": [0, 0, 0],
                         "cone_angle": 30, "color": [5, 5, 5]})
    assert [l.kind for l in scene.lights] == ["point", "spot"]
    del scene.lights[0]
    assert nxrender.render(scene, spp=1).radiance.mean() > 0


def test_an_empty_scene_built_up_renders():
    scene = nxrender.Scene()
    assert len(scene.objects) == 0 and len(scene.lights) == 0
    scene.objects.append({"shape": "sphere", "center": [0, 0, 0], "radius": 1,
                          "material": "matte", "emission": 1})
    image = nxrender.render(scene, spp=16)
    # the emitter's radiance 1 in every band (the 8 x 8 centre pixels' mean over the bands:
    # wavelength sampling alone makes it noisy, about 0.1% here)
    assert image.radiance[28:36, 28:36].mean() == pytest.approx(1, rel=0.01)


def test_vertices_are_a_triangles_corners_and_a_meshs_rows():
    scene = nxrender.Scene.from_text(MESH_SCENE)
    scene.objects.append({"shape": "triangle", "vA": [0, 0, 1], "vB": [1, 0, 1], "vC": [0, 1, 1],
                          "material": "matte", "reflectance": 0.5})
    mesh, triangle = scene.objects
    assert mesh.vertices.shape == (3, 3) and triangle.vertices == ((0, 0, 1), (1, 0, 1), (0, 1, 1))
    triangle.vertices = ((0, 0, 2), (1, 0, 2), (0, 1, 2))
    mesh.vertices = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0]])
    assert triangle.vA == (0, 0, 2) and mesh.vertices[1, 0] == 2
    with pytest.raises(ValueError, match=r"objects\[0\]\.vertices: expected face indices below"):
        mesh.vertices = np.zeros((2, 3))


def test_float64_rows_round_once_to_float_as_set_from_python():
    """Vertices given as float64 in a dict round to the same floats as when set as an array,
    also where a double lies exactly halfway between two floats (one rounding, not two)."""
    halfway = 1 + 2.0 ** -24  # exactly between 1 and the next float
    V = np.array([[halfway, 0, 0], [0, 1 + 3 * 2.0 ** -25, 0], [0, 0, 0.1]])
    F = np.array([[0, 1, 2]])
    d = {"settings": {"xres": 4, "yres": 4, "mode": "spectral_mcpt"},
         "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0]},
         "objects": [{"shape": "mesh", "vertices": V, "faces": F, "material": "matte",
                      "reflectance": 0.5}]}
    from_dict = nxrender.Scene.from_dict(d).objects[0].vertices
    assert np.array_equal(from_dict, V.astype(np.float32))
    scene = nxrender.Scene.from_dict(d)
    scene.objects[0].vertices = V
    assert np.array_equal(scene.objects[0].vertices, from_dict)


def test_whole_numbers_of_any_size_round_trip_through_dicts_and_text():
    """Whole numbers are written as integers (shortest-form text wrote 100000 as 1e+05, which
    integer fields refuse): sample counts, depths, seeds and faces using vertex 100,000+."""
    n = 100_002
    V = np.zeros((n, 3), np.float32)
    V[:, 0] = np.arange(n) * 1e-5
    V[-1] = [0, 1, 0]
    V[-2] = [1, 0, 0]
    F = np.array([[0, n - 2, n - 1]], np.uint32)
    d = {"settings": {"xres": 4, "yres": 4, "mode": "spectral_mcpt", "sampl": 100000,
                      "depth": 100000},
         "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0]},
         "objects": [{"shape": "mesh", "vertices": V, "faces": F, "material": "matte",
                      "reflectance": 0.5}]}
    scene = nxrender.Scene.from_dict(d)
    again = nxrender.Scene.from_dict(scene.to_dict())
    assert again.to_text() == scene.to_text()
    assert nxrender.Scene.from_text(scene.to_text()).to_text() == scene.to_text()
    assert "1e+05" not in scene.to_text()
    assert again.objects[0].faces.max() == n - 1
    appended = nxrender.Scene.from_dict({k: v for k, v in d.items() if k != "objects"})
    appended.objects.append(d["objects"][0])
    assert appended.objects[0].faces.max() == n - 1


def test_nesting_deeper_than_a_scene_and_self_containing_values_are_refused():
    deep = [0.5]
    for _ in range(50_000):
        deep = [deep]
    scene = nxrender.Scene.from_dict({
        "settings": {"xres": 4, "yres": 4, "mode": "spectral_mcpt"},
        "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0]}})
    with pytest.raises(ValueError, match=r"objects\[0\]\.reflectance\[0\]\[0\].*: expected values "
                       r"nested at most 16 levels deep"):
        scene.objects.append({"shape": "sphere", "center": [0, 0, 0], "radius": 1,
                              "material": "matte", "reflectance": deep})
    looped = {"shape": "sphere", "center": [0, 0, 0], "radius": 1, "material": "matte"}
    looped["reflectance"] = looped
    with pytest.raises(ValueError, match="nested at most 16 levels deep"):
        scene.objects.append(looped)
    top = {"settings": {"xres": 4}}
    top["settings"]["self"] = top
    with pytest.raises(ValueError, match=r"settings\.self\.settings\.self.*nested at most"):
        nxrender.Scene.from_dict(top)
    with pytest.raises(ValueError, match=r"settings\.xres: expected a finite number, found 10000"
                       r".*\(401 digits\)"):
        nxrender.Scene.from_dict({"settings": {"xres": 10 ** 400}})
    assert len(scene.objects) == 0


def test_integers_beyond_64_bits_are_refused_naming_the_parameter():
    scene = nxrender.Scene.from_dict({"settings": {"xres": 4, "yres": 4, "mode": "spectral_mcpt"},
                                      "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0]}})
    for set_it in (lambda v: scene.set("resolution", v),
                   lambda v: setattr(scene, "resolution", v)):
        with pytest.raises(ValueError, match=r"resolution\[0\]: expected an int in .*, found "
                                             r"10000000000000000000\.\.\. \(401 digits\)"):
            set_it((10 ** 400, 4))
    with pytest.raises(ValueError, match=r"spp: expected an int in \[1, .*\(401 digits\)"):
        nxrender.render(scene, spp=10 ** 400)
