"""The event log: one record per event (time, event, controllable, data, the state after it).

A generated node also writes *state records*, whose ``event`` is null, when its belief
changed without an event (a command acknowledged, a robot unconfirmed); the readers here
skip them: they are the events' log.

Written as JSON Lines by the simulator and by generated nodes (their ``event_log``
parameter); also as MCAP (JSON-encoded messages on the channel ``/robosc/events``,
with a JSON schema) so that Foxglove and the ROS bag tools open it.
"""

from __future__ import annotations

import json
import stat
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import Any, BinaryIO

from robosc.record import field, record

CHANNEL = "/robosc/events"
SCHEMA = {
    "title": "robosc.Event",
    "type": "object",
    "properties": {
        "time": {"type": "number", "description": "seconds"},
        "event": {"type": "string"},
        "controllable": {"type": "boolean"},
        "data": {},
        "state": {
            "type": "object",
            "properties": {"automata": {"type": "object"}, "variables": {"type": "object"}},
        },
    },
    "required": ["time", "event", "controllable"],
}


MAX_TIME = float(((1 << 64) - 1) // 10**9)  # seconds: MCAP stamps messages in unsigned 64-bit nanoseconds
MAX_EVENT = 1000  # characters of an event's name (a model's names have at most 100; the rest is room)


class LogError(Exception):
    """The log cannot be read; the message names the file and line."""


@record
class Record:
    time: float
    event: str
    controllable: bool
    data: Any
    state: dict[str, Any]
    extra: dict[str, Any] = field(default_factory=dict)  # other fields of the record (the simulator's step), kept

    def as_json(self) -> dict[str, Any]:
        return {
            **self.extra,
            "time": self.time,
            "event": self.event,
            "controllable": self.controllable,
            "data": self.data,
            "state": self.state,
        }


def _record(raw: Any, where: str) -> Record | None:
    """The event record ``raw``; None for a state record (``"event": null``)."""
    if not isinstance(raw, dict):
        raise LogError(f"{where}: not an event record (a JSON object)")
    if "event" in raw and raw["event"] is None:
        return None
    try:
        time = raw["time"]
        event = raw["event"]
        controllable = raw["controllable"]
    except KeyError as error:
        raise LogError(f"{where}: an event record needs time, event and controllable (no {error})") from None
    if isinstance(time, bool) or not isinstance(time, (int, float)) or not 0 <= time <= MAX_TIME:
        raise LogError(
            f"{where}: 'time' must be a number of seconds from 0 to {MAX_TIME:.0f} "
            f"(the nanoseconds of an MCAP log), not {_shown(time)}"
        )
    if not isinstance(event, str) or not event or len(event) > MAX_EVENT:
        raise LogError(f"{where}: 'event' must be a name of 1 to {MAX_EVENT} characters, not {_shown(event)}")
    if not isinstance(controllable, bool):
        raise LogError(f"{where}: 'controllable' must be true or false")
    state = raw.get("state") or {}
    extra = {k: v for k, v in raw.items() if k not in _FIELDS}
    return Record(float(time), event, controllable, raw.get("data"), state if isinstance(state, dict) else {}, extra)


_FIELDS = ("time", "event", "controllable", "data", "state")


def _shown(value: Any) -> str:
    text = json.dumps(value) if isinstance(value, (str, int, float)) else type(value).__name__
    return text if len(text) <= 40 else text[:37] + "..."


MAX_LOG_BYTES = 1 << 30


def read_log(path: str | Path) -> list[Record]:
    """The records of a JSON Lines (``.jsonl``, ``.json``, ``.log``) or MCAP (``.mcap``) log."""
    path = Path(path)
    try:
        info = path.stat()
        if not stat.S_ISREG(info.st_mode):
            raise LogError(f"{path}: not a regular file (a directory, pipe or device), so not an event log")
        if info.st_size > MAX_LOG_BYTES:
            raise LogError(f"{path}: {info.st_size} bytes is too large for an event log (at most {MAX_LOG_BYTES})")
        if path.suffix == ".mcap":
            with path.open("rb") as handle:
                return list(_read_mcap(handle, str(path)))
        text = path.read_text(encoding="utf-8")
    except OSError as error:
        raise LogError(f"{path}: cannot read: {error.strerror or error}") from None
    except UnicodeDecodeError:
        raise LogError(f"{path}: not UTF-8 text (an MCAP log must end in .mcap)") from None
    records = []
    for number, line in enumerate(text.splitlines(), 1):
        if not line.strip():
            continue
        try:
            raw = json.loads(line)
        except json.JSONDecodeError as error:
            raise LogError(f"{path}:{number}:{error.colno}: not JSON: {error.msg}") from None
        except RecursionError:
            raise LogError(f"{path}:{number}:1: JSON nested too deeply") from None
        found = _record(raw, f"{path}:{number}:1")
        if found is not None:
            records.append(found)
    return records


def _read_mcap(handle: BinaryIO, name: str) -> Iterator[Record]:
    from mcap.exceptions import McapError
    from mcap.reader import make_reader

    try:
        for _, channel, message in make_reader(handle).iter_messages(topics=[CHANNEL]):
            found = _record(json.loads(message.data), f"{name}: message at {message.log_time} ns on {channel.topic}")
            if found is not None:
                yield found
    except RecursionError:
        raise LogError(f"{name}: a message's JSON is nested too deeply") from None
    except (McapError, json.JSONDecodeError, ValueError) as error:
        raise LogError(f"{name}: not a readable MCAP event log: {error}") from None


def write_mcap(records: Iterable[Record | dict[str, Any]], handle: BinaryIO) -> int:
    """Write records as MCAP; returns how many."""
    writer = McapLog(handle)
    count = 0
    for item in records:
        writer.write(item.as_json() if isinstance(item, Record) else item)
        count += 1
    writer.close()
    return count


class McapLog:
    """An MCAP event log written one record at a time (the simulator's ``--log x.mcap``)."""

    def __init__(self, handle: BinaryIO) -> None:
        from mcap.writer import Writer

        self.handle = handle
        self.writer = Writer(handle)
        self.writer.start(profile="", library="robosc")
        schema = self.writer.register_schema("robosc.Event", "jsonschema", json.dumps(SCHEMA).encode())
        self.channel = self.writer.register_channel(CHANNEL, "json", schema)
        self.sequence = 0

    def write(self, record: dict[str, Any]) -> None:
        nanoseconds = int(float(record["time"]) * 1e9)
        self.writer.add_message(
            self.channel,
            log_time=nanoseconds,
            publish_time=nanoseconds,
            sequence=self.sequence,
            data=json.dumps(record, sort_keys=True).encode(),
        )
        self.sequence += 1

    def close(self) -> None:
        self.writer.finish()  # type: ignore[no-untyped-call]
