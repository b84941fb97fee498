"""What a notebook shows: ``ars.Image``, the numpy array ``Renderer.render`` returns,
shown as a picture; ``ars.Replay``, the browser replay ``Simulation.replay`` and
``Simulation.save_replay`` return, shown as a player."""

from __future__ import annotations

import html
import os
import struct
import zlib
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["Image", "Replay"]


def _png(pixels: npt.NDArray[np.uint8]) -> bytes:
    """PNG bytes of a (height, width[, channels]) uint8 array of 1, 3 or 4 channels."""
    if pixels.ndim == 2:
        pixels = pixels[:, :, None]
    height, width, channels = pixels.shape
    colour_type = {1: 0, 3: 2, 4: 6}[channels]
    rows = np.ascontiguousarray(pixels).reshape(height, width * channels)
    # Each row starts with its filter type, 0 (none).
    raw = np.concatenate([np.zeros((height, 1), np.uint8), rows], axis=1).tobytes()

    def chunk(kind: bytes, data: bytes) -> bytes:
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    return (
        b"\x89PNG\r\n\x1a\n"
        + chunk(b"IHDR", header)
        + chunk(b"IDAT", zlib.compress(raw))
        + chunk(b"IEND", b"")
    )


def _write_whole(path: str | os.PathLike[str], data: bytes, what: str) -> None:
    """Writes ``data`` to ``path`` through a hidden temporary file beside it, renamed
    into place: the file appears whole or not at all. An ``OSError`` comes out as an
    ``ars.FileError`` naming ``what`` and the path."""
    path = os.fspath(path)
    temporary = os.path.join(
        os.path.dirname(path) or ".", f".{os.path.basename(path)}.{os.getpid()}.partial"
    )
    try:
        with open(temporary, "wb") as f:
            f.write(data)
        os.replace(temporary, path)
    except OSError as e:
        from ars import FileError

        reason = e.strerror or str(e)
        raise FileError(e.errno, f"cannot write {what} {path!r}: {reason}", path) from e
    finally:
        if os.path.exists(temporary):
            os.remove(temporary)


class Image(np.ndarray[Any, np.dtype[Any]]):
    """An image as ``Renderer.render`` returns it: a numpy array of shape (height,
    width, 3), ``uint8``, which Jupyter shows as a picture (``_repr_png_``). Everything
    numpy does with it works as with any array; what numpy computes from it (sums,
    differences, comparisons) is a plain array."""

    def __array_wrap__(
        self, array: npt.NDArray[Any], context: Any = None, return_scalar: bool = False
    ) -> Any:
        result = np.asarray(array)
        return result[()] if return_scalar else result

    def _repr_png_(self) -> bytes | None:
        shown = self.ndim == 2 or (self.ndim == 3 and self.shape[2] in (1, 3, 4))
        if not shown or self.dtype != np.uint8 or self.size == 0:
            return None
        return _png(np.asarray(self))

    def save(self, path: str | os.PathLike[str]) -> None:
        """Writes the image to ``path`` as a PNG file (whole: a temporary file
        renamed). An image that is not (height, width[, 1, 3 or 4]) ``uint8`` is an
        ``ars.InputError``, a folder that cannot be written an ``ars.FileError``."""
        png = self._repr_png_()
        if png is None:
            from ars import InputError

            raise InputError(
                f"a PNG holds a (height, width[, 1, 3 or 4]) uint8 image, not an array of shape "
                f"{self.shape} and type {self.dtype}"
            )
        _write_whole(path, png, "the PNG image")


class Replay:
    """A browser replay: one self-contained HTML page (no network needed) that plays
    a recorded run back, with an orbit camera, play/pause, a time slider, speed and
    plots. Jupyter shows it inline (``_repr_html_``); ``save`` writes it."""

    def __init__(
        self, html: str, path: str | os.PathLike[str] | None, frames: int, start: float, end: float
    ) -> None:
        self.html = html
        self.path = None if path is None else os.fspath(path)
        self.frames = frames
        self.start = start
        self.end = end

    def save(self, path: str | os.PathLike[str]) -> None:
        """Writes the page to ``path`` (whole: a temporary file renamed); a folder
        that cannot be written is an ``ars.FileError``."""
        _write_whole(path, self.html.encode("utf-8"), "the replay")
        self.path = os.fspath(path)

    def _repr_html_(self) -> str:
        # In an iframe of its own: the page's script and ids stay out of the notebook's.
        return (
            f'<iframe srcdoc="{html.escape(self.html, quote=True)}" style="border:0;width:100%;height:720px" '
            'sandbox="allow-scripts"></iframe>'
        )

    def __repr__(self) -> str:
        where = f", {self.path!r}" if self.path else ""
        return f"<ars.Replay {self.frames} frames, t = {self.start:g} to {self.end:g} s{where}>"
