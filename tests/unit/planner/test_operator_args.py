"""`./semgoal plan` refuses a step number it cannot send, before anything is sent ('²' printed a
traceback, and 4294967302 wrapped round to step 6 in the uint32 field)."""

import pytest

from semgoal_planner.operator import plan_main


@pytest.mark.parametrize("index", ["²", "4294967302", "-1", "1.5", "x"])
def test_a_step_number_out_of_range_or_not_a_number_is_refused(index: str, capsys) -> None:
    with pytest.raises(SystemExit) as exit_info:
        plan_main(["remove", index])
    assert exit_info.value.code == 2
    assert f"INDEX must be a step number (0 to 4294967295), got {index!r}" in capsys.readouterr().err
