"""Live object and light lists under edits that Python code makes while a value is converted
(a value's __float__, a sequence's __getitem__ or __iter__ appending to or deleting from the
very list being edited), Python's list idioms (swap, extend), and how views follow their items.
Run under AddressSanitizer in CI's second pass: a reference held across a conversion is a
use after free there."""

import pytest

import nxrender


def scene_with_spheres(n=3):
    scene = nxrender.Scene.from_dict({
        "settings": {"xres": 8, "yres": 8, "mode": "spectral_mcpt", "sampl": 1},
        "camera": {"position": [0, 1.5, -4], "look_at": [0, 0.5, 0]},
        "objects": [{"shape": "sphere", "center": [k, 0.5, 0], "radius": 0.1 + 0.1 * k,
                     "material": "matte", "reflectance": 0.5} for k in range(n)],
        "lights": [{"type": "point", "position": [0, 3, -1], "color": [2, 2, 2]}]})
    return scene


def sphere(r):
    return {"shape": "sphere", "center": [0, 2, 0], "radius": r, "material": "matte",
            "reflectance": 0.5}


class GrowingFloat:
    """A number whose conversion appends many objects (the list's storage moves)."""

    def __init__(self, value, scene, count=200):
        self.value, self.scene, self.count = value, scene, count

    def __float__(self):
        for _ in range(self.count):
            self.scene.objects.append(sphere(0.05))
        return float(self.value)


class ShrinkingFloat:
    """A number whose conversion deletes every object, the one being edited among them."""

    def __init__(self, value, scene):
        self.value, self.scene = value, scene

    def __float__(self):
        while len(self.scene.objects) > 0:
            del self.scene.objects[0]
        return float(self.value)


class EditingList(list):
    """A list (as a dict's value) whose iteration first runs `edit`."""

    def __init__(self, items, edit):
        super().__init__(items)
        self.edit = edit

    def __iter__(self):
        self.edit()
        return super().__iter__()


def grow(scene, count):
    return lambda: [scene.objects.append(sphere(0.05)) for _ in range(count)]


def shrink(scene):
    def run():
        while len(scene.objects) > 0:
            del scene.objects[0]
    return run


def sphere_at(center, r):
    return {"shape": "sphere", "center": center, "radius": r, "material": "matte",
            "reflectance": 0.5}


class GrowingPoint:
    """A sequence of three numbers whose __getitem__ appends objects."""

    def __init__(self, point, scene):
        self.point, self.scene = point, scene

    def __len__(self):
        return 3

    def __getitem__(self, i):
        if i >= 3:
            raise IndexError(i)
        for _ in range(50):
            self.scene.objects.append(sphere(0.05))
        return self.point[i]


def test_a_setter_whose_value_grows_the_list_edits_the_right_object():
    scene = scene_with_spheres()
    ball = scene.objects[1]
    ball.radius = GrowingFloat(0.7, scene)
    assert len(scene.objects) == 203
    assert scene.objects[1].radius == pytest.approx(0.7)
    assert [scene.objects[k].radius for k in (0, 2)] == pytest.approx([0.1, 0.3])
    ball.center = GrowingPoint([0, 1, 2], scene)
    assert scene.objects[1].center == (0, 1, 2)
    # a light's parameter and a material's
    scene.lights[0].color = [GrowingFloat(3, scene), 3, 3]
    assert scene.lights[0].color[0] == 3
    scene.objects[2].material.reflectance = GrowingFloat(0.25, scene)
    assert scene.objects[2].material.reflectance == 0.25


def test_a_setter_whose_value_removes_the_object_is_refused_clearly():
    scene = scene_with_spheres()
    ball = scene.objects[1]
    # (it was objects[0] when the conversion's loop deleted it)
    with pytest.raises(ValueError, match=r"objects\[0\]: this object is no longer in the scene "
                       r"\(del objects\[0\]\)"):
        ball.radius = ShrinkingFloat(0.7, scene)
    assert len(scene.objects) == 0


def test_insert_append_and_assign_convert_before_they_place():
    scene = scene_with_spheres()
    scene.objects.insert(1, sphere_at(EditingList([0, 2, 0], grow(scene, 10)), 0.9))
    # converted first (10 appended at the end), then inserted at position 1 of the list as it
    # was then
    assert len(scene.objects) == 14 and scene.objects[1].radius == pytest.approx(0.9)
    scene.objects[0] = sphere_at(EditingList([0, 2, 0], grow(scene, 300)), 0.8)
    assert len(scene.objects) == 314 and scene.objects[0].radius == pytest.approx(0.8)
    scene.objects.append(sphere_at(EditingList([0, 2, 0], shrink(scene)), 0.6))
    assert len(scene.objects) == 1 and scene.objects[0].radius == pytest.approx(0.6)
    with pytest.raises(IndexError, match="objects index 3 out of range"):
        scene.objects[3] = sphere(0.2)
    scene2 = scene_with_spheres()
    with pytest.raises(IndexError, match="objects index 2 out of range"):
        scene2.objects[2] = sphere_at(EditingList([0, 2, 0], shrink(scene2)), 0.6)


def test_extend_is_all_or_nothing():
    scene = scene_with_spheres()
    with pytest.raises(nxrender.Error, match=r"objects\[5\].radius: expected a radius"):
        scene.objects.extend([sphere(0.2), sphere(0.3), sphere(0)])
    assert len(scene.objects) == 3
    scene.objects.extend(iter([sphere(0.2), sphere(0.3)]))
    assert [o.radius for o in scene.objects][3:] == pytest.approx([0.2, 0.3])
    assert scene.edits[-2:] == ["objects.insert(3, " + repr(sphere(0.2)) + ")",
                                "objects.insert(4, " + repr(sphere(0.3)) + ")"]


def test_swap_idiom_swaps_and_views_follow_their_items():
    scene = scene_with_spheres()
    r = [o.radius for o in scene.objects]
    scene.objects[1], scene.objects[2] = scene.objects[2], scene.objects[1]
    assert [o.radius for o in scene.objects] == pytest.approx([r[0], r[2], r[1]])
    last = scene.objects[2]
    scene.objects.insert(0, sphere(0.9))
    assert last.radius == pytest.approx(r[1])  # it followed its object to position 3
    assert repr(last).startswith("<nxrender.Object objects[3] sphere")
    del scene.objects[0]
    last.radius = 0.55
    assert scene.objects[2].radius == pytest.approx(0.55)
    lights = scene.lights
    lamp = lights[0]
    lights.append({"type": "point", "position": [1, 3, -1], "color": [1, 1, 1]})
    del lights[0]
    with pytest.raises(ValueError, match=r"lights\[0\]: this light is no longer in the scene "
                       r"\(del lights\[0\]\)"):
        lamp.color = [1, 1, 1]


def test_a_material_view_follows_its_object():
    scene = scene_with_spheres()
    mat = scene.objects[2].material
    scene.objects.insert(0, sphere(0.9))
    mat.reflectance = 0.125
    assert scene.objects[3].material.reflectance == 0.125
    del scene.objects[3]
    with pytest.raises(ValueError, match=r"this object is no longer in the scene"):
        mat.reflectance = 0.5
