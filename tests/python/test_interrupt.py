"""Ctrl-C (SIGINT) during a render raises KeyboardInterrupt after the current pass; the GIL is
released while a pass renders."""
import os
import signal
import threading
import time

import pytest

import caustica
from conftest import CORNELL


def test_sigint_from_the_progress_callback_stops_after_that_pass():
    scene = caustica.load_scene(CORNELL, width=16, height=16)
    seen = []

    def progress(p):
        seen.append(p["spp"])
        if len(seen) == 2:
            os.kill(os.getpid(), signal.SIGINT)  # raised right here, in Python code

    r = caustica.Renderer(scene, spp=50, spp_per_pass=1)
    with pytest.raises(KeyboardInterrupt):
        r.run(progress)
    # The exception leaves the loop at once: no pass after the second.
    assert seen == [1, 2]
    assert r.progress()["spp"] == 2 and not r.finished
    assert r.develop().shape == (16, 16, 3)  # the render stays usable


def test_sigint_while_rendering_stops_after_the_current_pass():
    # The signal arrives while C++ renders (GIL released): Python's handler only sets a flag, and
    # the loop's check after the pass raises it.
    scene = caustica.load_scene(CORNELL, width=32, height=32)
    seen = []
    r = caustica.Renderer(scene, time=60, spp_per_pass=1)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        r.run(lambda p: seen.append(p["spp"]))
    timer.join()
    assert time.monotonic() - start < 20 and not r.finished
    # Every pass but the last reported progress; the interrupted one completed, none followed.
    assert r.progress()["spp"] == len(seen) + 1


def test_sigint_during_step_raises_after_it():
    scene = caustica.load_scene(CORNELL, width=64, height=64)
    r = caustica.Renderer(scene, spp=1 << 20, spp_per_pass=64, threads=1)  # one pass: a second
    timer = threading.Timer(0.1, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        r.step()
    timer.join()
    assert r.progress()["spp"] == 64


def test_gil_is_released_while_rendering():
    scene = caustica.load_scene(CORNELL, width=64, height=64)
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.001)

    r = caustica.Renderer(scene, spp=1 << 20, spp_per_pass=64, threads=1)
    t = threading.Thread(target=count)
    t.start()
    start = time.monotonic()
    r.step()  # one long pass: the other thread runs meanwhile
    end = time.monotonic()
    done.set()
    t.join()
    assert end - start > 0.05
    assert sum(start < x < end for x in ticks) >= 5
