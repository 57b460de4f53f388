"""Every accepted file variation gives the same estimate as plain CSV."""
import json

import numpy as np
import pytest

from conftest import write_text


def rows(M, sep, fmt="{:.17g}"):
    return [sep.join(fmt.format(v) for v in row) for row in M]


VARIANTS = {
    "comma": lambda M: "\n".join(rows(M, ",")) + "\n",
    "comma-spaces": lambda M: "\n".join(rows(M, ", ")) + "\n",
    "semicolon": lambda M: "\n".join(rows(M, ";")) + "\n",
    "tab": lambda M: "\n".join(rows(M, "\t")) + "\n",
    "matlab-save-ascii": lambda M: "".join("   " + "   ".join(f"{v:.16e}" for v in row) + "\n" for row in M),
    "crlf": lambda M: "\r\n".join(rows(M, ",")) + "\r\n",
    "bom": lambda M: "\ufeff" + "\n".join(rows(M, ",")) + "\n",
    "comments-and-blank-lines": lambda M: "# logged 2026-11-22\n\n" + "\n".join(rows(M, ",")) + "\n% end\n",
    "header-row": lambda M: "f1,f2,f3\n" + "\n".join(rows(M, ",")) + "\n",
    "no-final-newline": lambda M: "\n".join(rows(M, ",")),
}


def fit_json(spdfit, a, b, method="spde"):
    result = spdfit("fit", "--method", method, "--json", a, b)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_text_variants_read_like_plain_csv(spdfit, data, tmp_path, variant):
    A, B = data
    plain = fit_json(spdfit, write_text(tmp_path / "A.csv", VARIANTS["comma"](A)),
                     write_text(tmp_path / "B.csv", VARIANTS["comma"](B)))
    a = write_text(tmp_path / f"A_{variant}.txt", VARIANTS[variant](A))
    b = write_text(tmp_path / f"B_{variant}.txt", VARIANTS[variant](B))
    got = fit_json(spdfit, a, b)
    tolerance = 1e-14 if variant == "matlab-save-ascii" else 0.0  # %.16e keeps 17 digits
    assert np.allclose(got["X"], plain["X"], rtol=tolerance, atol=0)


@pytest.mark.parametrize("order", ["C", "F"])
def test_npy_in_c_and_fortran_order(spdfit, data, tmp_path, order):
    A, B = data
    np.save(tmp_path / "A.npy", np.asarray(A, order=order))
    np.save(tmp_path / "B.npy", np.asarray(B, order=order))
    np.savetxt(tmp_path / "A.csv", A, delimiter=",", fmt="%.17g")
    np.savetxt(tmp_path / "B.csv", B, delimiter=",", fmt="%.17g")
    assert fit_json(spdfit, tmp_path / "A.npy", tmp_path / "B.npy")["X"] == \
        fit_json(spdfit, tmp_path / "A.csv", tmp_path / "B.csv")["X"]


def test_npy_and_csv_may_be_mixed(spdfit, data, tmp_path):
    A, B = data
    np.save(tmp_path / "A.npy", A)
    np.savetxt(tmp_path / "B.csv", B, delimiter=",", fmt="%.17g")
    assert fit_json(spdfit, tmp_path / "A.npy", tmp_path / "B.csv")["m"] == 9


def test_npy_file_named_csv_is_read_by_content(spdfit, data, tmp_path):
    A, B = data
    np.save(tmp_path / "A.npy", A)
    (tmp_path / "A.npy").rename(tmp_path / "A_really_npy.csv")
    np.save(tmp_path / "B.npy", B)
    assert fit_json(spdfit, tmp_path / "A_really_npy.csv", tmp_path / "B.npy")["n"] == 3
