"""nxrender.dataset: datasets of many scenes (docs/datasets.md).

    import nxrender, nxrender.dataset
    def scene(index):                      # an nxrender.Scene, or a dict for Scene.from_dict
        ...
    report = nxrender.dataset.generate(scene, 1000, "out", spp=64,
                                       aovs=["components", "normals", "albedo"])
    data = nxrender.dataset.Dataset("out")  # len(data); data[i] -> dict of arrays
    loader = torch.utils.data.DataLoader(data, batch_size=16, shuffle=True)

The command line is nxdataset (a program of the build): nxdataset GENERATOR.py --count N -o DIR
[--spp S] [--aov LIST] [--seed S] [--task I/N] [--jobs K] [--threads T], GENERATOR.py
defining scene(index). Item i is rendered with a seed derived from i and the dataset's seed
(recorded); a Slurm job array splits the indices by SLURM_ARRAY_TASK_ID and
SLURM_ARRAY_TASK_COUNT (or --task I/N), item i going to task i mod N; an item is written
atomically (a temporary file renamed) with its scene as text, the options and the render key,
so a rerun skips finished items and redoes broken or missing ones.
"""

import json
import operator
import os
import re
import sys
import threading
import time
import zlib

FORMAT = "nxrender-dataset-5"
# Formats a Dataset still reads (4: without checksums; 3: one pair of byte-plane frames per
# float16 array).
_READABLE_FORMATS = (FORMAT, "nxrender-dataset-4", "nxrender-dataset-3")
_MANIFEST = "dataset.json"
# The most items a dataset holds (item names have room for 10^9; a count beyond is a typo).
MAX_COUNT = 10 ** 9


def item_seed(dataset_seed, index):
    """The seed item `index` renders with: a 31-bit hash of the dataset's seed and the index
    (FNV-1a), the same on every machine and task."""
    h = 0xcbf29ce484222325
    for byte in f"{int(dataset_seed)}:{int(index)}".encode():
        h = ((h ^ byte) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return int((h ^ (h >> 31)) & 0x7FFFFFFF)


def item_path(out, index):
    """The file of item `index` in dataset directory `out`."""
    return os.path.join(out, "items", f"item_{int(index):07d}.nxi")


def task_split(task=None, environ=None):
    """(I, N): this task's share of the indices, those i with i mod N == I. `task` as "I/N" or
    (I, N); else a Slurm array task's SLURM_ARRAY_TASK_ID (minus SLURM_ARRAY_TASK_MIN) of
    SLURM_ARRAY_TASK_COUNT; else (0, 1)."""
    env = os.environ if environ is None else environ
    if task is None and "SLURM_ARRAY_TASK_ID" in env:
        names = ("SLURM_ARRAY_TASK_ID", "SLURM_ARRAY_TASK_MIN", "SLURM_ARRAY_TASK_MAX",
                 "SLURM_ARRAY_TASK_STEP", "SLURM_ARRAY_TASK_COUNT")
        try:
            first = int(env.get("SLURM_ARRAY_TASK_MIN", "0"))
            step = int(env.get("SLURM_ARRAY_TASK_STEP", "1"))
            offset = int(env["SLURM_ARRAY_TASK_ID"]) - first
            count = int(env["SLURM_ARRAY_TASK_COUNT"])
            last = int(env.get("SLURM_ARRAY_TASK_MAX", str(first + step * (count - 1))))
        except KeyError as e:
            raise ValueError(f"task: a Slurm array task needs {e.args[0]} too") from None
        except ValueError:
            raise ValueError("task: expected whole numbers in " + ", ".join(names) + ", found " +
                             ", ".join(repr(env.get(n)) for n in names)) from None
        # A stepped array (--array=0-6:2) numbers its tasks MIN, MIN+STEP, ...: task k of COUNT.
        # An array of other ids (--array=1,5,7) cannot be split so: refused, not left partial.
        if step < 1 or offset % step or last != first + step * (count - 1):
            raise ValueError("task: expected a Slurm array of evenly stepped ids (--array=0-N or "
                             "0-N:S), found " +
                             ", ".join(f"{n}={env.get(n)}" for n in names if n in env) +
                             "; give --task I/N to each task instead")
        task = (offset // step, count)
    if task is None:
        return 0, 1
    if isinstance(task, str):
        parts = task.split("/")
        try:
            task = (int(parts[0]), int(parts[1])) if len(parts) == 2 else None
        except ValueError:
            task = None
        if task is None:
            raise ValueError(f"task: expected I/N (e.g. 0/4), found {task!r}")
    ident, count = int(task[0]), int(task[1])
    if not (count >= 1 and 0 <= ident < count):
        raise ValueError(f"task: expected 0 <= I < N, found {ident}/{count}")
    return ident, count


def _settings(count, spp, aovs, seed, generator):
    return {"format": FORMAT, "count": int(count), "spp": spp, "aovs": list(aovs),
            "seed": int(seed), "generator": generator}


def generator_identity(scene_fn):
    """What a manifest records of the scene generator: its module and name, and a digest of its
    source (two generators, or two versions of one, never fill one directory)."""
    import hashlib
    import inspect
    name = f"{getattr(scene_fn, '__module__', '?')}.{getattr(scene_fn, '__qualname__', '?')}"
    try:
        source = inspect.getsource(scene_fn)
    except (OSError, TypeError):
        source = repr(scene_fn)
    return f"{name} {hashlib.sha256(source.encode()).hexdigest()[:16]}"


def _read_manifest(path):
    """The manifest's settings; errors name the file."""
    try:
        with open(path) as f:
            held = json.load(f)
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}: not a dataset manifest (damaged JSON: {e})") from None
    if not isinstance(held, dict):
        raise ValueError(f"{path}: not a dataset manifest (expected a JSON object)")
    return held


def _has_items(out):
    folder = os.path.join(out, "items")
    try:
        return any(name.endswith(".nxi") for name in os.listdir(folder))
    except FileNotFoundError:
        return False


def _check_manifest(out, settings):
    """Checks that an existing manifest has these settings (a dataset is never mixed from two
    configurations or generators); True when it exists. A manifest without any item (left by a
    run that failed before its first item) does not hold its settings against a new run."""
    path = os.path.join(out, _MANIFEST)
    if not os.path.exists(path):
        return False
    held = _read_manifest(path)
    mine = dict(settings, version=held.get("version"))
    if held != mine:
        if not _has_items(out):
            os.remove(path)
            return False
        raise ValueError(f"{path}: the dataset there was made with {held}, not {mine}: "
                         "give another directory, or the same settings to continue it")
    return True


def _create_manifest(out, settings):
    """Writes the manifest if there is none, atomically (another task may be creating it at the
    same moment: the first one's stays), then checks it has these settings."""
    import nxrender
    path = os.path.join(out, _MANIFEST)
    temp = f"{path}.tmp{os.getpid()}.{threading.get_ident()}"
    with open(temp, "w") as f:
        json.dump(dict(settings, version=nxrender.__version__), f, indent=1)
    try:
        os.link(temp, path)  # fails if it exists: never replaces another run's manifest
    except FileExistsError:
        pass
    finally:
        os.remove(temp)
    if not _check_manifest(out, settings):
        raise ValueError(f"{path}: removed while this run was writing it")


# An item file: the magic, the record's length (8 bytes, little-endian), the record (JSON), then
# (format 5) the record's CRC-32 (4 bytes), then the arrays' bytes, whose CRC-32 the record holds.
_MAGIC_UNCHECKED = b"NXDATASET-ITEM-1\n"  # formats 3 and 4: no checksums
_MAGIC = b"NXDATASET-ITEM-2\n"


# Per thread, the buffer Dataset reads items into (reused: a fresh 1 MB bytes object per item
# cost a third of the reading time besides the decoding).
_read_buffers = threading.local()


def _file_bytes(path, reuse):
    """The bytes of the file at `path`: a bytes object, or with `reuse` a memoryview of this
    thread's reused buffer (valid until the thread's next read)."""
    if not reuse:
        with open(path, "rb") as f:
            return f.read()
    with open(path, "rb", buffering=0) as f:
        size = os.fstat(f.fileno()).st_size
        buffer = getattr(_read_buffers, "data", None)
        if buffer is None or len(buffer) < size:
            buffer = _read_buffers.data = bytearray(max(size, 1 << 20))
        view = memoryview(buffer)[:size]
        got = 0
        while got < size:
            n = f.readinto(view[got:])
            if not n:
                break
            got += n
        return view[:got]


def _read_item(path, reuse=False, verify=False):
    """(record, blobs) of an item file: its JSON record and its bytes after it (with `reuse`, in
    this thread's reused buffer: _file_bytes). The record's checksum is checked, and with
    `verify` the arrays' (reading checks their zstd frames' own checksums as it decodes them).
    Raises ValueError for a file that is not a complete, intact item."""
    data = _file_bytes(path, reuse)
    magic = bytes(data[:len(_MAGIC)])
    checked = magic == _MAGIC
    if not checked and magic != _MAGIC_UNCHECKED:
        raise ValueError("not an item file")
    head = len(_MAGIC) + 8
    if len(data) < head:
        raise ValueError("truncated")
    n = int.from_bytes(data[len(_MAGIC):head], "little")
    start = head + n + (4 if checked else 0)
    if len(data) < start:
        raise ValueError("truncated")
    text = bytes(data[head:head + n])
    if checked and zlib.crc32(text) != int.from_bytes(data[head + n:start], "little"):
        raise ValueError("its record is damaged (checksum)")
    try:
        meta = json.loads(text)
        blobs = memoryview(data)[start:]
        declared = sum(int(a["bytes"]) for a in meta["arrays"].values())
    except (ValueError, TypeError, KeyError, AttributeError) as e:
        raise ValueError(f"its record is not an item's ({e})") from None
    if len(blobs) != declared:
        raise ValueError("truncated" if len(blobs) < declared else "longer than its record says")
    if checked and verify and zlib.crc32(blobs) != meta.get("crc32"):
        raise ValueError("its arrays are damaged (checksum)")
    return meta, blobs


def _valid(path, index, settings):
    """True when the item file is complete, intact (its checksums) and was made with these
    settings."""
    try:
        meta, _ = _read_item(path, verify=True)
    except Exception:  # a truncated, damaged or foreign file: redo it
        return False
    return meta.get("index") == index and all(meta.get(k) == v for k, v in settings.items()
                                              if k != "count")


# Component layers that are the radiance minus another stored one: derived when read, not
# stored (the reflected and fluoresced parts sum to the radiance, as do direct and indirect).
_DERIVED = {"fluoresced": "reflected", "indirect": "direct"}
# The quantisation's share of the noise it may add: the error from dropping low bits stays
# below this fraction of the layer's median relative Monte Carlo standard deviation (so the
# noise variance grows by at most its square, 1%).
NOISE_SHARE = 0.1
_ZSTD_LEVEL = 3
# The level of packed low nibbles (noise): a negative level stores literals without Huffman
# coding, which gained 3% in size there and took 5/6 of their decoding time.
_ZSTD_NIBBLE_LEVEL = -1


def to_half(array, drop=0, k=None):
    """(uint16 bits of float16 values, k): `array` times 2^k as float16, k chosen so that its
    largest magnitude lies in [2^14, 2^15) (radiance can be far below float16's smallest normal
    number, 6e-5, where it would lose precision; a power of 2 scales exactly), rounded to
    10 - drop mantissa bits. k = 0 for an array of zeros; `k` given: that scale."""
    import numpy as np
    a = np.asarray(array, np.float32)
    if k is None:
        largest = float(np.max(np.abs(a))) if a.size else 0.0
        k = int(np.floor(np.log2(16384.0 / largest))) if largest > 0 else 0
    bits = (a * np.float32(2.0 ** k)).astype(np.float16).view(np.uint16)
    if drop:
        wide = bits.astype(np.uint32) + (1 << (drop - 1))
        bits = (wide & (0xFFFF & ~((1 << drop) - 1))).astype(np.uint16)
    return bits, k


def from_half(bits, k):
    """The float32 values to_half stored as (bits, k)."""
    import numpy as np
    out = bits.view(np.float16).astype(np.float32)
    out *= np.float32(2.0 ** -k)  # (a power of 2: exact)
    return out


def stored_values(array, encoding):
    """`array` as an item stores it with `encoding` (its record's "arrays" entry): what the
    item reads back, exactly."""
    bits, k = to_half(array, encoding.get("drop", 0))
    if k != encoding["k"]:
        raise ValueError(f"not the array this encoding was made for (scale 2^{k}, not "
                         f"2^{encoding['k']})")
    return from_half(bits, k)


def _noise_drop(values, variance):
    """The most low mantissa bits (0-6) that can be dropped from `values` while the rounding
    this adds stays below NOISE_SHARE of their median relative standard deviation (from
    `variance`, the variance of each mean), and that ratio. The rounding is measured relative
    to each value, over the values float16 keeps as normal numbers (those below, tiny beside
    the layer's largest, hold fewer bits whatever is dropped)."""
    import numpy as np
    v = np.asarray(values, np.float32)
    var = np.asarray(variance, np.float32)
    seen = (v > 0) & (var > 0)
    if not seen.any():
        return 0, 0.0
    noise = float(np.median(np.sqrt(var[seen]) / v[seen]))
    # (the rounding's statistics from every 7th value: the scale from the whole array)
    bits, k = to_half(v)
    kept = v[seen][::7]
    kept = kept[np.abs(kept * np.float32(2.0 ** k)) >= 2.0 ** -14]
    if not kept.size:
        return 0, 0.0
    exact = from_half(to_half(kept, 0, k)[0], k)
    best, ratio = 0, 0.0
    for drop in range(1, 7):
        back = from_half(to_half(kept, drop, k)[0], k)
        error = float(np.sqrt(np.mean(((back - exact) / kept) ** 2)))
        if error > NOISE_SHARE * noise:
            break
        best, ratio = drop, error / noise
    return best, ratio


def _zstd():
    try:
        import zstandard
    except ImportError:
        raise ImportError("nxrender.dataset stores items with zstd: install python3-zstandard "
                          "(apt-get install python3-zstandard)") from None
    return zstandard


# Values per chunk of a float16 array: each chunk its own frames, so that the cores share an
# item's layers evenly and a chunk's planes stay in the cache while converted (format 4).
_CHUNK = 65536


def _half_frames(bits, drop, zc, nibble_zc):
    """The zstd frames of float16 bits, per chunk of _CHUNK values: its low bytes' (when at least
    4 low bits were dropped, only their high nibbles, two to a byte: half the symbols to decode;
    compressed at _ZSTD_NIBBLE_LEVEL) and its high bytes'."""
    import numpy as np
    flat = bits.ravel()
    frames = []
    for start in range(0, flat.size, _CHUNK):
        chunk = flat[start:start + _CHUNK]
        low = (chunk & 0xFF).astype(np.uint8)
        if drop >= 4:
            if low.size % 2:
                low = np.append(low, np.uint8(0))
            low = (low[0::2] >> 4) | (low[1::2] & 0xF0)
        frames += [(nibble_zc if drop >= 4 else zc).compress(low.tobytes()),
                   zc.compress((chunk >> 8).astype(np.uint8).tobytes())]
    return frames


def _encode(arrays):
    """(records, blobs): each array as zstd-compressed bytes; float16 bits byte-shuffled into
    frames per chunk (_half_frames; the high bytes of smooth or noisy values compress well
    apart, the chunks decode on every core at once), their sizes in "frames"."""
    import numpy as np
    # Each frame carries its content's checksum, checked whenever it is decoded.
    zc = _zstd().ZstdCompressor(level=_ZSTD_LEVEL, write_checksum=True)
    nibble_zc = _zstd().ZstdCompressor(level=_ZSTD_NIBBLE_LEVEL, write_checksum=True)
    records, blobs = {}, []
    for name, (array, extra) in arrays.items():
        a = np.ascontiguousarray(array)
        if a.dtype == np.uint16:  # float16 bits
            frames = _half_frames(a, extra.get("drop", 0), zc, nibble_zc)
            kind, layout = "f16", {"chunk": _CHUNK, "nibbles": extra.get("drop", 0) >= 4}
        else:
            frames, kind, layout = [zc.compress(a.tobytes())], str(a.dtype), {}
        blob = b"".join(frames)
        records[name] = dict(extra, kind=kind, shape=list(a.shape), bytes=len(blob),
                             frames=[len(f) for f in frames], **layout)
        blobs.append(blob)
    return records, blobs


def _in_torch_worker():
    """True in a torch DataLoader worker process."""
    torch_data = sys.modules.get("torch.utils.data")
    return torch_data is not None and torch_data.get_worker_info() is not None


def _batch_array(shape, dtype):
    """An empty batch array: in a DataLoader worker a torch tensor in shared memory (passed to
    the main process as it is, where a numpy array is copied into shared memory first), else a
    numpy array."""
    import numpy as np
    if _in_torch_worker():
        import torch
        return torch.from_numpy(np.empty(0, dtype)).new_empty(shape).share_memory_()
    return np.empty(shape, dtype)


def _as_numpy(array):
    """A numpy view of a batch array (numpy or torch)."""
    return array if hasattr(array, "__array_interface__") else array.numpy()


def _cannot_read(path, index, error):
    """The error a Dataset raises for an item it cannot read."""
    return ValueError(f"{path}: cannot read item {index} ({error}): rerun nxdataset, which "
                      "redoes broken items")


_KINDS = ("f16", "uint32", "float32")


def _check_shapes(meta):
    """Refuses an item record whose arrays do not fit its own scene (before anything is
    allocated for them): each array (H, W) or (H, W, C) with H x W the scene's resolution and C
    at most the bands recorded (or 3: normals, positions), of a known kind; and all of them
    within the memory the machine has. A record that declares an 8192 x 8192 radiance for a
    small scene once decoded into 1.1 GB."""
    scene = meta.get("scene")
    if not isinstance(scene, str):
        raise ValueError("its record holds no scene")
    size = [re.search(rf"<{tag}>\s*(\d+)\s*</{tag}>", scene) for tag in ("yres", "xres")]
    if not all(size):
        raise ValueError("its scene gives no resolution")
    h, w = (int(m.group(1)) for m in size)
    bands = len(meta.get("wavelengths") or [])
    total = 0
    for name, r in meta["arrays"].items():
        shape, kind = r.get("shape"), r.get("kind")
        if kind not in _KINDS:
            raise ValueError(f"{name}: expected an array of kind {', '.join(_KINDS)}, found "
                             f"{kind!r:.40}")
        if not (isinstance(shape, list) and 2 <= len(shape) <= 3 and
                all(isinstance(n, int) and not isinstance(n, bool) for n in shape) and
                shape[:2] == [h, w] and (len(shape) == 2 or 1 <= shape[2] <= max(bands, 3))):
            raise ValueError(f"{name}: expected a shape ({h}, {w}[, C <= {max(bands, 3)}]) as its "
                             f"scene renders, found {shape!r:.60}")
        total += 4 * h * w * (shape[2] if len(shape) == 3 else 1)
    try:
        memory = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (ValueError, OSError):
        memory = 0
    if memory and 2 * total > memory:
        raise ValueError(f"its arrays need {total / 2**30:.1f} GiB, more than half the memory")


def _describe(shapes):
    """Layer shapes as text: 'radiance (128, 128, 32), ...'."""
    return ", ".join(f"{name} {shape}" for name, (shape, _) in shapes.items())


def _decode(records, blobs, derived=(), outputs=None):
    """The arrays of `records` (name -> record, in the item's order of blobs, each with its
    "offset") from the item's bytes, and the `derived` layers (names in _DERIVED: the radiance
    minus another): decoded by the library in parallel (zstd, the byte shuffle undone,
    float16 times 2^-k to float32 exactly as from_half, the differences in float32 as numpy
    takes them; ids as int32, as torch takes no uint32); into `outputs` (arrays in the order of
    records, then derived) when given."""
    import nxrender
    names = list(records)
    specs = [(r["offset"], r["frames"], r["kind"], r["shape"], r.get("k", 0), r.get("chunk", 0),
              bool(r.get("nibbles", False))) for r in records.values()]
    differences = [(names.index("radiance"), names.index(_DERIVED[d])) for d in derived]
    arrays = nxrender._decode_arrays(blobs, specs, differences, outputs)
    return dict(zip(names + list(derived), arrays))


def _arrays(image, aovs):
    """The arrays an item stores, by name, with their encodings: radiance-like layers as
    float16 scaled by a power of 2 with the low bits the noise allows dropped (_noise_drop);
    ground truth as float16 scaled so, all its bits kept; ids as uint32 and depth as float32;
    the layers of _DERIVED left out."""
    import numpy as np
    noisy = {"radiance": (image.radiance, image.variance)}
    layers, variances = image.components, image.component_variances
    for name, array in layers.items():
        if _DERIVED.get(name) not in layers:
            noisy[name] = (array, variances.get(name))
    out = {}
    for name, (array, variance) in noisy.items():
        drop, ratio = _noise_drop(array, variance) if variance is not None else (0, 0.0)
        bits, k = to_half(array, drop)
        out[name] = (bits, {"k": k, "drop": drop, "quantisation_to_noise": round(ratio, 4)})
    exact = dict(image.aovs)
    if "white" in aovs and image.white is not None:
        exact["white"] = image.white
    for name, array in exact.items():
        bits, k = to_half(array)
        out[name] = (bits, {"k": k, "drop": 0})
    if image.object_id is not None:
        out["object_id"] = (np.asarray(image.object_id, np.uint32), {})
        out["material_id"] = (np.asarray(image.material_id, np.uint32), {})
    if image.depth is not None:
        out["depth"] = (np.asarray(image.depth, np.float32), {})
    return out


def _write_item(path, index, seed, scene_text, settings, image, aovs):
    records, blobs = _encode(_arrays(image, aovs))
    derived = [n for n, other in _DERIVED.items() if other in records and n in image.components]
    meta = dict(settings, index=int(index), item_seed=int(seed), derived=derived,
                render_key=image.attributes.get("nxrender.renderKey", ""),
                wavelengths=[float(w) for w in image.wavelengths],
                arrays=records, scene=scene_text)
    crc = 0
    for blob in blobs:
        crc = zlib.crc32(blob, crc)
    meta["crc32"] = crc
    head = json.dumps(meta).encode()
    temp = f"{path}.tmp{os.getpid()}.{threading.get_ident()}"
    with open(temp, "wb") as f:
        f.write(_MAGIC + len(head).to_bytes(8, "little") + head +
                zlib.crc32(head).to_bytes(4, "little"))
        for blob in blobs:
            f.write(blob)
        f.flush()
        os.fsync(f.fileno())
    os.replace(temp, path)
    return {name: r["bytes"] for name, r in records.items()}


def _remove_leftovers(out, indices):
    """Removes the temporary files an interrupted run of these items left (each item belongs
    to one task, so no other task is writing them)."""
    mine = {os.path.basename(item_path(out, i)) for i in indices}
    folder = os.path.join(out, "items")
    for name in os.listdir(folder):
        stem, sep, _ = name.partition(".nxi.tmp")
        if sep and stem + ".nxi" in mine:
            try:
                os.remove(os.path.join(folder, name))
            except FileNotFoundError:
                pass


def _scene_of(scene_fn, index):
    """(scene, its text) of item `index`, taken when scene_fn returns: a copy, so a generator
    that keeps one Scene and edits it for each index (a sweep) cannot change an item while it
    renders, and the item records what was rendered."""
    import nxrender
    try:
        scene = scene_fn(index)
    except SystemExit as e:  # sys.exit() in a generator is its failure, not the run's end
        raise RuntimeError(f"scene({index}) called sys.exit({e.code!r})") from None
    if isinstance(scene, dict):
        scene = nxrender.Scene.from_dict(scene, f"scene({index})")
    elif isinstance(scene, nxrender.Scene):
        scene = scene.copy()
    else:
        raise TypeError(f"scene({index}): expected an nxrender.Scene or a dict, found "
                        f"{type(scene).__name__}")
    return scene, scene.to_text()


def _whole(value, name, lo, hi=None):
    """value as an int (numpy integers too) within [lo, hi]; errors name the argument."""
    if isinstance(value, bool):
        raise TypeError(f"{name}: expected a whole number, found {value!r}")
    try:
        v = operator.index(value)
    except TypeError:
        raise TypeError(f"{name}: expected a whole number, found {type(value).__name__} "
                        f"{value!r:.40}") from None
    if v < lo or (hi is not None and v > hi):
        bound = f">= {lo}" if hi is None else f"from {lo} to {hi:,}"
        raise ValueError(f"{name}: expected a whole number {bound}, found {v}")
    return v


def generate(scene_fn, count, out, spp=None, aovs=("components",), seed=0, task=None,
             jobs=1, threads=None, log=None, generator=None):
    """Renders items scene_fn(i) of range(count) that belong to this task (see task_split)
    into dataset directory `out`, skipping finished ones; returns a report dict (items
    rendered and skipped, seconds, items per hour, bytes per item per layer). `jobs` items
    render at once, each on threads // jobs of the machine's threads (or `threads`). The
    manifest records the settings and the generator (`generator`, else generator_identity of
    scene_fn): a rerun must match them. It is written with the first item."""
    import concurrent.futures
    import nxrender
    # Every argument checked before anything is written (a failed run leaves nothing behind).
    count = _whole(count, "count", 1, MAX_COUNT)
    jobs = _whole(jobs, "jobs", 1, 4096)
    spp = None if spp is None else _whole(spp, "spp", 1, 1 << 30)
    threads = None if threads is None else _whole(threads, "threads", 1, 4096)
    seed = _whole(seed, "seed", 0, (1 << 32) - 1)
    if isinstance(aovs, str):
        raise TypeError(f"aovs: expected a list of layer names, found the string {aovs!r}")
    aovs = list(aovs)
    for a in aovs:
        if a in ("lightgroups",):
            raise ValueError("aovs: light groups differ between scenes: not in datasets")
    nxrender.check_aovs(aovs)
    ident, tasks = task_split(task)
    settings = _settings(count, spp, aovs, seed,
                         generator if generator is not None else generator_identity(scene_fn))
    out = os.fspath(out)
    manifest_ready = _check_manifest(out, settings)
    os.makedirs(os.path.join(out, "items"), exist_ok=True)
    log = log if log is not None else (lambda text: print(text, file=sys.stderr, flush=True))
    mine = range(ident, count, tasks)
    _remove_leftovers(out, mine)
    todo = [i for i in mine if not _valid(item_path(out, i), i, settings)]
    cores = os.cpu_count() or 1
    per_job = threads if threads is not None else max(1, cores // jobs)
    start = time.monotonic()
    sizes, done = {}, 0
    render_seconds = 0.0

    # `jobs` renders at a time; one more worker writes an item while the next renders (the
    # render and numpy's conversions release the GIL).
    renders = threading.Semaphore(jobs)

    manifest_lock = threading.Lock()

    def render_one(index, scene, text):
        nonlocal manifest_ready
        with renders:
            t = time.monotonic()
            image = nxrender.render(scene, spp=spp, seed=item_seed(seed, index),
                                    threads=per_job, aovs=aovs)
            took = time.monotonic() - t
        with manifest_lock:  # before the first item: created, or another run's checked
            if not manifest_ready:
                _create_manifest(out, settings)
                manifest_ready = True
        written = _write_item(item_path(out, index), index, item_seed(seed, index),
                              text, settings, image, aovs)
        return written, took

    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs + 1) as pool:
        pending = set()
        queue = iter(todo)
        exhausted = False
        while pending or not exhausted:
            while not exhausted and len(pending) < jobs + 1:
                index = next(queue, None)
                if index is None:
                    exhausted = True
                    break
                scene, text = _scene_of(scene_fn, index)  # (the generator runs on this thread)
                pending.add(pool.submit(render_one, index, scene, text))
            if not pending:
                break
            finished, pending = concurrent.futures.wait(
                pending, return_when=concurrent.futures.FIRST_COMPLETED)
            for f in finished:
                written, took = f.result()
                render_seconds += took
                done += 1
                for name, n in written.items():
                    sizes[name] = sizes.get(name, 0) + n
                elapsed = time.monotonic() - start
                log(f"nxdataset: {done}/{len(todo)} items of task {ident}/{tasks} "
                    f"({3600 * done / max(elapsed, 1e-9):.0f} items/hour)")
    seconds = time.monotonic() - start
    report = {"task": f"{ident}/{tasks}", "items": len(mine), "rendered": done,
              "skipped": len(mine) - len(todo), "seconds": seconds,
              "items_per_hour": 3600 * done / seconds if done and seconds > 0 else 0.0,
              "render_seconds": render_seconds,
              "bytes_per_item": {k: v / done for k, v in sorted(sizes.items())} if done else {}}
    if done:
        report["bytes_per_item_total"] = sum(report["bytes_per_item"].values())
    return report


class Dataset:
    """A dataset directory made by generate or nxdataset as a map-style dataset:
    len(data) items, data[i] a dict of numpy arrays (float32; ids int32) by layer name
    (`radiance` (H, W, bands), the component layers, the ground-truth layers), `seed` and
    `index`, as torch.utils.data.DataLoader takes it; `layers` (names) keeps only those (and
    decodes only what they need). data[[i, j, ...]] (or a slice) is a batch: arrays (B, ...),
    decoded into place (loader() reads batches so). Missing or broken items are refused at
    construction (rerun nxdataset), unless allow_missing=True (then only those present)."""

    def __init__(self, root, allow_missing=False, layers=None):
        self.root = os.fspath(root)
        # (None: every layer; else only these are decoded, a derived one with what it needs)
        self.layers = None if layers is None else list(layers)
        if isinstance(self.layers, list) and not all(isinstance(n, str) for n in self.layers):
            raise TypeError(f"layers: expected layer names, found {layers!r:.60}")
        manifest = os.path.join(self.root, _MANIFEST)
        try:
            self.settings = _read_manifest(manifest)
        except FileNotFoundError:
            raise FileNotFoundError(f"{manifest}: not found: not a dataset directory "
                                    "(nxdataset writes one)") from None
        if self.settings.get("format") not in _READABLE_FORMATS:
            raise ValueError(f"{manifest}: expected format {FORMAT}, found "
                             f"{self.settings.get('format')!r}")
        try:
            count = _whole(self.settings.get("count"), "count", 1, MAX_COUNT)
        except (TypeError, ValueError) as e:
            raise ValueError(f"{manifest}: {e}") from None
        # The items present, from one listing of the folder (not a look-up per index).
        pattern = re.compile(r"item_(\d{7,})\.nxi")
        try:
            names = os.listdir(os.path.join(self.root, "items"))
        except FileNotFoundError:
            names = []
        found = set()
        for name in names:
            m = pattern.fullmatch(name)
            if m and int(m.group(1)) < count:
                found.add(int(m.group(1)))
        present = sorted(found)
        if len(present) < count and not allow_missing:
            first = next(i for i in range(count) if i not in found)
            raise ValueError(f"{self.root}: {count - len(present)} of {count} items missing "
                             f"(first: {first}): rerun nxdataset to finish it, or pass "
                             "allow_missing=True")
        self.indices = present
        if self.layers is not None and present:  # names checked once, against an item
            meta = self.meta(0)
            held = set(meta["arrays"]) | set(meta.get("derived", []))
            unknown = [n for n in self.layers if n not in held]
            if unknown:
                raise ValueError(f"layers: no layer {unknown[0]!r} (the items hold "
                                 f"{', '.join(sorted(held))})")

    def __len__(self):
        return len(self.indices)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return self._batch(range(*i.indices(len(self))))
        if isinstance(i, (list, tuple, range)) or getattr(i, "ndim", 0) == 1:
            return self._batch(self._positions(i))
        index, path = self._locate(i)
        try:
            meta, blobs = _read_item(path, reuse=True)
            records, derived = self._plan(meta)
            item = _decode(records, blobs, derived)
            if self.layers is not None:
                item = {name: item[name] for name in self.layers}
        except Exception as e:
            raise _cannot_read(path, index, e) from None
        item["seed"] = int(meta["item_seed"])
        item["index"] = int(index)
        return item

    def loader(self, batch_size, shuffle=False, drop_last=False, **options):
        """A torch DataLoader of batches read as data[[i, j, ...]]: each item decoded into its
        batch slice, not collated by copying (the same dicts of (B, ...) tensors as
        DataLoader(data, batch_size) gives, about 2x faster); options go to DataLoader
        (num_workers, generator, ...)."""
        import torch.utils.data as tud
        order = tud.RandomSampler(self, generator=options.pop("generator", None)) if shuffle \
            else tud.SequentialSampler(self)
        return tud.DataLoader(self, batch_size=None,
                              sampler=tud.BatchSampler(order, batch_size, drop_last), **options)

    def _positions(self, key):
        """The positions a list, tuple, range or 1-d array names; a boolean mask (numpy's
        meaning) as the positions where it is true, refused unless as long as the dataset."""
        dtype = getattr(key, "dtype", None)
        if (dtype is not None and dtype.kind == "b") or \
                (isinstance(key, (list, tuple)) and key and
                 all(isinstance(k, bool) or type(k).__name__ == "bool_" for k in key)):
            mask = list(key)
            if len(mask) != len(self):
                raise IndexError(f"a boolean mask of {len(mask)} values for a dataset of "
                                 f"{len(self)} items")
            return [p for p, keep in enumerate(mask) if keep]
        return list(key)

    def _locate(self, i):
        """(dataset index, file) of position i (an int; negative counts from the end)."""
        if isinstance(i, bool) or type(i).__name__ == "bool_":
            raise TypeError(f"expected an item position (an int), or a list, slice or integer "
                            f"array of them, found the boolean {i!r}")
        try:
            i = operator.index(i)
        except TypeError:
            raise TypeError(f"expected an item position (an int), or a list, slice or integer "
                            f"array of them, found {type(i).__name__} {i!r:.40}") from None
        if not -len(self) <= i < len(self):
            raise IndexError(f"item {i} of a dataset of {len(self)}")
        index = self.indices[i]
        return index, item_path(self.root, index)

    def _plan(self, meta):
        """(records to decode, each with its "offset"; derived layers) of an item's record for
        this dataset's layers."""
        wanted = set(meta["arrays"]) | set(meta.get("derived", []))
        if self.layers is not None:
            unknown = [n for n in self.layers if n not in wanted]
            if unknown:
                raise KeyError(f"no layer {unknown[0]!r} (the items hold "
                               f"{', '.join(sorted(wanted))})")
            wanted = set(self.layers)
            for name, other in _DERIVED.items():
                if name in wanted:
                    wanted |= {"radiance", other}
        _check_shapes(meta)
        records, at = {}, 0
        for name, record in meta["arrays"].items():
            if name in wanted:
                records[name] = dict(record, offset=at)
            at += record["bytes"]
        derived = [name for name in _DERIVED if name in wanted and name in meta.get("derived", [])]
        return records, derived

    def _batch(self, positions):
        """Items at `positions` as one batch: a dict of arrays (B, ...) by layer name, `seed`
        and `index` (B,) int64, each item decoded straight into its slice (what a DataLoader's
        collation gives, without its copy). The items' layers must have one shape."""
        import numpy as np
        positions = list(positions)
        batch = None
        seeds, indices = [], []
        for b, position in enumerate(positions):
            index, path = self._locate(position)
            try:
                meta, blobs = _read_item(path, reuse=True)
                records, derived = self._plan(meta)
                shapes = {name: (tuple(r["shape"]), np.int32 if r["kind"] == "uint32"
                                 else np.float32) for name, r in records.items()}
                for name in derived:
                    shapes[name] = (shapes["radiance"][0], np.float32)
                if batch is None:
                    first = (index, shapes)
                    batch = {name: _batch_array((len(positions),) + shape, dtype)
                             for name, (shape, dtype) in shapes.items()}
                elif shapes != first[1]:
                    raise ValueError(f"its layers ({_describe(shapes)}) differ from item "
                                     f"{first[0]}'s ({_describe(first[1])}): items of different "
                                     "shapes cannot be read as one batch")
                # (outputs in this item's order of arrays, which _decode follows)
                _decode(records, blobs, derived, [_as_numpy(batch[name])[b] for name in shapes])
            except Exception as e:
                raise _cannot_read(path, index, e) from None
            seeds.append(int(meta["item_seed"]))
            indices.append(int(index))
        if batch is None:
            batch = {}
        elif self.layers is not None:
            batch = {name: batch[name] for name in self.layers}
        batch["seed"] = np.array(seeds, np.int64)
        batch["index"] = np.array(indices, np.int64)
        return batch

    def meta(self, i):
        """Item i's record: its index, seed, scene text, options and render key."""
        return _read_item(item_path(self.root, self.indices[i]))[0]


# ---- Random scenes that are plausible (docs/datasets.md, "Random scenes") ----
# Each helper takes a numpy Generator (numpy.random.default_rng(seed)), so a generator seeded
# from its index makes the same scene every time.

_GRID_NM = list(range(360, 831, 10))


def random_reflectance(rng, lo=0.02, hi=0.9):
    """A smooth reflectance spectrum, (wavelengths_nm, values) on 360-830 nm every 10 nm: the
    sigmoid of a random quadratic in the wavelength, the form that represents every sRGB
    reflectance smoothly (Jakob and Hanika, "A Low-Dimensional Function Space for Efficient
    Spectral Upsampling", 2019), mapped into [lo, hi] (natural reflectances lie within about
    0.02-0.9 and vary slowly with wavelength: Maloney 1986, Parkkinen et al. 1989)."""
    import numpy as np
    x = (np.array(_GRID_NM, float) - 595) / 235
    c0, c1, c2 = rng.uniform(-2.5, 2.5), rng.uniform(-5, 5), rng.uniform(-6, 6)
    s = 1 / (1 + np.exp(-(c0 + c1 * x + c2 * x * x)))
    return (list(_GRID_NM), [float(v) for v in lo + (hi - lo) * s])


# Ranges of organic dyes' skew-Cauchy parameters, from the absorption and emission maxima and
# quantum yields of common fluorophores (coumarins, fluorescein, rhodamines, cyanines; J. R.
# Lakowicz, "Principles of Fluorescence Spectroscopy", 3rd ed., Springer 2006, ch. 3): absorption
# peaks 350-650 nm, Stokes shifts 20-120 nm, quantum yields 0.1-0.95; widths as the model's
# curves fit such bands (docs/fluorescence.md).
DYE_RANGES = {"absorption": (350.0, 650.0), "stokes": (20.0, 120.0), "width": (15.0, 40.0),
              "yield": (0.1, 0.95)}


def random_dye(rng):
    """A fluorescent dye within DYE_RANGES, as the scene format's <fluorescence> dict."""
    return {k: round(float(rng.uniform(*r)), 3) for k, r in DYE_RANGES.items()}


# Built-in lamp spectra (docs/spectral-library.md) a scene may be lit by.
LAMPS = ("D65", "D50", "A", "blackbody:3000", "bl")
# Narrow-band LEDs: peaks 400-650 nm, FWHM 15-40 nm (E. F. Schubert, "Light-Emitting Diodes",
# 2nd ed., Cambridge 2006, ch. 12: about 1.8 kT wide in energy, 20-30 nm in the visible).
LED_RANGES = {"peak": (400.0, 650.0), "fwhm": (15.0, 40.0)}


def random_led(rng):
    """A narrow-band LED's spectrum, (wavelengths_nm, values): a Gaussian of a peak and FWHM
    within LED_RANGES, on 360-830 nm every 2 nm, peak 100 (as the CIE illuminants are 100 at
    560 nm)."""
    import numpy as np
    peak, fwhm = rng.uniform(*LED_RANGES["peak"]), rng.uniform(*LED_RANGES["fwhm"])
    nm = np.arange(360, 831, 2.0)
    return ([float(v) for v in nm],
            [float(v) for v in 100 * np.exp(-4 * np.log(2) * ((nm - peak) / fwhm) ** 2)])


def random_lamp(rng, led_share=0.5):
    """A lamp spectrum: a random LED with probability led_share, else one of LAMPS by name."""
    if rng.uniform() < led_share:
        return random_led(rng)
    return str(LAMPS[int(rng.integers(len(LAMPS)))])


def place_on_plane(rng, count, kinds=("sphere", "box", "cylinder"), extent=2.0,
                   size=(0.25, 0.6), gap=0.05, tries=1000):
    """`count` objects of the primitive kinds resting on the plane y = 0 within
    |x|, |z| <= extent, none intersecting another: each placed where its bounding circle on
    the plane, widened by `gap`, meets no other (rejection sampling; fewer objects when there
    is no room after `tries`). Returns shape dicts without materials (add them)."""
    import math
    placed, out = [], []
    for _ in range(tries):
        if len(out) == count:
            break
        kind = kinds[int(rng.integers(len(kinds)))]
        r = float(rng.uniform(*size))
        x, z = (float(v) for v in rng.uniform(-extent + r, extent - r, 2))
        if any(math.hypot(x - px, z - pz) < r + pr + gap for px, pz, pr in placed):
            continue
        placed.append((x, z, r))
        if kind == "sphere":
            out.append({"shape": "sphere", "center": [x, r, z], "radius": r})
        elif kind == "box":
            side = r * math.sqrt(2)  # its diagonal on the plane is the circle's diameter
            turn = float(rng.uniform(0, 90))
            out.append({"shape": "box", "center": [0, side / 2, 0], "size": [side] * 3,
                        "transform": [{"rotate": [0, 1, 0, turn]}, {"translate": [x, 0, z]}]})
        elif kind == "cylinder":
            height = float(rng.uniform(0.5, 2.0)) * r
            out.append({"shape": "cylinder", "p0": [x, 0, z], "p1": [x, height, z],
                        "radius": r, "capped": "true"})
        else:
            raise ValueError(f"kinds: expected sphere, box or cylinder, found {kind!r}")
    return out


def orbit_camera(rng, target=(0.0, 0.3, 0.0), distance=(4.0, 7.0), elevation=(10.0, 45.0),
                 fov=(30.0, 45.0)):
    """A camera on an orbit around `target`: azimuth uniform, elevation (degrees above the
    plane), distance and field of view uniform in their ranges; the scene format's camera
    dict."""
    import math
    a = float(rng.uniform(0, 2 * math.pi))
    e = math.radians(float(rng.uniform(*elevation)))
    d = float(rng.uniform(*distance))
    tx, ty, tz = target
    return {"position": [tx + d * math.cos(e) * math.sin(a), ty + d * math.sin(e),
                         tz - d * math.cos(e) * math.cos(a)],
            "look_at": list(target), "fov": round(float(rng.uniform(*fov)), 3)}


def _load_generator(path):
    import importlib.util
    spec = importlib.util.spec_from_file_location("nxdataset_generator", path)
    if spec is None:
        raise ValueError(f"{path}: expected a Python file defining scene(index)")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    if not callable(getattr(module, "scene", None)):
        raise ValueError(f"{path}: expected a function scene(index), found none")
    return module.scene


def main(argv=None):
    """nxdataset's command line; returns its exit status."""
    import argparse
    parser = argparse.ArgumentParser(
        prog="nxdataset", description="Renders a dataset of many scenes (docs/datasets.md).")
    parser.add_argument("generator", help="a Python file defining scene(index)")
    parser.add_argument("--count", type=int, required=True, help="items 0..N-1")
    parser.add_argument("-o", "--output", required=True, help="the dataset directory")
    parser.add_argument("--spp", type=int, default=None, help="samples per pixel (default: "
                        "the scenes')")
    parser.add_argument("--aov", default="components",
                        help="comma list of layers, as nxrender's --aov (default components)")
    parser.add_argument("--seed", type=int, default=0, help="the dataset's seed (default 0)")
    parser.add_argument("--task", default=None, help="I/N: this task's share (default: a Slurm "
                        "array task's, else all)")
    parser.add_argument("--jobs", type=int, default=1, help="items rendered at once")
    parser.add_argument("--threads", type=int, default=None, help="threads per item")
    args = parser.parse_args(argv)
    try:
        scene_fn = _load_generator(args.generator)
        aovs = [a for a in args.aov.split(",") if a] if args.aov else []
        report = generate(scene_fn, args.count, args.output, spp=args.spp, aovs=aovs,
                          seed=args.seed, task=args.task, jobs=args.jobs, threads=args.threads)
    except (ValueError, TypeError, OSError) as e:
        print(f"nxdataset: error: {e}", file=sys.stderr)
        return 2
    except Exception as e:  # nxrender.Error and what a generator raises
        print(f"nxdataset: error: {type(e).__name__}: {e}", file=sys.stderr)
        return 1
    per = report.get("bytes_per_item", {})
    print(f"nxdataset: task {report['task']}: {report['rendered']} items rendered, "
          f"{report['skipped']} already done, {report['seconds']:.1f} s, "
          f"{report['items_per_hour']:.0f} items/hour")
    if per:
        print("nxdataset: bytes per item: " +
              ", ".join(f"{k} {v / 1e6:.3f} MB" for k, v in per.items()) +
              f"; total {report['bytes_per_item_total'] / 1e6:.3f} MB")
    return 0
