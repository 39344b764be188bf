"""Shared fixtures. Records are read from <repository root>/../shared/data/records,
never copied into the project; a missing folder or file skips with the reason."""
import os
from pathlib import Path

import pytest

# A command's first run takes the SciPy reference while the compiled kernel it needs is not
# built (analytic.engines.first_run_reference): in a session that builds the kernels as it
# goes, which path served would depend on the order tests ran in. The suite asks for the
# kernel throughout; tests/test_first_run.py tests the reference path on its own.
os.environ.setdefault("ISOROCK_FIRST_RUN", "kernel")

ROOT = Path(__file__).resolve().parent.parent


def pytest_addoption(parser):
    parser.addoption("--regenerate-golden", action="store_true", default=False,
                     help="write tests/golden/<engine>.json from this run instead of comparing with it "
                          "(only after checking that a change of numbers is intended)")
RECORDS = ROOT.parent / "shared" / "data" / "records"


def pytest_xdist_auto_num_workers(config):
    """`-n auto` (pyproject's addopts): the cores this process may use, not the host's
    (os.cpu_count() in a container counts the machine's), at most 4 (each worker loads
    MuJoCo, PyBullet and Drake)."""
    import os
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    return max(1, min(4, cores))


@pytest.fixture(scope="session")
def records_dir() -> Path:
    if not RECORDS.is_dir():
        pytest.skip(f"shared records folder not found at {RECORDS} (expected beside the repository)")
    return RECORDS


def _record(records_dir: Path, name: str) -> Path:
    path = records_dir / name
    if not path.is_file():
        pytest.skip(f"{path} not found")
    return path


@pytest.fixture(scope="session")
def kobe_at2(records_dir) -> Path:
    """1995 Kobe JMA N-S, PEER NGA AT2 (g), 7500 points at 0.02 s."""
    return _record(records_dir, "RSN1106_KOBE_KJM000.AT2")


@pytest.fixture(scope="session")
def kobe_jma(records_dir) -> Path:
    """The same record as JMA distributes it (gal), 2567 points at 0.02 s."""
    return _record(records_dir, "KOBE_NS")


@pytest.fixture
def char_device(tmp_path):
    """char_device("null" | "full"): a character device to write to. As root, a node of
    its own in tmp_path (a regression that replaces the path must not replace the machine's
    /dev/null); as another user, /dev/null or /dev/full, which that user cannot replace."""
    import os
    import stat
    numbers = {"null": (1, 3), "full": (1, 7)}

    def make(name):
        if os.geteuid() != 0:
            return Path("/dev") / name
        node = tmp_path / f"dev-{name}"
        try:
            os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(*numbers[name]))
        except OSError as e:
            pytest.skip(f"cannot make a device node as root here ({e.strerror})")
        return node
    return make


#: a session of at least this many tests starts the isolator kernel's build in a second
#: process at its start (its own run would wait for it there, a minute or two on a fresh
#: checkout, with the machine's second core idle)
BACKGROUND_BUILD_FROM = 200


#: the suite's longest tests (pytest --durations, 8–50 s each on the 2 shared cores), started
#: first: pytest-xdist hands tests out in order, and one of these drawn last kept one worker
#: busy for its whole length after the other had finished. Only the order: a name that goes
#: stale runs in its place. (test_plugins' are left in place: their module's fixture, a pip
#: install, would be made twice.)
LONGEST_FIRST = (
    "test_stress.py::test_quick_edges_and_draws_pass_on_every_grid_engine",
    "test_scorecard.py::test_a_quick_scorecard_of_the_fast_engines",
    "test_statue_engines.py::test_a_config_files_statue_table",
    "test_experiments_fit.py::test_a_model_fitted_on_some_records_predicts",
    "test_mjx.py::test_a_compiled_chunk_is_kept_for_the_next_process",
    "test_two_components_drake.py::test_a_zero_second_component_on_the_linear_isolator",
    "test_two_components_drake.py::test_a_zero_second_component_on_a_fixed_base",
    "test_sliding_kernel.py::test_kernel_is_the_reference_on_random_sliding_cases",
    "test_statue_engines.py::test_validate_a_statue_skips_the_engine_that_cannot_carry_it",
    "test_api.py::test_a_report_from_a_script_without_a_main_guard",
    "test_statue_drake.py::test_run_a_statue_on_drake_from_the_command_line",
    "test_verdict.py::test_the_rule_recomputed_on_the_papers_record",
    "test_two_components_dart.py::test_run_reports_the_3d_numbers_for_dart",
    "test_mjx.py::test_a_batch_is_its_runs_alone",
    "test_light_install.py::test_validate_runs_without_any_extra",
    "test_statue_engines.py::test_a_statues_report_names_the_statue",
    "test_statue_dart.py::test_the_bust_at_a_quarter_of_its_size",
    "test_two_components_dart.py::test_the_block_shaken_along_y_alone",
    "test_two_components_drake.py::test_turning_the_pair_and_the_statue_by_one_angle",
    "test_fast.py::test_random_pulses_summary_matches_reference",
    "test_experiments.py::test_command_runs_bullet_on_a_real_test",
    "test_campaign.py::test_fragility_comparison_and_agreement_map",
)


def _place(item) -> tuple[int, int]:
    """Longest first (in LONGEST_FIRST's order), the isolator_kernel tests last: on a fresh
    checkout without built kernels they would wait for the kernel's background build with this
    process idle."""
    if item.get_closest_marker("isolator_kernel") is not None:
        return (2, 0)
    node = item.nodeid.rpartition("/")[2]
    for k, name in enumerate(LONGEST_FIRST):
        if node.startswith(name):
            return (0, k)
    return (1, 0)


def pytest_collection_modifyitems(items):
    """The order the tests are handed out in (_place; otherwise the order collected)."""
    items.sort(key=_place)


def _build_in_background(session):
    """A process building the non-linear isolators' kernel (`fast._integrate_iso`) while
    this one builds the linear one and runs the tests before any needs it; a test that
    needs it first waits for that build (kernel_cache's build lock) instead of starting
    its own. None where it is built already, the session is short, or the JIT is asked for."""
    import os
    import subprocess
    import sys
    if len(session.items) < BACKGROUND_BUILD_FROM or os.environ.get("ISOROCK_KERNEL") == "jit":
        return None
    from isorock.analytic import fast, kernel_cache
    if kernel_cache.is_built(fast._integrate_iso):
        return None
    code = "from isorock.analytic import fast, kernel_cache\nkernel_cache.prepare(fast._integrate_iso)\n"
    return subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


@pytest.fixture(scope="session", autouse=True)
def compiled_analytic_kernel(request):
    """Load (on a new machine: compile, ~1–2 min) the analytic kernel once, before any test
    reads what a command printed: its one-time 'compiling …' lines on stderr belong to no
    test's output. The isolator kernel is built beside it in a second process."""
    builder = None
    try:
        import numpy as np

        builder = _build_in_background(request.session)
        from isorock.analytic.motion import GroundMotion, load_motion
        from isorock.analytic.system import paper_system
        from isorock.validate.core.engines import get_engine
        # every kind of input the kernel specializes on: no motion, a pulse, a record
        motions = (None, load_motion("sine:amp=0.6,freq=1.3,cycles=1"),
                   GroundMotion.from_array(np.array([0.0, 0.5, -0.5, 0.0]), dt=0.02, units="g"))
        for system in (paper_system(), paper_system(fixed_base=True)):
            for motion in motions:
                get_engine("analytic").simulate(system, motion, duration=0.5, theta0=0.3 * system.alpha)
    except ImportError:  # numba missing: the tests that need the kernel say so themselves
        pass
    yield
    if builder is not None and builder.poll() is None:  # a session that never needed it
        builder.kill()  # its half build's folder goes with the next build (clear_leftovers)
        builder.wait()
