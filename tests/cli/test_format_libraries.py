"""Issue 19: libmatio and libzip are opened at the first .mat or .npz file, and Open MPI only under
an MPI launcher (the plugin spdfit-mpi.so), not at every start of the command line (linked, they
and the HDF5, curl and TLS libraries they pull in were about half of its start-up time). The
dynamic loader's own log (LD_DEBUG=files) says which libraries a run opened: none of them for a
fit from CSV files, libmatio for a .mat file, libzip for an .npz."""
import os
import re
import subprocess

import numpy as np
import pytest
import scipy.io

from spdfit_testing import SLOWDOWN, cli_path

ON_DEMAND = ("libmatio", "libzip", "libhdf5", "libmpi", "spdfit-mpi")


def opened_libraries(*args):
    """The shared libraries the loader opened for `spdfit args` (its LD_DEBUG=files log), and
    the run's output."""
    env = dict(os.environ, LD_DEBUG="files")
    r = subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True, env=env,
                       timeout=60 * SLOWDOWN)
    assert r.returncode == 0, r.stderr[-2000:]
    opened = set(re.findall(r"file=(\S+) \[\d+\];  (?:needed|dynamically loaded) by", r.stderr))
    return opened, r


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("formats")
    rng = np.random.default_rng(19)
    A = rng.standard_normal((20, 3))
    B = A @ np.diag([1.0, 2.0, 3.0]) + 1e-3 * rng.standard_normal((20, 3))
    np.savetxt(folder / "A.csv", A, delimiter=",")
    np.savetxt(folder / "B.csv", B, delimiter=",")
    scipy.io.savemat(folder / "A.mat", {"A": A})
    np.savez(folder / "A.npz", A=A)
    return folder


def test_a_fit_from_csv_opens_neither_a_format_library_nor_mpi(files):
    opened, _ = opened_libraries("fit", "-m", "spde", files / "A.csv", files / "B.csv")
    # The log names the libraries linked at start (else the check below would pass vacuously).
    assert any(name.startswith("libc.so") for name in opened), opened
    assert not [name for name in opened if os.path.basename(name).startswith(ON_DEMAND)], opened


def test_a_mat_file_opens_libmatio_and_reads_the_same_numbers(files):
    opened, r = opened_libraries("fit", "-m", "spde", files / "A.mat", files / "B.csv")
    assert any(name.startswith("libmatio") for name in opened), opened
    assert not any(name.startswith("libzip") for name in opened), opened
    csv = subprocess.run([cli_path(), "fit", "-m", "spde", files / "A.csv", files / "B.csv"], capture_output=True, text=True,
                         timeout=60 * SLOWDOWN)
    assert r.stdout == csv.stdout


def test_an_npz_archive_opens_libzip_and_not_libmatio(files):
    opened, r = opened_libraries("fit", "-m", "spde", files / "A.npz", files / "B.csv")
    assert any(name.startswith("libzip") for name in opened), opened
    assert not any(name.startswith(("libmatio", "libhdf5")) for name in opened), opened
