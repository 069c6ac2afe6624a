"""The GIL is released while rendering, Ctrl-C stops a render cleanly, progress reaches the
caller's thread, and renders on several Python threads at once are those rendered alone."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import nxrender


def test_other_python_threads_run_while_rendering(scenes):
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    t = threading.Thread(target=ticker)
    start = time.monotonic()
    t.start()
    nxrender.render(scenes / "blacklight.scn", spp=16, threads=1)
    end = time.monotonic()
    stop.set()
    t.join()
    during = [x for x in ticks if start < x < end]
    # with the GIL held for the whole render the ticker would not run at all; released, it
    # runs about every millisecond: require a tenth of that, and no gap of half the render
    assert end - start > 0.2
    assert len(during) > 0.1 * (end - start) / 0.001
    gaps = np.diff([start] + during + [end])
    assert gaps.max() < 0.5 * (end - start)


def test_progress_on_the_calling_thread(scenes):
    calls = []
    caller = threading.get_ident()
    nxrender.render(scenes / "white_floor.scn", spp=16,
                    progress=lambda done, total: calls.append((done, total, threading.get_ident())))
    assert calls, "progress was never called"
    assert all(ident == caller for _, _, ident in calls)
    done = [d for d, _, _ in calls]
    assert done == sorted(done) and len(set(done)) == len(done)
    assert calls[-1][0] == calls[-1][1] > 0


def test_exception_in_progress_stops_the_render(scenes):
    class Stop(Exception):
        pass

    def progress(done, total):
        raise Stop()

    start = time.monotonic()
    with pytest.raises(Stop):
        nxrender.render(scenes / "blacklight.scn", spp=4096, progress=progress)
    assert time.monotonic() - start < 30


def test_ctrl_c_stops_the_render(scenes):
    """SIGINT during a long render raises KeyboardInterrupt once the workers stopped (the
    whole render would take minutes)."""
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            nxrender.render(scenes / "blacklight.scn", spp=1 << 16)
    finally:
        timer.cancel()
    assert time.monotonic() - start < 30
    # the module is usable afterwards
    assert nxrender.render(scenes / "white_floor.scn", spp=1).radiance.shape == (90, 160, 60)


def test_concurrent_renders_equal_sequential(scenes):
    scene = scenes / "blacklight.scn"
    alone = [nxrender.render(scene, spp=4, seed=s).radiance for s in (1, 2)]
    results = {}

    def work(seed):
        results[seed] = nxrender.render(scene, spp=4, seed=seed, threads=1).radiance

    threads = [threading.Thread(target=work, args=(s,)) for s in (1, 2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert np.array_equal(results[1], alone[0]) and np.array_equal(results[2], alone[1])
    assert not np.array_equal(alone[0], alone[1])


def test_adaptive_sampling_as_the_command_line(scenes, tmp_path, run_cli):
    image = nxrender.render(scenes / "glass.scn", spp=512, target_error=0.8, adaptive=True,
                            threads=2)
    assert image.attributes["nxrender.sampleRange"] == "0:512"
    assert image.attributes["nxrender.adaptive"] == "target 0.8 of luminance"
    counts = image.sample_count
    assert counts.min() >= 16 and counts.max() > counts.min()
    out = tmp_path / "a.exr"
    code, err = run_cli("--threads", "1", "--spp", "512", "--adaptive", "--target-error", "0.8",
                        "-o", out, scenes / "glass.scn")
    assert code == 0, err
    assert "adaptive: reached the target error" in err
    cli = nxrender.read_exr(out)
    assert np.array_equal(cli.sample_count, counts)
    assert np.array_equal(cli.radiance, image.radiance)
    with pytest.raises(ValueError, match="^adaptive: expected a target_error"):
        nxrender.render(scenes / "glass.scn", spp=16, adaptive=True)


def test_target_error_stops_early(scenes):
    image = nxrender.render(scenes / "white_floor.scn", spp=4096, target_error=0.05)
    reached = int(image.attributes["nxrender.sampleRange"].split(":")[1])
    assert 0 < reached < 4096
    assert (image.sample_count == reached).all()
