"""impactkit in Jupyter: a kernel's interrupt (the notebook's stop button)
stops a long call with KeyboardInterrupt, binds nothing, and leaves the
kernel usable, with a progress bar drawn meanwhile; and the paper's
notebook (examples/notebooks/paper.ipynb) runs headless to its end, its
cells asserting what they show and writing its figures."""

import os
import queue
import time

import nbformat
import numpy as np
from jupyter_client.manager import KernelManager
from nbclient import NotebookClient

import impactkit

SOURCE = os.environ["IMPACTKIT_SOURCE_DIR"]
# A map of 20000 rows of 20 values (a quarter of an hour), reporting after
# each row.
LONG_MAP = ("impactkit.parameter_map(impactkit.System.paper(), from_=1.7, to=1.9, steps=20, "
            "from2=0.6, to2=0.8, steps2=20000, transient_periods=200, recorded_periods=50, "
            "progress={progress})")
SMALL_MAP = dict(from_=1.7, to=1.9, steps=3, from2=0.6, to2=0.8, steps2=2,
                 transient_periods=200, recorded_periods=40)


def run_cell(client, code, timeout=60):
    """Executes `code`; returns (reply content, what it printed to stdout and
    stderr, as two strings)."""
    msg_id = client.execute(code)
    out, err = [], []
    deadline = time.monotonic() + timeout
    while True:
        message = client.get_iopub_msg(timeout=max(1.0, deadline - time.monotonic()))
        if message["parent_header"].get("msg_id") != msg_id:
            continue
        if message["msg_type"] == "stream":
            (out if message["content"]["name"] == "stdout" else err).append(
                message["content"]["text"])
        if message["msg_type"] == "status" and message["content"]["execution_state"] == "idle":
            break
    return client.get_shell_msg(timeout=timeout)["content"], "".join(out), "".join(err)


def test_a_kernel_interrupt_stops_a_long_map_and_the_kernel_goes_on():
    manager = KernelManager(kernel_name="python3")
    manager.start_kernel(env=dict(os.environ), cwd=SOURCE)
    client = manager.client()
    client.start_channels()
    try:
        client.wait_for_ready(timeout=60)
        reply, _, _ = run_cell(client, "import impactkit")
        assert reply["status"] == "ok"
        # The long call, its progress drawn by tqdm (a text bar on stderr
        # without ipywidgets): interrupted once its first report is seen.
        # stop_on_error=False: the interrupt's error must not make the kernel
        # abort the requests that follow (ipykernel does by default, racing
        # with the next cell).
        msg_id = client.execute("grid = " + LONG_MAP.format(progress="True"),
                                stop_on_error=False)
        bar = ""
        while "/400000" not in bar:  # tqdm's first line: 0/400000 cells
            message = client.get_iopub_msg(timeout=60)
            if (message["parent_header"].get("msg_id") == msg_id
                    and message["msg_type"] == "stream"):
                bar += message["content"]["text"]
        interrupted = time.monotonic()
        manager.interrupt_kernel()
        while True:
            reply = client.get_shell_msg(timeout=60)
            if reply["parent_header"].get("msg_id") == msg_id:
                break
        assert time.monotonic() - interrupted < 10
        assert reply["content"]["status"] == "error"
        assert reply["content"]["ename"] == "KeyboardInterrupt"
        assert "grid:" in bar  # tqdm's description is the stage
        # Nothing was bound, and the kernel computes what a fresh process does.
        reply, out, _ = run_cell(client, "print('grid' in dir())")
        assert reply["status"] == "ok" and out.strip() == "False"
        reply, out, _ = run_cell(
            client, "small = impactkit.parameter_map(impactkit.System.paper(), **%r)\n"
            "print(*small['kind'].ravel()); print(*[x.hex() for x in small['max_velocity'].ravel()])"
            % SMALL_MAP)
        assert reply["status"] == "ok", reply
        here = impactkit.parameter_map(impactkit.System.paper(), **SMALL_MAP)
        kinds, speeds = out.splitlines()
        assert kinds.split() == list(here["kind"].ravel())
        np.testing.assert_array_equal([float.fromhex(x) for x in speeds.split()],
                                      here["max_velocity"].ravel())
    finally:
        client.stop_channels()
        manager.shutdown_kernel(now=True)


def test_the_paper_notebook_runs_to_its_end(tmp_path):
    path = os.path.join(SOURCE, "examples", "notebooks", "paper.ipynb")
    notebook = nbformat.read(path, as_version=4)
    figures = tmp_path / "figures"
    # The notebook writes its figures where IMPACTKIT_FIGURES says.
    os.environ["IMPACTKIT_FIGURES"] = str(figures)
    try:
        NotebookClient(notebook, timeout=300, kernel_name="python3",
                       resources={"metadata": {"path": os.path.dirname(path)}}).execute()
    finally:
        del os.environ["IMPACTKIT_FIGURES"]
    errors = [output for cell in notebook.cells if cell.cell_type == "code"
              for output in cell.get("outputs", []) if output.output_type == "error"]
    assert not errors
    written = sorted(p.name for p in figures.glob("*.png"))
    assert written == ["basins.png", "fig3_sweep.png", "omega_r_map.png", "p11_branch.png"]
    assert all((figures / name).stat().st_size > 10000 for name in written)
