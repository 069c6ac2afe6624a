"""Datasets of many scenes (docs/datasets.md): nxdataset as a two-task Slurm array (by its
environment variables), one task killed and rerun, a broken item redone, every item read back
through Dataset (and a torch DataLoader when torch is installed) equal to a direct render of
scene(i) with its recorded seed; settings never mixed; missing items refused."""

import os
import signal
import subprocess
import time

import numpy as np
import pytest

import nxrender
import nxrender.dataset

GENERATOR = '''
import os, time
def scene(index):
    # (a task told to stall does so after its first item: the test kills it there)
    if os.environ.get("NX_TEST_STALL") and index >= int(os.environ["NX_TEST_STALL"]):
        time.sleep(60)
    return {
        "settings": {"xres": 24, "yres": 16, "mode": "spectral_mcpt", "sampl": 4,
                     "bands": "400:700:50"},
        "camera": {"position": [0, 2, -6], "look_at": [0, 0.5, 0]},
        "objects": [
            {"shape": "sphere", "center": [0.2 * index - 0.5, 1, 0], "radius": 0.4 + 0.05 * index,
             "material": "matte", "reflectance": 0.6,
             "fluorescence": {"absorption": "blue", "stokes": 80}},
            {"shape": "plane", "normal": [0, 1, 0], "distance": 0, "material": "matte",
             "reflectance": 0.5},
        ],
        "lights": [{"type": "point", "position": [0, 3, -2], "color": [1, 1, 1]}],
    }
'''
COUNT = 7


def nxdataset():
    return os.path.join(os.path.dirname(os.environ["NXRENDER_CLI"]), "nxdataset")


def run(generator, out, task, extra=(), env=None, wait=True):
    e = dict(os.environ, SLURM_ARRAY_TASK_ID=str(task), SLURM_ARRAY_TASK_COUNT="2",
             **(env or {}))
    cmd = [nxdataset(), str(generator), "--count", str(COUNT), "-o", str(out),
           "--aov", "components,normals,ids", "--threads", "1", *extra]
    if not wait:
        return subprocess.Popen(cmd, env=e, stderr=subprocess.PIPE, stdout=subprocess.PIPE)
    return subprocess.run(cmd, env=e, capture_output=True, text=True, timeout=300)


def load_generator(path):
    namespace = {}
    exec(compile(path.read_text(), str(path), "exec"), namespace)
    return namespace["scene"]


def test_two_tasks_interrupted_and_rerun_read_back_as_rendered(tmp_path):
    gen = tmp_path / "gen.py"
    gen.write_text(GENERATOR)
    out = tmp_path / "data"
    first = run(gen, out, 0, extra=["--jobs", "2"])
    assert first.returncode == 0, first.stderr
    assert "4 items rendered" in first.stdout and "bytes per item" in first.stdout
    # Task 1 (items 1, 3, 5) stalls at item 3: killed once item 1 is written.
    stalled = run(gen, out, 1, env={"NX_TEST_STALL": "3"}, wait=False)
    deadline = time.monotonic() + 120
    while not os.path.exists(nxrender.dataset.item_path(out, 1)):
        assert stalled.poll() is None, stalled.stderr.read()
        assert time.monotonic() < deadline
        time.sleep(0.05)
    stalled.send_signal(signal.SIGKILL)
    stalled.wait()
    # (what a task killed while writing leaves: its rerun removes it)
    leftover = str(nxrender.dataset.item_path(out, 3)) + ".tmp999.1"
    open(leftover, "wb").close()
    with pytest.raises(ValueError, match="2 of 7 items missing"):
        nxrender.dataset.Dataset(out)
    partial = nxrender.dataset.Dataset(out, allow_missing=True)
    assert len(partial) == 5
    # A broken item (a truncated file) is redone by the rerun; finished ones are skipped.
    broken = nxrender.dataset.item_path(out, 2)
    with open(broken, "r+b") as f:
        f.truncate(os.path.getsize(broken) - 10)
    again = run(gen, out, 0)
    assert again.returncode == 0 and "1 items rendered, 3 already done" in again.stdout, \
        again.stdout + again.stderr
    rest = run(gen, out, 1)
    assert rest.returncode == 0 and "2 items rendered, 1 already done" in rest.stdout, \
        rest.stdout + rest.stderr
    assert not os.path.exists(leftover)
    data = nxrender.dataset.Dataset(out)
    assert len(data) == COUNT
    scene = load_generator(gen)
    for i in range(COUNT):
        item = data[i]
        assert item["index"] == i and item["seed"] == nxrender.dataset.item_seed(0, i)
        direct = nxrender.render(nxrender.Scene.from_dict(scene(i)), seed=item["seed"],
                                 threads=2, aovs=["components", "normals", "ids"])
        assert item["object_id"].dtype == np.int32  # (torch takes no uint32)
        np.testing.assert_array_equal(item["object_id"], direct.object_id)
        arrays = data.meta(i)["arrays"]

        def stored(name, a):  # as the item stores it: float16 scaled, low bits as recorded
            return nxrender.dataset.stored_values(a, arrays[name])
        np.testing.assert_array_equal(item["radiance"], stored("radiance", direct.radiance))
        for name in ("reflected", "direct"):
            np.testing.assert_array_equal(item[name], stored(name, direct.components[name]))
        # derived from the radiance and the stored part, within the two parts' rounding
        for name, other in (("fluoresced", "reflected"), ("indirect", "direct")):
            np.testing.assert_array_equal(item[name], item["radiance"] - item[other])
            bound = sum(np.abs(a).max() * 2.0 ** (arrays[n]["drop"] - 11) for n, a in
                        (("radiance", direct.radiance), (other, direct.components[other])))
            assert np.abs(item[name] - direct.components[name]).max() <= bound, name
        np.testing.assert_array_equal(item["normals"], stored("normals", direct.aovs["normals"]))
        assert arrays["normals"]["drop"] == 0  # ground truth keeps every float16 bit
        # the rounding stays within its noise share: at most 2^-(11 - drop) of the largest
        drop = arrays["radiance"]["drop"]
        assert np.max(np.abs(item["radiance"] - direct.radiance)) <= \
            np.max(np.abs(direct.radiance)) * 2.0 ** (drop - 11)
        assert arrays["radiance"]["quantisation_to_noise"] <= nxrender.dataset.NOISE_SHARE
        assert nxrender.Scene.from_text(data.meta(i)["scene"]).to_text() == \
            nxrender.Scene.from_dict(scene(i)).to_text()
    # Only some layers, a derived one among them; an unknown one named.
    some = nxrender.dataset.Dataset(out, layers=["fluoresced", "normals"])[2]
    assert set(some) == {"fluoresced", "normals", "seed", "index"}
    np.testing.assert_array_equal(some["fluoresced"], data[2]["fluoresced"])
    with pytest.raises(ValueError, match="no layer 'albedo'"):
        nxrender.dataset.Dataset(out, layers=["albedo"])[0]
    # Through a DataLoader as it is.
    try:
        import torch.utils.data
    except ImportError:
        torch = None
    if torch is not None:
        batches = list(torch.utils.data.DataLoader(data, batch_size=3))
        assert [b["radiance"].shape[0] for b in batches] == [3, 3, 1]
        assert batches[0]["radiance"].shape[1:] == (16, 24, 7)
        assert batches[0]["seed"].tolist() == [nxrender.dataset.item_seed(0, i) for i in range(3)]
        # Batches decoded into place: the same tensors as the collated ones.
        for shuffle in (False, True):
            read = list(data.loader(3, shuffle=shuffle, generator=torch.Generator().manual_seed(1)))
            assert [len(b["index"]) for b in read] == [3, 3, 1]
            assert sorted(i for b in read for i in b["index"].tolist()) == list(range(COUNT))
            for b in read:
                for name, value in b.items():
                    expected = torch.stack([torch.as_tensor(np.asarray(data[i][name]))
                                            for i in b["index"].tolist()])
                    assert torch.equal(value, expected), name
        two = list(data.loader(4, num_workers=2))  # (worker batches in shared memory)
        assert torch.equal(two[1]["reflected"],
                           torch.from_numpy(np.stack([data[i]["reflected"] for i in range(4, 7)])))
    # A batch by a list, a slice or an index array: each layer stacked, seeds and indices.
    for key in ([0, 2, 5], slice(0, 6, 2), np.array([5, 2])):
        batch = data[key]
        positions = list(range(COUNT))[key] if isinstance(key, slice) else list(key)
        assert batch["index"].tolist() == positions and batch["seed"].dtype == np.int64
        for name in ("radiance", "fluoresced", "normals", "object_id"):
            np.testing.assert_array_equal(batch[name], np.stack([data[p][name] for p in positions]))
    assert set(nxrender.dataset.Dataset(out, layers=["fluoresced"])[[1, 2]]) == \
        {"fluoresced", "seed", "index"}
    with pytest.raises(IndexError, match="item 7 of a dataset of 7"):
        data[[0, 7]]
    for bad in ("radiance", 1.5, [0, 1.5]):
        with pytest.raises(TypeError, match="expected an item position"):
            data[bad]
    # An item whose first frame was overwritten is refused, naming it (decoded in the library).
    meta, blobs = nxrender.dataset._read_item(nxrender.dataset.item_path(out, 4))
    with open(nxrender.dataset.item_path(out, 4), "r+b") as f:
        f.seek(os.path.getsize(f.name) - len(blobs))
        f.write(b"\0\0\0\0")
    with pytest.raises(ValueError, match=r"cannot read item 4 \(expected a zstd frame of"):
        data[4]


def test_item_encoding_round_trips_every_layout():
    """The codec alone: float16 arrays in several chunks (a count neither a multiple of the
    chunk nor even), every number of dropped bits (nibble-packed low bytes from 4 on), tiny,
    negative and non-finite values, a derived difference, decoded exactly as from_half gives;
    format 3's layout (one pair of frames per array) still read; bad outputs refused."""
    ds = nxrender.dataset
    rng = np.random.default_rng(3)
    count = 2 * ds._CHUNK + 12345
    base = rng.lognormal(-8, 3, count).astype(np.float32) * rng.choice([-1, 1], count)
    base[:6] = [0, np.inf, -np.inf, np.nan, 1e-30, 6e4]
    for drop in (0, 3, 4, 6):
        a = base.copy()
        a[1:4] = 1.0  # (the scale needs finite values)
        b = (a * 0.5 + rng.normal(0, 1e-4, count)).astype(np.float32)
        # (ids of another shape first: the difference names arrays by their place in the item)
        arrays = {"object_id": (np.arange(7, dtype=np.uint32), {})}
        for n, (bits, k) in (("radiance", ds.to_half(a, drop)), ("reflected", ds.to_half(b, drop))):
            arrays[n] = (bits, {"k": k, "drop": drop})
        records, blobs = ds._encode(arrays)
        assert records["radiance"]["nibbles"] == (drop >= 4)
        assert len(records["radiance"]["frames"]) == 2 * 3
        offset = 0
        for r in records.values():
            r["offset"], offset = offset, offset + r["bytes"]
        out = ds._decode(records, b"".join(blobs), ["fluoresced"])
        want = {n: ds.from_half(bits, extra["k"]) for n, (bits, extra) in arrays.items()
                if n != "object_id"}
        for n in want:
            np.testing.assert_array_equal(out[n], want[n])
        np.testing.assert_array_equal(out["fluoresced"], want["radiance"] - want["reflected"])
        np.testing.assert_array_equal(out["object_id"], np.arange(7))
    # Format 3: each float16 array's low and high bytes as one frame each.
    import zstandard
    bits, k = ds.to_half(base[6:], 2)
    frames = [zstandard.ZstdCompressor().compress((bits & 0xFF).astype(np.uint8).tobytes()),
              zstandard.ZstdCompressor().compress((bits >> 8).astype(np.uint8).tobytes())]
    old = {"radiance": {"kind": "f16", "k": k, "shape": [bits.size], "offset": 0,
                        "frames": [len(f) for f in frames]}}
    np.testing.assert_array_equal(ds._decode(old, b"".join(frames))["radiance"],
                                  ds.from_half(bits, k))
    # Outputs of the wrong kind or shape are refused.
    specs = [(0, old["radiance"]["frames"], "f16", [bits.size], k, 0, False)]
    for bad in (np.empty(bits.size, np.float64), np.empty(bits.size - 1, np.float32),
                np.empty(2 * bits.size, np.float32)[::2]):
        with pytest.raises(ValueError, match="expected a writable C-contiguous float32 output"):
            nxrender._decode_arrays(b"".join(frames), specs, [], [bad])


def test_a_batch_of_items_of_different_shapes_is_refused(tmp_path):
    def scene(index):
        return {"settings": {"xres": 8 + 4 * index, "yres": 8, "mode": "spectral_mcpt",
                             "sampl": 1, "bands": "400:700:100"},
                "camera": {"position": [0, 1, -4], "look_at": [0, 0, 0]},
                "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1,
                             "material": "matte", "reflectance": 0.5}],
                "lights": [{"type": "point", "position": [0, 3, -2], "color": [1, 1, 1]}]}
    nxrender.dataset.generate(scene, 2, tmp_path / "d", aovs=(), log=lambda text: None)
    data = nxrender.dataset.Dataset(tmp_path / "d")
    assert data[0]["radiance"].shape == (8, 8, 4) and data[1]["radiance"].shape == (8, 12, 4)
    with pytest.raises(ValueError, match=r"cannot read item 1 \(its layers \(radiance \(8, 12, "
                                         r"4\)\) differ from item 0's \(radiance \(8, 8, 4\)\)"):
        data[[0, 1]]


def test_settings_are_never_mixed_and_bad_tasks_refused(tmp_path):
    gen = tmp_path / "gen.py"
    gen.write_text(GENERATOR)
    out = tmp_path / "data"
    assert run(gen, out, 0).returncode == 0
    other = run(gen, out, 1, extra=["--spp", "8"])
    assert other.returncode == 2 and "made with" in other.stderr, other.stderr
    with pytest.raises(ValueError, match="0 <= I < N"):
        nxrender.dataset.task_split("2/2")
    with pytest.raises(ValueError, match="SLURM_ARRAY_TASK_COUNT"):
        nxrender.dataset.task_split(environ={"SLURM_ARRAY_TASK_ID": "1"})
    assert nxrender.dataset.task_split(environ={"SLURM_ARRAY_TASK_ID": "5",
                                                "SLURM_ARRAY_TASK_MIN": "4",
                                                "SLURM_ARRAY_TASK_COUNT": "3"}) == (1, 3)
    bad = tmp_path / "bad.py"
    bad.write_text("def scene(index):\n    return 42\n")
    res = subprocess.run([nxdataset(), str(bad), "--count", "1", "-o", str(tmp_path / "b")],
                         capture_output=True, text=True)
    assert res.returncode != 0 and "expected an nxrender.Scene or a dict" in res.stderr


def test_random_scenes_are_plausible_and_the_example_renders(tmp_path):
    import math
    import runpy
    ds = nxrender.dataset
    gen = runpy.run_path(os.path.join(os.environ["NX_SOURCE_DIR"], "scenes", "datasets",
                                      "separation.py"))
    dyed = plain = 0
    for i in range(40):
        d = gen["scene"](i)
        # the same scene for the same index
        assert nxrender.Scene.from_dict(d).to_text() == \
            nxrender.Scene.from_dict(gen["scene"](i)).to_text()
        shapes = d["objects"][1:]
        assert 2 <= len(shapes) <= 5
        circles = []
        for o in shapes:
            if o["shape"] == "sphere":
                (x, y, z), r = o["center"], o["radius"]
                assert abs(y - r) < 1e-9  # resting on the floor
            elif o["shape"] == "box":
                x, z = o["transform"][1]["translate"][0], o["transform"][1]["translate"][2]
                r = o["size"][0] / math.sqrt(2)
                assert abs(o["center"][1] - o["size"][1] / 2) < 1e-9
            else:
                x, _, z = o["p0"]
                r = o["radius"]
                assert o["p0"][1] == 0 and o["p1"][1] > 0
            circles.append((x, z, r))
            nm, values = o["reflectance"]
            v = np.array(values)
            assert v.min() >= 0.02 - 1e-9 and v.max() <= 0.9 + 1e-9
            assert np.abs(np.diff(v, 2)).max() < 0.1  # smooth over 10 nm steps
            if "fluorescence" in o:
                dyed += 1
                for k, (lo, hi) in ds.DYE_RANGES.items():
                    assert lo <= o["fluorescence"][k] <= hi, k
            else:
                plain += 1
        for a in range(len(circles)):
            for b in range(a):
                (xa, za, ra), (xb, zb, rb) = circles[a], circles[b]
                assert math.hypot(xa - xb, za - zb) >= ra + rb, (i, circles)
        cam = d["camera"]
        assert cam["position"][1] > 0.3  # above the floor
    assert dyed > 10 and plain > 10
    led = ds.random_led(np.random.default_rng(1))
    peak = led[0][int(np.argmax(led[1]))]
    assert ds.LED_RANGES["peak"][0] - 2 <= peak <= ds.LED_RANGES["peak"][1] + 2
    # two items of the example, small: the components split their radiance
    report = ds.generate(gen["scene"], 2, tmp_path / "sep", spp=2, aovs=["components"],
                         threads=2, log=lambda text: None)
    assert report["rendered"] == 2
    data = ds.Dataset(tmp_path / "sep")
    for i in range(2):
        item = data[i]
        assert item["radiance"].shape == (128, 128, 31) and item["radiance"].max() > 0
        np.testing.assert_array_equal(item["fluoresced"], item["radiance"] - item["reflected"])
