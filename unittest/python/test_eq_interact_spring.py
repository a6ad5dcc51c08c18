"""Stick-slip from the interaction between contacts (paper Sec. IV,
"Stick-slip versus smooth sliding"; examples/eq-interact/run_spring.py).

A slider on realistic thresholds (x_s = 1, N = 4080) pulled through a
spring K = 2 K* (K* = 0.17425 K_s, the non-interacting ME):

* kappa = 0: K > K*, the slider follows the quasi-static branch: no slip
  (no stretch of time with V > 3 v in which it advances > 5 stage
  windows), and within any stage window it advances at most
  K/(K - K*) = 2 windows (3 allowed for the noise at N = 4080);
* kappa = 0.2: K*_eff = 4.5 K* > K (run_kstar.py), the slider slips at
  the static peak: a slip of more than 5 windows starting while the spring
  force is within 5 % of the static peak, with a force drop larger than
  5 times the largest force drop of the smooth run within the same
  stage interval, and a velocity peak above 3 v.

Time step 0.2 (0.1 in the example): the slider's damping rate 2 and
spring frequency 0.6 stay well resolved.
"""
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "examples" / "eq-interact"))
import run_spring  # noqa: E402


def _largest_drop(d, n):
    """Largest decrease of the spring force within n records."""
    Fk = d[:, 4]
    return max(float(np.max(Fk[:-m] - Fk[m:])) for m in range(1, n + 1))


def test_interaction_turns_smooth_sliding_into_stick_slip(tmp_path):
    runs = {k: run_spring.run_one(k, tmp_path, Kratio=2.0, seed=2024, xend=4.2, dt=0.2)
            for k in (0.0, 0.2)}
    smooth, stick = (run_spring.slips(runs[k]) for k in (0.0, 0.2))

    assert smooth["events"] == [], smooth["events"]
    assert smooth["max_advance"] < 3.0
    assert smooth["v_max"] < 3.0

    assert len(stick["events"]) >= 1
    first = stick["events"][0]
    d = runs[0.2]
    peak = d[:, 4].max()
    i = int(np.argmin(np.abs(d[:, 0] - first["stage"])))
    assert d[max(i - 1, 0), 4] > 0.95 * peak          # slips at the static peak
    assert first["jump"] > 5 * run_spring.WINDOW
    assert stick["v_max"] > 3.0
    # the force drop of the slip against the smooth run's noise
    ds = runs[0.0][runs[0.0][:, 0] >= run_spring.LOAD]
    noise = _largest_drop(ds, 2 * int(round(run_spring.WINDOW / (ds[1, 0] - ds[0, 0]))))
    assert first["drop"] > 5 * noise, (first, noise)
    assert stick["max_advance"] > 2 * smooth["max_advance"]
