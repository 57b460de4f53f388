"""Type stubs for spdfit._errors (see _errors.py for the documentation)."""
from typing import Dict, List, Optional, Tuple, Type

class DataError(ValueError):
    code: str

class NumericalError(RuntimeError):
    result: Optional[object]
    code: str
    def __init__(self, message: str, result: Optional[object] = ...) -> None: ...

class SpdfitWarning(UserWarning): ...

# warning classes: class {}(SpdfitWarning): ...

WARNING_CLASSES: Dict[str, Type[SpdfitWarning]]

def warning_class(code: str) -> Type[SpdfitWarning]: ...
def warn(message: str, code: str = ...) -> None: ...
def outcome_codes() -> List[Tuple[str, str, str, str, str]]: ...
