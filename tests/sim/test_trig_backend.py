"""The state's bulk trigonometry (the curvy lasers' heads, a BulletML volley's new bullets'
velocities and headings) goes through the world's collision backend: compiled or not, the
same bits, so a replay does not depend on whether numba is installed."""

from __future__ import annotations

from support.compiled import NEEDS_NUMBA

from broadsword.bench.game_frame import LASER_LEVEL
from broadsword.collision._kernel import Kernel
from broadsword.runner import Runner, StageStart
from broadsword.sim import Input
from broadsword.sim.hashing import part_digests

STEPS = 200


def _digests(monkeypatch, kernel: Kernel) -> tuple[list[bytes], int, int]:
    monkeypatch.setenv("BROADSWORD_KERNEL", kernel.value)  # the world's pipeline takes the default
    runner = Runner.open(StageStart(str(LASER_LEVEL), 0))
    world = runner.world
    backend = world.pipeline.backend
    assert world.pipeline.kernel is kernel
    assert world.enemy_bullets.trig is backend and world.lasers.trig is backend
    out = []
    for _ in range(STEPS):
        runner.step(Input(fire=True))
        out.append(part_digests(world))
    return out, world.guns.engine.fired, len(world.lasers.live_rows())


@NEEDS_NUMBA
def test_laser_scene__same_state_under_both_kernels(monkeypatch):
    """The laser scene stepped under each kernel: the same part digests
    at every frame (its volleys and curvy lasers are what the backend's trigonometry does)."""
    compiled, fired, lit = _digests(monkeypatch, Kernel.NUMBA)
    reference, _, _ = _digests(monkeypatch, Kernel.NUMPY)
    assert fired > 2_000 and lit > 50  # the scene reached what it is for
    first = next((i for i, (a, b) in enumerate(zip(compiled, reference, strict=True)) if a != b), None)
    assert first is None, f"the states differ from frame {first}"
