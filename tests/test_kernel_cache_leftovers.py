"""The kernel cache (issue 24, item 16): a damaged module in the first cache folder that
cannot be removed (an unwritable package folder) must not hide a good kernel in a later
one (every run recompiled for 33 s), and it is said in one line at most; a killed
build's `.build-*` folder is cleared by the next build."""
from __future__ import annotations

import os
import shutil

import pytest

from isorock.analytic import fast, kernel_cache


@pytest.fixture
def fresh(monkeypatch):
    monkeypatch.setattr(kernel_cache, "_aot_loaded", {})

    def no_build(*a, **k):
        raise AssertionError("rebuilt although a good kernel was cached")
    monkeypatch.setattr(kernel_cache, "_build_module", no_build)
    return monkeypatch


def test_a_damaged_module_that_cannot_be_removed_does_not_hide_a_good_one(tmp_path, fresh, capsys):
    dispatcher = fast._integrate
    name = kernel_cache._module_name(dispatcher)
    good = kernel_cache._find_module(name)
    assert good is not None  # this checkout's kernel, built by earlier tests or runs
    first, second = tmp_path / "pkg", tmp_path / "xdg"
    first.mkdir()
    second.mkdir()
    suffix = good[good.index(name) + len(name):]
    (first / (name + suffix)).write_bytes(b"")  # a 0-byte module
    shutil.copyfile(good, second / (name + suffix))
    fresh.setattr(kernel_cache, "cache_dirs", lambda: [str(first), str(second)])
    real_remove = os.remove
    fresh.setattr(kernel_cache.os, "remove", lambda p: (_ for _ in ()).throw(PermissionError(13, "read-only"))
                  if str(p).startswith(str(first)) else real_remove(p))
    fn = kernel_cache._aot_function(dispatcher)
    assert fn is not None
    err = capsys.readouterr().err
    assert err.count("\n") <= 1, err


def test_a_killed_builds_leftovers_are_cleared(tmp_path, monkeypatch):
    stale = tmp_path / ".build-999999999-abc"  # a process id that is not running
    stale.mkdir()
    (stale / "kernel.c").write_text("half a build")
    live = tmp_path / f".build-{os.getpid()}-xyz"  # this process's own build: kept
    live.mkdir()
    kernel_cache.clear_leftovers(str(tmp_path))
    assert not stale.exists() and live.exists()


# --- leftovers in the user's folder -----------------------------------------------------

BLOCK = ["--height", "2", "--width", "0.7", "--mass", "3800", "--base-mass", "3800", "--fixed-base"]


def _in(folder, argv, capsys):
    from isorock.validate.cli.main import main
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        code = main(argv)
    finally:
        os.chdir(cwd)
    return code, capsys.readouterr().err


def test_scene_out_with_a_trailing_slash_is_refused(tmp_path, capsys):
    code, err = _in(tmp_path, ["scene", "--engine", "mujoco", "--out", "newdir/"], capsys)
    assert code == 2 and err.count("\n") == 1 and "file path" in err
    assert list(tmp_path.iterdir()) == []


def test_stress_writes_no_hypothesis_folder_where_it_runs(tmp_path, capsys):
    code, _ = _in(tmp_path, ["stress", "--quick", "--drawn", "2", "--engines", "analytic", "--out", "st"], capsys)
    assert code == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["st"]


@pytest.mark.parametrize("option, value, why", [("--speed", "1e-6", "MAX_FRAMES"), ("--fps", "1e6", "below 10000")])
def test_view_bounds_its_frames_and_says_why(tmp_path, capsys, option, value, why):
    code, err = _in(tmp_path, ["view", *BLOCK, "--motion", "sine:amp=0.2,freq=1", "--out", "v.gif", option, value],
                    capsys)
    assert code == 2 and err.count("\n") == 1 and why in err, err
    assert list(tmp_path.iterdir()) == []


def test_a_killed_writers_staging_files_are_cleared_by_the_next_write(tmp_path, capsys):
    stale = tmp_path / ".isorock-staging-999999999-x.json.abc123"  # its writer was killed with SIGKILL
    stale.write_text("half a file")
    code, _ = _in(tmp_path, ["run", *BLOCK, "--theta0", "0.5", "--duration", "1", "--json", "x.json"], capsys)
    assert code == 0 and sorted(p.name for p in tmp_path.iterdir()) == ["x.json"]


def test_threads_that_all_need_an_unbuilt_kernel_build_it_once(monkeypatch):
    """simulate_batch's threads all call a kernel on its first use: each built it side by
    side (`isorock design --isolator friction-pendulum` on a fresh checkout compiled
    _integrate_iso twice, 91 and 120 s); the later threads now wait and load the first's."""
    import threading
    import time
    monkeypatch.setattr(kernel_cache, "_aot_loaded", {})
    monkeypatch.setattr(kernel_cache, "_find_modules", lambda name: [])  # nothing cached yet
    monkeypatch.setattr(kernel_cache, "_pycc", lambda: None)
    builds = []

    def build(dispatcher, name):
        builds.append(name)
        time.sleep(0.2)  # long enough for every thread to arrive while it builds
        raise OSError("no compiler here")  # the JIT kernel serves: all threads get None
    monkeypatch.setattr(kernel_cache, "_build_module", build)
    got = []
    threads = [threading.Thread(target=lambda: got.append(kernel_cache._aot_function(fast._integrate)))
               for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(builds) == 1 and got == [None] * 4
