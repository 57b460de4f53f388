"""Damaged level-5 .mat files whose declared sizes libmatio would allocate (4 GB to 2^64 bytes)
before reading the bytes (tests/support/level5_mat.py builds one for each path): spdfit checks the
file's structure the way libmatio reads it and refuses each with its own message, naming the
file, within the hostile-file limits on time and memory (conftest.py: RLIMIT_AS of 256 MB outside
the sanitizer build, under which libmatio's allocation would fail and give another message)."""
import pytest

import level5_mat


@pytest.mark.parametrize("file", sorted(level5_mat.CRAFTED))
def test_a_size_libmatio_would_allocate_is_refused_before_it_reads(rejects, tmp_path, file):
    data, fragment = level5_mat.CRAFTED[file]
    path = tmp_path / file
    path.write_bytes(data)
    # spdfit's own message: its check ran before libmatio read the file.
    rejects(["fit", "--method", "ls", path, path], path, ": is a damaged .mat file (", fragment)


def write_mat73(path, datasets):
    """A MATLAB 7.3 file (HDF5 after a 512-byte MATLAB header): name -> (MATLAB class, options of
    h5py's create_dataset)."""
    h5py = pytest.importorskip("h5py")
    import numpy as np
    with h5py.File(path, "w", userblock_size=512) as f:
        for name, (matlab_class, options) in datasets.items():
            dataset = f.create_dataset(name, **options)
            text = matlab_class.encode()
            string = h5py.h5t.C_S1.copy()
            string.set_size(len(text))
            string.set_strpad(h5py.h5t.STR_NULLTERM)
            attribute = h5py.h5a.create(dataset.id, b"MATLAB_class", string, h5py.h5s.create(h5py.h5s.SCALAR))
            attribute.write(np.array(text, dtype=f"S{len(text)}"), mtype=string)
    with open(path, "r+b") as f:
        f.write(b"MATLAB 7.3 MAT-file, crafted".ljust(116, b" ") + bytes(8) + b"\x00\x02IM")


@pytest.mark.parametrize("shape, points", [((1 << 16, 1 << 16), 4294967296), ((1 << 12, 1 << 12), 16777216)])
def test_a_7_3_cell_array_declaring_more_cells_than_the_file_holds(rejects, tmp_path, shape, points):
    # An HDF5 dataspace is a declared shape: chunks never written take no bytes, so a 3 kB file can
    # declare 2^32 cells, whose references and pointers libmatio allocated (2 x 32 GB; 2 x 128 MB
    # for 4096 x 4096) while it only listed the variables, and then the numeric x was not found.
    import h5py
    import numpy as np
    path = tmp_path / "cells.mat"
    write_mat73(path, {"c": ("cell", {"shape": shape, "dtype": h5py.ref_dtype, "chunks": (16, 16)}),
                       "x": ("double", {"data": np.eye(2)})})
    assert path.stat().st_size < 4096
    rejects(["fit", "--method", "ls", f"{path}:x", f"{path}:x"], path,
            f": is a damaged .mat file (dataset '/c' declares {points} values of 8 bytes, more than the file can hold)")


def test_a_7_3_matrix_compressed_a_thousand_times_still_reads(run, tmp_path):
    # The bound is deflate's ratio of the file's size: 3.2 MB of ones in a file of a few kB reads.
    import numpy as np
    path = tmp_path / "ones.mat"
    write_mat73(path, {"A": ("double", {"data": np.ones((4, 100_000)), "chunks": (4, 25_000),
                                        "compression": "gzip", "compression_opts": 9})})
    assert path.stat().st_size * 100 < 3_200_000
    r = run("fit", "--method", "ls", f"{path}:A", f"{path}:A")
    assert r.returncode == 0, r.stderr
