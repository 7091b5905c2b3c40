"""ROS domain ids held by file locks: graphs side by side get distinct ids, and a holder killed outright frees
its id at once."""

import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from semgoal_ros.domains import DOMAINS, NoFreeDomainError, lease


def test_held_ids_are_distinct_and_avoid_what_is_asked(tmp_path: Path) -> None:
    held = [lease({7}, tmp_path) for _ in range(len(DOMAINS) - 1)]
    try:
        assert len({domain for domain, _ in held}) == len(held) and 7 not in {domain for domain, _ in held}
        with pytest.raises(NoFreeDomainError, match="held by a running graph"):
            lease({7}, tmp_path)
    finally:
        for _, handle in held:
            handle.close()
    assert lease(set(), tmp_path)[0] in DOMAINS


@pytest.mark.slow
def test_a_killed_holder_frees_its_id(tmp_path: Path) -> None:
    avoid = set(DOMAINS) - {42}
    holder = subprocess.Popen([sys.executable, "-c", f"from pathlib import Path; from semgoal_ros.domains import lease; "
                               f"d, h = lease({avoid!r}, Path({str(tmp_path)!r})); print(d, flush=True); "
                               "import time; time.sleep(60)"], stdout=subprocess.PIPE, text=True)
    assert holder.stdout.readline().strip() == "42"
    with pytest.raises(NoFreeDomainError):
        lease(avoid, tmp_path)
    holder.send_signal(signal.SIGKILL)
    holder.wait(timeout=10)
    time.sleep(0.1)
    assert lease(avoid, tmp_path)[0] == 42
