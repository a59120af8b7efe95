"""The add-on keeps what batten_native's allocator freed for the next build.

mimalloc (batten_native's allocator) gives freed memory back to the system after 10 ms by
default, and the next build then faults it all in again. Importing :mod:`batten` sets
``MIMALLOC_PURGE_DELAY`` before ``batten_native`` loads, unless the user set it.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# Two builds of the frigate 0.1 s apart; prints the page faults of the second.
_SECOND_BUILD_FAULTS = """
import resource, sys, time
sys.path.insert(0, {addon!r})
import batten
import batten_native as bn
_, curves, _ = bn.network_from_json(open({network!r}).read())
bn.build_surface(curves, 1e-4, 12)
time.sleep(0.1)
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
bn.build_surface(curves, 1e-4, 12)
print(resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before)
"""


def _second_build_faults(purge_delay: str | None) -> int:
    env = {k: v for k, v in os.environ.items() if k != "MIMALLOC_PURGE_DELAY"}
    if purge_delay is not None:
        env["MIMALLOC_PURGE_DELAY"] = purge_delay
    code = _SECOND_BUILD_FAULTS.format(
        addon=str(ROOT / "addon"), network=str(ROOT / "examples" / "frigate_network.json")
    )
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True)
    return int(out.stdout.split()[-1])


def test_importing_batten_sets_the_purge_delay_and_keeps_the_users():
    code = "import os, batten; print(os.environ['MIMALLOC_PURGE_DELAY'])"
    env = {k: v for k, v in os.environ.items() if k != "MIMALLOC_PURGE_DELAY"}
    env["PYTHONPATH"] = str(ROOT / "addon")
    run = lambda env: subprocess.run(  # noqa: E731
        [sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True
    ).stdout.strip()
    assert run(env) == "1000"
    assert run({**env, "MIMALLOC_PURGE_DELAY": "0"}) == "0"


def test_a_second_build_reuses_the_first_builds_memory():
    # With the add-on's delay the second build finds the first one's pages still there; with
    # mimalloc purging at once it faults them in again.
    kept = _second_build_faults(None)
    purged = _second_build_faults("0")
    assert purged >= 100, f"purged at once: {purged} page faults"
    assert kept <= purged // 4, f"kept {kept} page faults against {purged} purged"
