"""Regenerate the golden traces of the shipped patterns (tests/patterns/golden/*.json).

    python tools/golden_patterns.py            # rewrite every golden file
    python tools/golden_patterns.py --check    # exit 1 if any differs (what the test does)

Each golden file holds, for one pattern run by ``bulletml.trace`` (rank 0.5, seed 0, emitter
at (240, 160), target at (240, 560), the kinds with the parameters in ``RUNS``): the live
bullet count after every frame and every bullet's position (4 decimals) after frames 60,
120 and 180. Regenerate only after checking a change of behaviour is intended: the simple
patterns are also checked against hand-computed positions in tests/patterns.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from broadsword.fileio import write_atomic  # noqa: E402
from broadsword.patterns import bulletml  # noqa: E402

PATTERNS = ROOT / "assets" / "patterns"
GOLDEN = ROOT / "tests" / "patterns" / "golden"
FRAMES = 180
SNAPSHOTS = (60, 120, 180)
ORIGIN, TARGET = (240.0, 160.0), (240.0, 560.0)
#: The game's kinds need parameters: speed px/frame, shots, spread or turn (degrees), every, delay (frames).
RUNS = {
    "aimed": (3.0, 3, 20.0, 40, 5),
    "spread": (2.5, 5, 60.0, 40, 0),
    "ring": (2.5, 12, 10.0, 30, 0),
    "spiral": (3.0, 4, 11.0, 6, 0),
}


def golden(name: str) -> dict:
    """The golden record of ``assets/patterns/NAME.xml``."""
    pattern = bulletml.load(PATTERNS / f"{name}.xml")
    params = RUNS.get(name, ())
    eng = bulletml.Engine(rank=0.5, seed=0)
    eng.target = np.array(TARGET)
    eng.add_emitter(pattern, ORIGIN, params)
    counts, shots = [], {}
    for frame in range(1, FRAMES + 1):
        eng.step()
        counts.append(eng.bullets.n)
        if frame in SNAPSHOTS:
            shots[str(frame)] = np.round(eng.bullets.pos[: eng.bullets.n], 4).tolist()
    return {
        "pattern": f"{name}.xml",
        "params": list(params),
        "rank": 0.5,
        "seed": 0,
        "origin": ORIGIN,
        "target": TARGET,
        "counts": counts,
        "positions": shots,
    }


def names() -> list[str]:
    return sorted(p.stem for p in PATTERNS.glob("*.xml"))


def main(argv: list[str]) -> int:
    check = "--check" in argv
    bad = 0
    for name in names():
        data = golden(name)
        path = GOLDEN / f"{name}.json"
        if check:
            if not path.exists() or json.loads(path.read_text()) != json.loads(json.dumps(data)):
                print(f"{path}: differs from a fresh run", file=sys.stderr)
                bad += 1
        else:
            write_atomic(path, (json.dumps(data, separators=(",", ":")) + "\n").encode())
            print(f"wrote {path.relative_to(ROOT)}")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
