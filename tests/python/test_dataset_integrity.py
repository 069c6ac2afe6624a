"""Datasets under bad inputs and damage (issue: reliability round 5): damaged items are refused
or redone, never read as other values; records are checked against their own scene before
anything is allocated; settings and generators are never mixed; a failed run leaves nothing
that refuses the corrected one; Slurm arrays of any step; arguments named in their errors."""

import json
import os
import random
import subprocess
import sys
import time
import zlib

import numpy as np
import pytest

import nxrender
import nxrender.dataset as nds


def small_scene(index):
    return {"settings": {"xres": 8, "yres": 6, "mode": "spectral_mcpt", "sampl": 2,
                         "bands": "400:700:100"},
            "camera": {"position": [0, 1, -4], "look_at": [0, 0, 0]},
            "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 0.5 + 0.1 * index,
                         "material": "matte", "reflectance": 0.5}],
            "lights": [{"type": "point", "position": [0, 3, -2], "color": [1, 1, 1]}]}


def quiet(text):
    pass


def made(tmp_path, count=2, **options):
    out = tmp_path / "d"
    nds.generate(small_scene, count, out, log=quiet, **options)
    return out


def rewrite_record(path, change):
    """Rewrites an item's record through `change` with valid checksums (a forged record)."""
    data = open(path, "rb").read()
    head = len(nds._MAGIC) + 8
    n = int.from_bytes(data[len(nds._MAGIC):head], "little")
    meta = json.loads(data[head:head + n])
    change(meta)
    text = json.dumps(meta).encode()
    with open(path, "wb") as f:
        f.write(nds._MAGIC + len(text).to_bytes(8, "little") + text +
                zlib.crc32(text).to_bytes(4, "little") + data[head + n + 4:])


def test_flipped_bits_are_refused_or_redone_never_read_changed(tmp_path):
    out = made(tmp_path)
    data = nds.Dataset(out)
    good = data[0]
    path = nds.item_path(out, 0)
    original = open(path, "rb").read()
    rng = random.Random(7)
    settings = nds._read_manifest(os.path.join(out, "dataset.json"))
    for _ in range(60):
        bit = rng.randrange(8 * len(original))
        flipped = bytearray(original)
        flipped[bit // 8] ^= 1 << (bit % 8)
        open(path, "wb").write(bytes(flipped))
        try:
            item = nds.Dataset(out)[0]
        except ValueError as e:
            assert "cannot read item 0" in str(e)
        else:
            for name, value in good.items():
                np.testing.assert_array_equal(item[name], value, err_msg=f"bit {bit}")
        # the rerun's check sees every flip
        assert not nds._valid(path, 0, {k: v for k, v in settings.items() if k != "version"})
    open(path, "wb").write(original)
    assert nds._valid(path, 0, {k: v for k, v in settings.items() if k != "version"})


def test_a_record_is_checked_against_its_own_scene_before_decoding(tmp_path):
    out = made(tmp_path)
    path = nds.item_path(out, 1)

    def huge(meta):
        meta["arrays"]["radiance"]["shape"] = [8192, 8192, 4]
    rewrite_record(path, huge)
    with pytest.raises(ValueError, match=r"cannot read item 1 \(radiance: expected a shape "
                       r"\(6, 8\[, C <= 4\]\) as its scene renders, found \[8192, 8192, 4\]"):
        nds.Dataset(out)[1]

    def kind(meta):
        meta["arrays"]["radiance"]["shape"] = [6, 8, 4]
        meta["arrays"]["radiance"]["kind"] = "float64"
    rewrite_record(path, kind)
    with pytest.raises(ValueError, match=r"radiance: expected an array of kind f16, uint32, "
                       r"float32, found 'float64'"):
        nds.Dataset(out)[[0, 1]]


def test_a_missing_item_among_many_is_found_at_once(tmp_path):
    out = tmp_path / "big"
    os.makedirs(out / "items")
    count = 100_000
    with open(out / "dataset.json", "w") as f:
        json.dump(dict(nds._settings(count, None, [], 0, "g"), version="x"), f)
    for i in range(count):
        if i != 77_777:
            open(nds.item_path(out, i), "wb").close()
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"1 of 100000 items missing \(first: 77777\)"):
        nds.Dataset(out)
    assert time.monotonic() - start < 10
    assert len(nds.Dataset(out, allow_missing=True)) == count - 1


def test_failed_runs_leave_nothing_that_refuses_the_corrected_command(tmp_path):
    out = tmp_path / "d"
    for bad, error in [({"spp": 0}, "spp: expected a whole number from 1"),
                       ({"aovs": ["bogus"]}, "aovs: expected 'white'"),
                       ({"threads": 0}, "threads: expected a whole number from 1"),
                       ({"count": 10 ** 12}, "count: expected a whole number from 1 to "
                                             "1,000,000,000, found 1000000000000"),
                       ({"count": True}, "count: expected a whole number, found True")]:
        options = dict({"count": 2}, **bad)
        with pytest.raises((ValueError, TypeError), match=error.replace("(", r"\(")):
            nds.generate(small_scene, out=out, log=quiet, **options)
        assert not os.path.exists(out / "dataset.json"), bad
    # a scene the renderer refuses fails before any item: no manifest is left either
    with pytest.raises(nxrender.Error):
        nds.generate(lambda i: dict(small_scene(i), settings={"xres": 0}), 2, out, log=quiet)
    assert not os.path.exists(out / "dataset.json")
    report = nds.generate(small_scene, np.int64(2), out, spp=np.int32(2), log=quiet)
    assert report["rendered"] == 2


def test_settings_and_generators_are_never_mixed(tmp_path):
    out = made(tmp_path)

    def other(index):
        return small_scene(index + 1)
    with pytest.raises(ValueError, match="made with"):
        nds.generate(other, 2, out, log=quiet)
    settings = nds._settings(2, None, ["components"], 0, "another generator")
    with pytest.raises(ValueError, match="made with"):
        nds._create_manifest(str(out), settings)
    with open(out / "dataset.json", "w") as f:
        f.write("{damaged")
    with pytest.raises(ValueError, match=r"dataset\.json: not a dataset manifest \(damaged JSON"):
        nds.Dataset(out)


def test_a_generator_editing_one_scene_gets_each_items_own_state(tmp_path):
    shared = nxrender.Scene.from_dict(small_scene(0))

    def sweep(index):  # the sweep idiom: one scene, edited for each index
        shared.objects[0].radius = 0.3 + 0.2 * index
        return shared
    out = tmp_path / "s"
    nds.generate(sweep, 4, out, jobs=2, log=quiet)
    data = nds.Dataset(out)
    for i in range(4):
        scene = nxrender.Scene.from_text(data.meta(i)["scene"])
        assert scene.objects[0].radius == pytest.approx(0.3 + 0.2 * i)
        direct = nxrender.render(scene, seed=data[i]["seed"], aovs=["components"])
        np.testing.assert_array_equal(
            data[i]["radiance"], nds.stored_values(direct.radiance, data.meta(i)["arrays"]["radiance"]))


def test_boolean_masks_select_items(tmp_path):
    out = made(tmp_path, count=3)
    data = nds.Dataset(out)
    assert data[np.array([True, False, True])]["index"].tolist() == [0, 2]
    assert data[[False, True, False]]["index"].tolist() == [1]
    with pytest.raises(IndexError, match="a boolean mask of 2 values for a dataset of 3"):
        data[np.array([True, False])]
    with pytest.raises(TypeError, match="found the boolean True"):
        data[True]
    with pytest.raises(ValueError, match="layers: no layer 'albedo'"):
        nds.Dataset(out, layers=["albedo"])


def test_slurm_arrays_of_any_step_cover_every_item():
    def split(ident, first, last, step, count):
        return nds.task_split(environ={"SLURM_ARRAY_TASK_ID": str(ident),
                                       "SLURM_ARRAY_TASK_MIN": str(first),
                                       "SLURM_ARRAY_TASK_MAX": str(last),
                                       "SLURM_ARRAY_TASK_STEP": str(step),
                                       "SLURM_ARRAY_TASK_COUNT": str(count)})
    tasks = [split(i, 0, 6, 2, 4) for i in (0, 2, 4, 6)]  # --array=0-6:2
    assert tasks == [(0, 4), (1, 4), (2, 4), (3, 4)]
    assert sorted(i for k, n in tasks for i in range(k, 10, n)) == list(range(10))
    assert split(9, 3, 9, 3, 3) == (2, 3)  # --array=3-9:3
    with pytest.raises(ValueError, match="evenly stepped ids"):
        split(5, 1, 7, 1, 3)  # --array=1,5,7: not a range


def test_a_generator_calling_exit_fails_the_run(tmp_path):
    gen = tmp_path / "exit.py"
    gen.write_text("import sys\ndef scene(index):\n    sys.exit(0)\n")
    cli = os.path.join(os.path.dirname(os.environ["NXRENDER_CLI"]), "nxdataset")
    res = subprocess.run([cli, str(gen), "--count", "2", "-o", str(tmp_path / "x")],
                         capture_output=True, text=True)
    assert res.returncode != 0 and "scene(0) called sys.exit(0)" in res.stderr, res.stderr
