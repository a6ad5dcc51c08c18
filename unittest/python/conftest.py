# pytest set-up for the FRICTION-EQ physics tests: the analysis tools live
# in tools/eqtools; lmp and eq-me come from FEQ_LMP / FEQ_EQME (set by ctest)
# or from ./build.
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
sys.path.insert(0, str(ROOT / "examples" / "eq-rigid"))
