"""Ctrl-C is Ctrl-C even where it lands inside an rclpy call and pybind11 hands it on as another error."""

from semgoal_ros.client import interrupted


def _raised(error: BaseException, cause: BaseException | None = None) -> BaseException:
    try:
        if cause is None:
            raise error
        raise error from cause
    except BaseException as caught:
        return caught


def test_a_keyboard_interrupt_is_one_plain_or_wrapped_by_pybind11() -> None:
    assert interrupted(_raised(KeyboardInterrupt()))
    assert interrupted(_raised(TypeError("Unable to convert function return value to a Python type!"), KeyboardInterrupt()))
    assert not interrupted(_raised(TypeError("a real type error")))
    assert not interrupted(_raised(RuntimeError("rcl: context invalid"), ValueError("bad")))
    assert not interrupted(None)
