"""Reading model files and finding the libraries a robot imports.

A library is found by the name after ``from``: every ``.rscd`` file next to the
model and on the user's search paths (``-I DIR``) is a candidate, and the first
whose text starts with ``library <that name>`` is used (directories in order,
files in name order).
"""

from __future__ import annotations

import re
import stat
from collections.abc import Sequence
from pathlib import Path

from robosc.language import syntax as s
from robosc.language.codes import Code
from robosc.language.diagnostics import Diagnostic
from robosc.language.parser import parse_source
from robosc.language.resolver import LibraryUnit, Reporter, scope_of
from robosc.language.source import SourceFile
from robosc.record import record

_LIBRARY_HEADER = re.compile(r"\A(?:\s+|//[^\n]*|/\*.*?\*/)*library\s+\^?([A-Za-z_][A-Za-z0-9_]*)", re.DOTALL)


class InputError(Exception):
    """A file cannot be read as a model (missing, a directory, not UTF-8, unreadable)."""


MAX_MODEL_BYTES = 16 * 1024 * 1024  # a 5,000-line model is about 0.2 MB


def regular_file(path: str | Path, what: str = "a model file", limit: int = MAX_MODEL_BYTES) -> Path:
    """``path`` if it is a regular file of at most ``limit`` bytes, else :class:`InputError`
    (a FIFO or a device such as /dev/zero would block or never end)."""
    p = Path(path)
    try:
        info = p.stat()
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror or exc}") from None
    if stat.S_ISDIR(info.st_mode):
        raise InputError(f"{path}: is a directory, not {what}")
    if not stat.S_ISREG(info.st_mode):
        raise InputError(f"{path}: not a regular file (a pipe, socket or device), so not {what}")
    if info.st_size > limit:
        raise InputError(f"{path}: {info.st_size} bytes is too large for {what} (at most {limit})")
    return p


def read_source(path: str | Path) -> SourceFile:
    """Read a model file as UTF-8 text, or raise :class:`InputError` saying why not."""
    try:
        p = regular_file(path)
        data = p.read_bytes()
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except PermissionError:
        raise InputError(f"{path}: permission denied") from None
    except OSError as exc:
        raise InputError(f"{path}: cannot read: {exc.strerror or exc}") from None
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        raise InputError(f"{path}:{line}: not UTF-8 text (byte 0x{data[exc.start]:02x})") from None
    return SourceFile(str(path), text)


@record(frozen=False)
class LibraryFinder:
    """Finds, reads, parses and resolves the libraries a model imports (once each)."""

    search_paths: Sequence[Path]
    sources: dict[str, SourceFile]

    def __post_init__(self) -> None:
        self._units: dict[str, LibraryUnit | None] = {}
        self._index: dict[str, Path] | None = None
        self._loading: set[str] = set()
        self._duplicates: dict[str, list[Path]] = {}

    def _library_files(self) -> dict[str, Path]:
        if self._index is None:
            self._index = {}
            for directory in self.search_paths:
                try:
                    candidates = sorted(directory.glob("*.rscd"))
                except OSError:
                    continue
                for candidate in candidates:
                    try:
                        regular_file(candidate)
                        with candidate.open(encoding="utf-8", errors="replace") as handle:
                            head = handle.read(4096)
                    except (OSError, InputError):
                        continue
                    match = _LIBRARY_HEADER.match(head)
                    if match:
                        found = self._index.setdefault(match.group(1), candidate)
                        if found != candidate and found.resolve() != candidate.resolve():
                            self._duplicates.setdefault(match.group(1), [found]).append(candidate)
        return self._index

    def find(self, name: s.Name, reporter: Reporter) -> LibraryUnit | None:
        if name.text in self._units:
            return self._units[name.text]
        path = self._library_files().get(name.text)
        if path is None:
            where = ", ".join(str(p) for p in self.search_paths) or "."
            reporter.unknown(name.span, "library", name.text, self._library_files())
            reporter.diagnostics[-1] = _with_hint(
                reporter.diagnostics[-1], f"looked in {where}; add a directory with -I DIR"
            )
            return None
        if name.text in self._duplicates:
            where = " and ".join(str(p) for p in self._duplicates[name.text])
            reporter.error(
                name.span,
                f"more than one library is named '{name.text}': {where}",
                Code.IO,
                "keep one of them, or give the other a different 'library' name",
            )
            self._units[name.text] = None
            return None
        try:
            source = read_source(path)
        except InputError as exc:
            reporter.error(name.span, f"cannot read library '{name.text}': {exc}", Code.IO)
            self._units[name.text] = None
            return None
        self.sources[source.path] = source
        parsed = parse_source(source)
        reporter.diagnostics.extend(parsed.diagnostics)
        unit = None
        if parsed.syntax is not None:
            unit = LibraryUnit(parsed.syntax, scope_of(parsed.syntax, reporter))
        self._units[name.text] = unit
        return unit


def _with_hint(diagnostic: Diagnostic, extra: str) -> Diagnostic:
    hint = f"{diagnostic.hint} ({extra})" if diagnostic.hint else extra
    return Diagnostic(diagnostic.severity, diagnostic.message, diagnostic.span, diagnostic.code, hint)
