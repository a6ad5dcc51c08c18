# pytest set-up for the FRICTION-EQ physics tests: the analysis tools live
# in tools/eqtools; lmp and eq-me come from FEQ_LMP / FEQ_EQME (set by ctest)
# or from ./build.
import importlib.util
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))


def load_example(name):
    """examples/<name>/run.py as module example_<name> (the examples all
    call their driver run.py)."""
    spec = importlib.util.spec_from_file_location(f"example_{name.replace('-', '_')}",
                                                  ROOT / "examples" / name / "run.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod
