"""ROS messages as JSON for tools that speak JSON (the Foxglove live view): any message to plain data, a
request from a JSON object with every field checked, and a JSON schema of a message type. Generic over
rosidl's Python classes (their ``get_fields_and_field_types``), so a new field needs no change here."""

from __future__ import annotations

import re
from typing import Any

JSON_TYPES = {"boolean": "boolean", "string": "string", "wstring": "string", "char": "integer", "octet": "integer",
              "float": "number", "double": "number"}
"""rosidl field types to JSON schema types (the integer types by their prefix)."""


def message_to_dict(message: Any) -> dict[str, Any]:
    """Every field of ``message`` as JSON-ready data (nested messages as objects, sequences as lists)."""
    return {name: _plain(getattr(message, name)) for name in message.get_fields_and_field_types()}


def _plain(value: Any) -> Any:
    if hasattr(value, "get_fields_and_field_types"):
        return message_to_dict(value)
    if isinstance(value, str | bool | int | float) or value is None:
        return value
    if isinstance(value, bytes):
        return list(value)
    return [_plain(item) for item in value]  # list, array.array, numpy array


def message_from_dict(message_class: type, data: Any) -> Any:
    """A ``message_class`` with the fields of the JSON object ``data`` (others at their defaults); ValueError
    naming the field for an unknown one or a value of the wrong type or range. Checked here: rosidl's setters
    check only when ROS_PYTHON_CHECK_FIELDS says so."""
    if not isinstance(data, dict):
        raise ValueError(f"expected a JSON object with fields of {message_class.__name__}, got {type(data).__name__}")
    fields = message_class.get_fields_and_field_types()
    unknown = sorted(set(data) - set(fields))
    if unknown:
        raise ValueError(f"unknown field(s) {', '.join(unknown)}; {message_class.__name__} has {', '.join(fields)}")
    message = message_class()
    for name, value in data.items():
        current = getattr(message, name)
        if hasattr(current, "get_fields_and_field_types"):
            value = message_from_dict(type(current), value)
        else:
            problem = _primitive_problem(fields[name], value)
            if problem:
                raise ValueError(f"field {name} ({fields[name]}): {problem}, got {value!r}")
        setattr(message, name, value)
    return message


def _primitive_problem(kind: str, value: Any) -> str:
    """Why ``value`` cannot be a field of rosidl type ``kind`` ("" when it can; sequences are not checked)."""
    integer = re.fullmatch(r"(u?)int(8|16|32|64)", kind)
    if integer:
        if isinstance(value, bool) or not isinstance(value, int):
            return "must be an integer"
        bits, unsigned = int(integer.group(2)), bool(integer.group(1))
        low, high = (0, 2 ** bits - 1) if unsigned else (-(2 ** (bits - 1)), 2 ** (bits - 1) - 1)
        return "" if low <= value <= high else f"must be within [{low}, {high}]"
    expected = {"boolean": bool, "float": (int, float), "double": (int, float)}.get(kind)
    if kind.startswith(("string", "wstring")):
        expected = str
    if expected is not None and (not isinstance(value, expected) or (expected is not bool and isinstance(value, bool))):
        return f"must be a {'number' if isinstance(expected, tuple) else expected.__name__}"
    return ""


def json_schema(message_class: type) -> dict[str, Any]:
    """A JSON schema of ``message_class`` (objects, arrays and primitive types; titles carry the ROS types)."""
    return {"type": "object", "title": message_class.__name__,
            "properties": {name: _field_schema(kind, getattr(message_class(), name))
                           for name, kind in message_class.get_fields_and_field_types().items()}}


def _field_schema(kind: str, example: Any) -> dict[str, Any]:
    sequence = re.fullmatch(r"sequence<(.+?)(, \d+)?>|(.+)\[\d+\]", kind)
    if sequence:
        item = sequence.group(1) or sequence.group(3)
        nested = example[0] if len(example) and hasattr(example[0], "get_fields_and_field_types") else None
        return {"type": "array", "items": json_schema(type(nested)) if nested is not None
                else _primitive_schema(item), "title": kind}
    if hasattr(example, "get_fields_and_field_types"):
        return json_schema(type(example))
    return _primitive_schema(kind)


def _primitive_schema(kind: str) -> dict[str, Any]:
    base = re.sub(r"<=\d+$", "", kind)
    if base.startswith(("int", "uint")):
        return {"type": "integer", "title": kind}
    if "/" in base:  # a message type inside an empty sequence: an object whose fields the example cannot show
        return {"type": "object", "title": kind}
    return {"type": JSON_TYPES.get(base, "string"), "title": kind}
