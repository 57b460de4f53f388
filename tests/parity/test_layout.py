"""The tree shows the architecture: every folder of src/ is listed in the README's layout table
and in CONTRIBUTING.md's "Where things live"."""

import os
import re
from pathlib import Path

SOURCE = Path(os.environ.get("SPDFIT_SOURCE_DIR", Path(__file__).resolve().parents[2]))


def test_every_src_folder_is_documented():
    folders = sorted(p.name for p in (SOURCE / "src").iterdir() if p.is_dir())
    readme = (SOURCE / "README.md").read_text()
    layout = readme[readme.index("## Layout"):]
    src_row = next(line for line in layout.splitlines() if line.startswith("| `src/`"))
    contributing = (SOURCE / "CONTRIBUTING.md").read_text()
    missing_readme = [f for f in folders if f"`{f}/`" not in src_row]
    missing_contributing = [f for f in folders if not re.search(rf"src/{f}/", contributing)]
    assert not missing_readme, f"README's layout table does not list src/{missing_readme}"
    assert not missing_contributing, f"CONTRIBUTING.md does not name src/{missing_contributing}"
