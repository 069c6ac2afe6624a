"""nxbench-dataset: the bytes and the reading speed of a dataset at the trial's settings.

    build/nxpython apps/python/nxbench_dataset.py [--count 24] [--dir DIR] [--repeat 3]

Renders COUNT items of the trial's kind of scene (a plane, a fluorescent sphere, a box and a
rough gold sphere under a point light, from an orbiting camera; 128 x 128, 31 bands, 64 spp,
components, ids and depth) with nxrender.dataset.generate, then prints the bytes per item and
the items per second of Dataset (every layer; radiance and reflected; radiance alone; batches
of 8 as data[[i, ...]]) and of torch DataLoaders (batches of 8: collated from single items, and
Dataset.loader's, decoded into place) when torch is installed, from the page cache (the fastest
of `repeat` passes). docs/datasets.md quotes its figures."""

import argparse
import collections
import os
import sys
import tempfile
import time


def scene(index):
    """The trial's kind of scene, its camera orbiting with the index."""
    import math
    angle = 0.7 * index
    return {
        "settings": {"xres": 128, "yres": 128, "mode": "spectral_mcpt", "sampl": 64,
                     "bands": "400:710:10"},
        "camera": {"position": [5 * math.sin(angle), 2.5, -5 * math.cos(angle)],
                   "look_at": [0, 0.5, 0]},
        "objects": [
            {"shape": "plane", "normal": [0, 1, 0], "distance": 0, "material": "matte",
             "reflectance": 0.5},
            {"shape": "sphere", "center": [-0.8, 0.6, 0], "radius": 0.6, "material": "matte",
             "reflectance": 0.6, "fluorescence": {"absorption": "blue", "stokes": 80}},
            {"shape": "box", "center": [0.9, 0.4, 0.3], "size": [0.8, 0.8, 0.8],
             "material": "matte", "reflectance": 0.4},
            {"shape": "sphere", "center": [0.2, 0.35, -1.0], "radius": 0.35,
             "material": "conductor", "metal": "gold", "alpha": 0.15},
        ],
        "lights": [{"type": "point", "position": [1, 4, -2], "color": [1, 1, 1],
                    "emission": 40}],
    }


def drain(values):
    """Runs through an iterable, keeping nothing (each item freed before the next is read)."""
    collections.deque(values, maxlen=0)


def fastest(run, repeat):
    """The seconds of the fastest of `repeat` calls of run()."""
    best = float("inf")
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - start)
    return best


def rate(read, count, repeat):
    """Items per second of read(i) over every item, the fastest of `repeat` passes."""
    return count / fastest(lambda: drain(read(i) for i in range(count)), repeat)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=24)
    parser.add_argument("--dir", default=None, help="where to write it (default: a temporary one)")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    import nxrender.dataset
    with tempfile.TemporaryDirectory() as temp:
        out = args.dir or os.path.join(temp, "data")
        nxrender.dataset.generate(scene, args.count, out, aovs=("components", "ids", "depth"),
                                  log=lambda text: None)
        items = [nxrender.dataset.item_path(out, i) for i in range(args.count)]
        size = sum(os.path.getsize(p) for p in items) / args.count
        print(f"{args.count} items of 128 x 128, 31 bands, 64 spp, components, ids, depth: "
              f"{size / 1e6:.2f} MB per item")
        for layers, label in ((None, "every layer"), (["radiance", "reflected"],
                                                      "radiance, reflected"),
                              (["radiance"], "radiance")):
            data = nxrender.dataset.Dataset(out, layers=layers)
            print(f"Dataset[i], {label}: {rate(data.__getitem__, len(data), args.repeat):.0f} "
                  "items/s")
        data = nxrender.dataset.Dataset(out)
        batches = [list(range(i, min(i + 8, len(data)))) for i in range(0, len(data), 8)]
        seconds = fastest(lambda: drain(data[batch] for batch in batches), args.repeat)
        print(f"Dataset[[i, ...]], batches of 8, every layer: {len(data) / seconds:.0f} items/s")
        try:
            import torch.utils.data
        except ImportError:
            print("DataLoader: torch not installed")
            return 0
        for workers, how in ((0, "collated"), (0, "loader()"), (2, "collated"), (2, "loader()")):
            loader = torch.utils.data.DataLoader(data, batch_size=8, num_workers=workers) \
                if how == "collated" else data.loader(8, num_workers=workers)
            seconds = fastest(lambda: drain(loader), args.repeat)  # noqa: B023 (called here)
            print(f"DataLoader, batches of 8, {how}, {workers} workers, every layer: "
                  f"{len(data) / seconds:.0f} items/s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
