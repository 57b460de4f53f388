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
