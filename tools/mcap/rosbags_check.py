"""Reads an MCAP file as `ros2 bag` would, with the `rosbags` package (pure Python: its own
MCAP reader, ros2msg parser and CDR decoder), and says whether every message decodes.

    python tools/mcap/rosbags_check.py run.mcap

- The bare .mcap file is opened without a metadata.yaml (rosbags 0.11 or later, as
  `ros2 bag info/play run.mcap` do since Humble).
- Each channel's QoS (`offered_qos_profiles`) is parsed as rosbag2 parses it.
- The message types are built from the file's own `ros2msg` schemas, each checked to
  have the same fields and the same RIHS01 type hash as ROS 2 Jazzy's definition
  (rosbags' ROS2_JAZZY store).
- Every message is decoded with those types: a message that leaves bytes unread or
  runs past its end is an error.

Prints, per topic, its type, QoS, count and first message; exits 1 on any problem.
"""

from __future__ import annotations

import sys
from pathlib import Path

from rosbags.highlevel import AnyReader
from rosbags.typesys import Stores, get_typestore


def problems_of(path: Path, show: bool = True) -> list[str]:
    """Every problem `rosbags` finds in the file (none: it decodes whole), printing each
    topic's summary when `show`."""
    problems: list[str] = []
    jazzy = get_typestore(Stores.ROS2_JAZZY)
    with AnyReader([path]) as reader:
        for name in sorted(reader.typestore.fielddefs):
            if name not in jazzy.fielddefs:
                problems.append(f"{name}: not a ROS 2 Jazzy type")
            elif reader.typestore.hash_rihs01(name) != jazzy.hash_rihs01(name):
                ours, theirs = reader.typestore.fielddefs[name][1], jazzy.fielddefs[name][1]
                problems.append(
                    f"{name}: fields differ from Jazzy's:\n  file: {ours}\n  Jazzy: {theirs}"
                )
        firsts: dict[str, object] = {}
        counts: dict[str, int] = {}
        for connection, timestamp, data in reader.messages():
            counts[connection.topic] = counts.get(connection.topic, 0) + 1
            try:
                message = reader.deserialize(data, connection.msgtype)
                # Encoding it again must give the same bytes (what was written is
                # exactly what the schema says).
                again = reader.typestore.serialize_cdr(message, connection.msgtype)
                if bytes(again) != bytes(data):
                    problems.append(
                        f"{connection.topic} at {timestamp}: re-encoded, {len(again)} bytes not {len(data)}"
                    )
            except Exception as e:  # noqa: BLE001 - every failure is reported, not raised
                problems.append(f"{connection.topic} at {timestamp}: {type(e).__name__}: {e}")
                continue
            firsts.setdefault(connection.topic, message)
        for connection in reader.connections:
            topic = connection.topic
            if connection.msgcount != counts.get(topic, 0):
                problems.append(
                    f"{topic}: {counts.get(topic, 0)} messages read, {connection.msgcount} counted"
                )
            qos = connection.ext.offered_qos_profiles
            if not qos:
                problems.append(f"{topic}: no offered_qos_profiles")
            if show:
                print(
                    f"\n{topic} ({connection.msgtype}, {connection.ext.serialization_format}): "
                    f"{counts.get(topic, 0)} messages"
                )
                for profile in qos:
                    print(f"  QoS: {profile}")
                print(f"  first: {shortened(firsts.get(topic))}")
    return problems


def shortened(message: object, width: int = 400) -> str:
    """A message's repr, cut to `width` characters."""
    text = repr(message)
    return text if len(text) <= width else text[:width] + f"... ({len(text)} chars)"


def main() -> int:
    if len(sys.argv) != 2:
        print("usage: python rosbags_check.py FILE.mcap", file=sys.stderr)
        return 2
    problems = problems_of(Path(sys.argv[1]))
    print("\nevery message decoded" if not problems else "\nPROBLEMS:\n" + "\n".join(problems))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
