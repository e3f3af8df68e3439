"""Output paths: which value of a run's results.json goes in a column of the sweep's table.

A path is segments joined by dots, read from the top of results.json:

    run.cycles                     a member of an object
    blocks.2.centroid.1            an integer indexes an array, from 0; negative from the end
    blocks.top.velocity.0          a word on an array of named objects picks the one of that name
    blocks[mass.23].centroid.0     KEY[NAME]: the element named NAME of array KEY (names with dots)
    histories.slide.last           first, last, min, max, mean: of a history's samples ("value"),
    histories.slide.value.-1       or of an array of numbers; a member of that name comes first

The value at the end must be a number, a boolean, a string or null: an object or an array needs
a further segment.
"""
import re
from dataclasses import dataclass

from vdec_sweep.errors import BAD_OUTPUT, SweepError

REDUCTIONS = {
    "first": lambda values: values[0],
    "last": lambda values: values[-1],
    "min": min,
    "max": max,
    "mean": lambda values: sum(values) / len(values),
}
_INTEGER = re.compile(r"-?\d+")
_WORD = re.compile(r"[^.\[\]]+")


class PathNotFound(LookupError):
    """The path does not lead to a value in this results.json; the message says where it stops."""


@dataclass(frozen=True)
class OutputPath:
    text: str
    segments: tuple    # of (kind, value): ("member", word), ("name", NAME); "member" also indexes


def parse_output_path(text):
    """The OutputPath of --output TEXT; SweepError(BAD_OUTPUT) when it is malformed."""
    def bad(why):
        return SweepError(BAD_OUTPUT, f"--output '{text}': {why}")

    segments, position = [], 0
    while True:
        word = _WORD.match(text, position)
        if word is None:
            raise bad(f"an empty segment at character {position + 1}" if position < len(text) or not text
                      else "ends with '.'")
        segments.append(("member", word.group()))
        position = word.end()
        while position < len(text) and text[position] == "[":
            close = text.find("]", position)
            if close < 0:
                raise bad(f"'[' at character {position + 1} is not closed")
            if close == position + 1:
                raise bad(f"an empty name '[]' at character {position + 1}")
            segments.append(("name", text[position + 1:close]))
            position = close + 1
        if position == len(text):
            return OutputPath(text, tuple(segments))
        if text[position] != ".":
            raise bad(f"'{text[position]}' at character {position + 1} where '.', '[' or the end was expected")
        position += 1


def _numbers(value):
    return isinstance(value, list) and value and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                     for v in value)


def _named(array, name, where):
    for element in array:
        if isinstance(element, dict) and element.get("name") == name:
            return element
    names = [e.get("name") for e in array if isinstance(e, dict) and isinstance(e.get("name"), str)]
    shown = ", ".join(names[:8]) + (", ..." if len(names) > 8 else "")
    raise PathNotFound(f"{where} has no element named '{name}'" + (f" (names: {shown})" if names else ""))


def resolve(path, results):
    """The value at path in results (a parsed results.json); PathNotFound if there is none."""
    value, where = results, "results.json"
    for kind, segment in path.segments:
        if kind == "name":
            if not isinstance(value, list):
                raise PathNotFound(f"{where} is not an array, so [{segment}] names nothing")
            value, where = _named(value, segment, where), f"{where}[{segment}]"
        elif isinstance(value, dict):
            if segment in value:
                value = value[segment]
            elif segment in REDUCTIONS and _numbers(value.get("value")):
                value = REDUCTIONS[segment](value["value"])
            else:
                keys = ", ".join(sorted(value)) or "none"
                raise PathNotFound(f"{where} has no member '{segment}' (members: {keys})")
            where = f"{where}.{segment}" if where != "results.json" else segment
        elif isinstance(value, list):
            if _INTEGER.fullmatch(segment):
                index = int(segment)
                if not -len(value) <= index < len(value):
                    raise PathNotFound(f"{where} has {len(value)} elements, no index {index}")
                value = value[index]
            elif segment in REDUCTIONS and _numbers(value):
                value = REDUCTIONS[segment](value)
            else:
                value = _named(value, segment, where)
            where = f"{where}.{segment}"
        else:
            raise PathNotFound(f"{where} is a value ({value!r}), it has no '{segment}'")
    if isinstance(value, (dict, list)):
        kind = "an object" if isinstance(value, dict) else f"an array of {len(value)}"
        raise PathNotFound(f"{where} is {kind}, not a value: add a segment (a member, an index, or "
                           f"{', '.join(REDUCTIONS)})")
    return value
