"""Scenes as data: meshes from arrays, scenes from dicts, to_dict and to_text round trips, live
object and light lists. Images that must be the same are compared bit for bit (the same
samples of the same scene)."""

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
