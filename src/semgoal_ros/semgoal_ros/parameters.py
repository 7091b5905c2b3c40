"""Node parameters the ROS way, one way for every node: each declared with a ParameterDescriptor
(description, range, choices, read-only), a bad start-up value refused with one clear line, and a change at
run time either applied by the node or refused with the reason (``ros2 param set`` prints it).

A node lists its parameters as :class:`Param` specs, calls :func:`declare` and, for the ones that may change
while it runs, :func:`apply_changes` with a function that puts a new value into effect.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from rcl_interfaces.msg import FloatingPointRange, IntegerRange, ParameterDescriptor, SetParametersResult

Value = bool | int | float | str


class ParameterValueError(ValueError):
    """A parameter value outside what the node accepts; the message names the node, the parameter and the rule."""


@dataclass(frozen=True)
class Param:
    name: str
    default: Value
    description: str
    choices: tuple[str, ...] = ()
    low: float | None = None
    """Smallest value allowed (inclusive), for numbers."""
    high: float | None = None
    runtime: bool = False
    """Whether a change takes effect while the node runs; otherwise the parameter is read-only after start-up."""

    def descriptor(self) -> ParameterDescriptor:
        descriptor = ParameterDescriptor(name=self.name, description=self.description, read_only=not self.runtime)
        if self.choices:
            descriptor.additional_constraints = f"one of: {', '.join(self.choices)}"
        if self.low is not None and self.high is not None:
            if isinstance(self.default, float):
                descriptor.floating_point_range = [FloatingPointRange(from_value=float(self.low), to_value=float(self.high))]
            elif isinstance(self.default, int) and not isinstance(self.default, bool):
                descriptor.integer_range = [IntegerRange(from_value=int(self.low), to_value=int(self.high), step=1)]
        return descriptor

    def problem(self, value: Value) -> str:
        """Why ``value`` is refused ("" when it is fine)."""
        if self.choices and value not in self.choices:
            return f"must be one of {', '.join(self.choices)}"
        if isinstance(value, bool) or not isinstance(value, int | float):
            return ""
        if value != value:  # NaN
            return "must be a number, not NaN"
        if (self.low is not None and value < self.low) or (self.high is not None and value > self.high):
            return f"must be within [{self.low}, {self.high}]"
        return ""


def declare(node, params: Sequence[Param]) -> dict[str, Value]:
    """Declare ``params`` on ``node`` and return their start-up values; :class:`ParameterValueError` for a bad one."""
    from rclpy.exceptions import InvalidParameterValueException

    values = {}
    for param in params:
        try:
            value = node.declare_parameter(param.name, param.default, param.descriptor()).value
        except InvalidParameterValueException as error:  # rclpy's own range check on the start-up value
            reason = str(error.args[0]).partition("Reason: ")[2] or str(error)
            raise ParameterValueError(f"{node.get_name()}: parameter {param.name} {reason}; "
                                      f"must be within [{param.low}, {param.high}]") from None
        problem = param.problem(value)
        if problem:
            raise ParameterValueError(f"{node.get_name()}: parameter {param.name}={value!r} {problem}")
        values[param.name] = value
    return values


def apply_changes(node, params: Sequence[Param], apply: Callable[[str, Value], None]) -> None:
    """Check every change at run time against its spec (rclpy has already refused read-only parameters and
    numbers out of range), and once all are set, ``apply(name, value)`` each one: a refused change leaves
    every value as it was."""
    specs = {param.name: param for param in params}

    def check(changes) -> SetParametersResult:
        for change in changes:
            spec = specs.get(change.name)
            problem = spec.problem(change.value) if spec else ""
            if problem:
                return SetParametersResult(successful=False, reason=f"{change.name} {problem}")
        return SetParametersResult(successful=True)

    def put_into_effect(changes) -> None:
        for change in changes:
            if change.name in specs:
                apply(change.name, change.value)

    node.add_on_set_parameters_callback(check)
    node.add_post_set_parameters_callback(put_into_effect)
