"""Progress of the long calls (the library's RunControl): a callable gets
each report, True draws a tqdm bar, and what the callable raises stops the
run and reaches the caller."""

import pytest

import impactkit


@pytest.fixture(scope="module")
def start():
    system = impactkit.System.paper(1.65)
    return system, impactkit.find_orbit(system, p=1, q=1)


def test_a_sweep_reports_each_value_once_in_order():
    reports = []
    run = impactkit.sweep(impactkit.System.paper(), from_=0.6, to=0.64, steps=5,
                          transient_periods=50, recorded_periods=10, threads=2, chunk_values=2,
                          progress=reports.append)
    assert [r["done"] for r in reports] == [1, 2, 3, 4, 5]
    assert all(r["stage"] == "sweep" and r["total"] == 5 for r in reports)
    # A sweep's values finish out of order: no point to say where it is.
    assert all(r["parameter"] is None and r["parameter2"] is None for r in reports)
    assert run["termination"] == "completed"


def test_a_branch_reports_each_point_it_accepts(start):
    system, orbit = start
    reports = []
    branch = impactkit.continue_branch(system, orbit, from_=1.65, to=1.7, progress=reports.append)
    # Every point after the start, where the branch is.
    assert [r["done"] for r in reports] == list(range(1, len(branch)))
    assert [r["parameter"] for r in reports] == list(branch.values[1:])
    assert all(r["stage"] == "branch" and r["total"] == 0 for r in reports)


def test_a_grid_reports_its_cells():
    reports = []
    grid = impactkit.parameter_map(impactkit.System.paper(), from_=1.7, to=1.8, steps=2,
                                   from2=0.7, to2=0.75, steps2=2, transient_periods=50,
                                   recorded_periods=10, progress=reports.append)
    assert reports[-1]["done"] == reports[-1]["total"] == grid["kind"].size
    assert all(r["stage"] == "grid" for r in reports)


def test_true_draws_a_tqdm_bar(start, capfd):
    pytest.importorskip("tqdm")
    system, orbit = start
    impactkit.continue_branch(system, orbit, from_=1.65, to=1.7, progress=True)
    assert "branch" in capfd.readouterr().err


@pytest.mark.parametrize("progress", ["yes", 3])
def test_progress_that_is_no_flag_or_callable_is_a_value_error(progress):
    with pytest.raises(ValueError, match="progress must be True, False or a callable"):
        impactkit.sweep(impactkit.System.paper(), from_=0.6, to=0.62, steps=2,
                        transient_periods=10, recorded_periods=5, progress=progress)


def test_what_the_callable_raises_stops_the_run(start):
    system, orbit = start

    def stop(report):
        if report["done"] == 3:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        impactkit.continue_branch(system, orbit, from_=1.65, to=1.8, progress=stop)
