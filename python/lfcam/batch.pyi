# Type stub of lfcam.batch (batch.py), so that editors complete and check its calls.
from os import PathLike
from typing import Any, Callable, Optional, Sequence, Union

from . import Error

_Path = Union[str, PathLike[str]]

CONNECT_TIMEOUT: float

class BatchError(Error):
    report: dict[str, Any]
    def __init__(self, message: str, report: dict[str, Any]) -> None: ...

def run(inputs: Union[_Path, Sequence[_Path]], output: _Path, steps: Union[str, Sequence[str]],
        white: Optional[_Path] = None, jobs: Optional[int] = None, report: Optional[_Path] = None,
        client: Any = None, progress: Optional[Callable[[int, int], None]] = None) -> dict[str, Any]: ...
def capture_task(input: str, name: str, steps: Sequence[str], white: str, output: str) -> dict[str, Any]: ...
def main(argv: Optional[Sequence[str]] = None) -> int: ...
