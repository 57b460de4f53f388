"""Names kept through the command line: `nearest --header` and `--json` carry the variables' names
of a labelled matrix (pandas' df.cov().to_csv(), a header row alone), `fit --report` labels X's
rows by A's columns and its columns by B's; and `--var-a` given with a file that has no named
arrays is a usage error that quotes it."""
import csv
import io
import json

import numpy as np

from conftest import write_text
from spdfit_testing import SOURCE_DIR

NAMES = ["ax", "ay", "torque z"]
# An indefinite covariance (pairwise deletion), so that the repair changes it.
S = np.array([[4.0, 2.0, 2.1], [2.0, 3.0, 2.9], [2.1, 2.9, 2.0]])


def pandas_cov_csv(names, S):
    """The text pandas' df.cov().to_csv() writes: an empty first header cell, the names as the
    header and as each row's first cell (quoted where a name needs it, as pandas quotes)."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow([""] + names)
    for name, row in zip(names, S):
        writer.writerow([name] + [repr(float(v)) for v in row])
    return out.getvalue()


def read_labelled(text):
    """What pandas.read_csv(f, index_col=0) gives for a labelled table: the index, the columns
    and the values (an independent reader: Python's csv module)."""
    rows = list(csv.reader(io.StringIO(text)))
    header = rows[0]
    assert header[0] == ""
    return [r[0] for r in rows[1:]], header[1:], np.array([[float(v) for v in r[1:]] for r in rows[1:]])


def test_nearest_header_keeps_the_names_of_a_pandas_cov_file(spdfit, tmp_path):
    path = write_text(tmp_path / "S.csv", pandas_cov_csv(NAMES, S))
    plain = spdfit("nearest", path)
    out = spdfit("nearest", "--header", path)
    assert out.returncode == 0 and plain.returncode == 0, out.stderr
    index, columns, X = read_labelled(out.stdout)
    assert index == NAMES and columns == NAMES
    # The same numbers as the unlabelled output, to the last bit.
    X_plain = np.array([[float(v) for v in line.split(",")] for line in plain.stdout.splitlines()])
    assert np.array_equal(X, X_plain)
    # A real repair: positive definite, symmetric, and not the input.
    assert np.all(np.linalg.eigvalsh(X) > 0) and np.array_equal(X, X.T) and not np.allclose(X, S)
    # The labelled output read back as input gives the same names and matrix: a round trip.
    again = spdfit("nearest", "--header", "-o", tmp_path / "again.csv", write_text(tmp_path / "X.csv", out.stdout))
    assert again.returncode == 0, again.stderr
    index2, columns2, X2 = read_labelled((tmp_path / "again.csv").read_text())
    assert index2 == NAMES and columns2 == NAMES
    np.testing.assert_allclose(X2, X, rtol=0, atol=1e-12)


def test_nearest_json_carries_the_names_and_keeps_every_key(spdfit, tmp_path):
    labelled = json.loads(spdfit("nearest", "--json", write_text(tmp_path / "S.csv", pandas_cov_csv(NAMES, S))).stdout)
    bare = json.loads(spdfit("nearest", "--json", write_text(tmp_path / "bare.csv", "\n".join(
        ",".join(repr(float(v)) for v in row) for row in S) + "\n")).stdout)
    assert labelled["names"] == NAMES
    assert "names" not in bare
    assert set(labelled) - {"names"} == set(bare)
    assert labelled["X"] == bare["X"]


def test_nearest_names_from_a_header_row_alone(spdfit, tmp_path):
    text = ",".join(NAMES[:2] + ["az"]) + "\n" + "\n".join(",".join(repr(float(v)) for v in row) for row in S) + "\n"
    path = write_text(tmp_path / "S.csv", text)
    out = spdfit("nearest", "--header", path)
    assert out.returncode == 0, out.stderr
    index, columns, _ = read_labelled(out.stdout)
    assert index == columns == ["ax", "ay", "az"]
    assert json.loads(spdfit("nearest", "--json", path).stdout)["names"] == ["ax", "ay", "az"]


def test_nearest_header_without_names_numbers_the_variables(spdfit, tmp_path):
    path = write_text(tmp_path / "S.csv", "\n".join(",".join(repr(float(v)) for v in row) for row in S) + "\n")
    index, columns, _ = read_labelled(spdfit("nearest", "--header", path).stdout)
    assert index == columns == ["1", "2", "3"]


def test_nearest_row_labels_that_differ_from_the_header_warn(spdfit, tmp_path):
    text = pandas_cov_csv(NAMES, S).replace("\nay,", "\nby,", 1)
    out = spdfit("nearest", "--header", write_text(tmp_path / "S.csv", text))
    assert out.returncode == 0, out.stderr
    assert "the row labels (ax, by, torque z) differ from the column names (ax, ay, torque z)" in out.stderr
    assert read_labelled(out.stdout)[0] == NAMES


def test_nearest_header_option_errors(spdfit, tmp_path):
    path = write_text(tmp_path / "S.csv", pandas_cov_csv(NAMES, S))
    both = spdfit("nearest", "--header", "--json", path)
    assert both.returncode == 2 and "excludes" in both.stderr
    npy = spdfit("nearest", "--header", "-o", tmp_path / "X.npy", path)
    assert npy.returncode == 2 and "--output" in npy.stderr and "--header" in npy.stderr


def labelled_ab(tmp_path):
    rng = np.random.default_rng(3)
    A = rng.uniform(-5, 5, (40, 3))
    X = np.array([[3.0, 1.0, 0.5], [1.0, 2.0, 0.2], [0.5, 0.2, 1.5]])
    B = A @ X + 0.05 * rng.standard_normal((40, 3))
    a = write_text(tmp_path / "A.csv", "ax,ay,alpha\n" + "\n".join(",".join(repr(float(v)) for v in r) for r in A) + "\n")
    b = write_text(tmp_path / "B.csv", "Fx,Fy,Mz\n" + "\n".join(",".join(repr(float(v)) for v in r) for r in B) + "\n")
    return a, b


def test_fit_report_labels_rows_by_a_and_columns_by_b(spdfit, tmp_path):
    a, b = labelled_ab(tmp_path)
    report = spdfit("fit", "--method", "ls", "--report", a, b)
    assert report.returncode == 0, report.stderr
    lines = report.stdout.splitlines()
    assert "rows: A's columns; columns: B's columns" in lines
    at = lines.index("rows: A's columns; columns: B's columns")
    assert lines[at + 1].split() == ["Fx", "Fy", "Mz"]
    X = np.array(json.loads(spdfit("fit", "--method", "ls", "--json", a, b).stdout)["X"])
    for i, name in enumerate(["ax", "ay", "alpha"]):
        cells = lines[at + 2 + i].split()
        assert cells[0] == name
        np.testing.assert_allclose([float(c) for c in cells[1:]], X[i], rtol=1e-5)


def test_fit_report_labels_the_noise_model_per_column(spdfit, tmp_path):
    a, b = labelled_ab(tmp_path)
    report = spdfit("fit", "--method", "auto", "--report", "--noise-std-a", "0.1,0.2,0.3",
                    "--noise-std-b", "0.5", a, b)
    assert report.returncode == 0, report.stderr
    assert "noise std in A ax 0.1, ay 0.2, alpha 0.3; in B 0.5" in report.stdout


def test_fit_report_without_names_numbers_rows_and_columns(spdfit, data, tmp_path):
    A, B = data
    np.savetxt(tmp_path / "A.csv", A, delimiter=",", fmt="%.17g")
    np.savetxt(tmp_path / "B.csv", B, delimiter=",", fmt="%.17g")
    report = spdfit("fit", "--method", "ls", "--report", tmp_path / "A.csv", tmp_path / "B.csv").stdout
    assert "rows: A's columns" not in report
    assert report.splitlines()[2].split() == ["1", "2", "3"]


def test_var_a_with_a_text_file_is_a_usage_error_quoting_it(spdfit, tmp_path):
    a, b = labelled_ab(tmp_path)
    out = spdfit("fit", "--method", "ls", "--var-a", "accel", a, b)
    assert out.returncode == 2
    assert (f"--var-a accel: --var-a names a variable inside a .mat or .npz file, but {a} is neither (it holds "
            "one matrix, no named arrays): drop --var-a accel") in out.stderr
    assert "Run 'spdfit fit --help'" in out.stderr
    out_b = spdfit("fit", "--method", "ls", "--var-b", "force", a, b)
    assert out_b.returncode == 2 and f"--var-b force: --var-b names a variable inside a .mat or .npz file, but {b}" \
        in out_b.stderr


def test_var_a_naming_an_existing_file_says_to_give_it_as_the_data(spdfit, tmp_path):
    a, b = labelled_ab(tmp_path)
    accel = write_text(tmp_path / "accel", "1,2,3\n")
    out = spdfit("fit", "--method", "ls", "--var-a", str(accel), a, b)
    assert out.returncode == 2
    assert f"to read {accel} as the data file, give it in {a}'s place" in out.stderr


def test_var_a_with_a_mat_file_still_reads_the_variable(spdfit):
    log = SOURCE_DIR / "examples" / "hexapod" / "log.mat"
    out = spdfit("fit", "--method", "spde", "--var-a", "accel", "--var-b", "force", log, log)
    assert out.returncode == 0, out.stderr


def test_nearest_names_from_r_write_csv_quoted_labels(spdfit, tmp_path):
    # R's write.csv(S) quotes every name, the index's empty header cell too.
    text = '"","x 1","y,2"\n"x 1",2,3\n"y,2",3,2\n'
    out = spdfit("nearest", "--header", write_text(tmp_path / "S.csv", text))
    assert out.returncode == 0, out.stderr
    index, columns, X = read_labelled(out.stdout)
    assert index == columns == ["x 1", "y,2"]
    assert np.all(np.linalg.eigvalsh(X) > 0)
    js = json.loads(spdfit("nearest", "--json", tmp_path / "S.csv").stdout)
    assert js["names"] == ["x 1", "y,2"] and js["X"] == X.tolist()
