"""The Python-module tests import the package as built (ctest puts build/python on
PYTHONPATH), the independent NumPy reference from tests/reference and the shared helpers of
tests/support."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "reference"))
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "support"))
