# The types of the `viewray` module (maturin ships this file in the wheel, with
# py.typed), for editors and notebooks. The module itself is Rust: src/module.rs.

import os
from typing import Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

class SceneError(Exception):
    """A scene that could not be loaded: `str(error)` is `path:line:column: message`."""

    path: str
    line: Optional[int]
    column: Optional[int]
    message: str

class Scene:
    """A loaded scene: camera, image size, samples, objects, materials and lights."""

    @staticmethod
    def load(path: Union[str, os.PathLike[str]]) -> Scene: ...
    @staticmethod
    def parse(text: str) -> Scene: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def samples(self) -> int: ...
    def rays(self) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def frame(self) -> dict[str, npt.NDArray[np.float64]]: ...
    def project(self, points: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def render(self, samples: Optional[int] = None) -> npt.NDArray[np.uint8]: ...

class Report:
    """What `check` found: whether every ray is right, and the catalogue's explanation."""
    @property
    def ok(self) -> bool: ...
    @property
    def wrong(self) -> int: ...
    @property
    def mistakes(self) -> list[str]: ...
    @property
    def alternatives(self) -> list[list[str]]: ...

def check(
    scene: Scene,
    origins: npt.NDArray[np.float64],
    directions: npt.NDArray[np.float64],
    *,
    tolerance: float = 1e-6,
    exact_direction: bool = False,
) -> Report: ...
