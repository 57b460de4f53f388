"""The Python-module tests import the package as built (ctest puts build/python on
PYTHONPATH) and the independent NumPy reference from tests/reference."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "reference"))
