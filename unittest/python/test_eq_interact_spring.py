"""A slip from the interaction between contacts (paper Sec. IV,
"Stick-slip versus smooth sliding"; examples/eq-interact/run_spring.py).

A slider on realistic thresholds (x_s = 1, N = 4080) pulled through a
spring K = 2 K* (K* = 0.17425 K_s, the non-interacting ME):

* kappa = 0: K > K*, the slider follows the quasi-static branch: no slip
  (no stretch of time with V > 3 v in which it advances > 5 stage
  windows), and within any stage window it advances at most
  K/(K - K*) = 2 windows (3 allowed for the noise at N = 4080);
* kappa = 0.2: K*_eff = 4.5 K* > K (run_kstar.py), the slider slips at
  the static peak: a slip of more than 5 windows starting while the spring
  force is within 5 % of the static peak, a velocity peak above 3 v, a
  spring-force drop of more than 0.03 N k_c, and a largest force drop
  within one stage window more than twice that of the smooth run (which
  stays below twice its quasi-static bound 2 K* WINDOW).  It is one slip,
  at the onset peak, not a repeated stick-slip cycle: the kinetic plateau
  is not steeper than K (run_spring.py to stage 6: one slip for kappa =
  0.05, 0.1, 0.2).

Time step 0.2 (0.1 in the example): the slider's damping rate 2 and
spring frequency 0.6 stay well resolved.
"""
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "examples" / "eq-interact"))
import run_spring  # noqa: E402


def _drop_per_window(d):
    """Largest decrease of the spring force within one stage window
    (stage > LOAD).  Quasi-static sliding bounds it by
    K K*/(K - K*) WINDOW = 2 K* WINDOW = 0.007 N k_c (plus noise)."""
    d = d[d[:, 0] >= run_spring.LOAD]
    n = int(round(run_spring.WINDOW / (d[1, 0] - d[0, 0])))
    return float(np.max(d[:-n, 4] - d[n:, 4]))


def test_interaction_turns_smooth_sliding_into_one_onset_slip(tmp_path):
    runs = {k: run_spring.run_one(k, tmp_path, Kratio=2.0, seed=2024, xend=4.2, dt=0.2)
            for k in (0.0, 0.2)}
    smooth, stick = (run_spring.slips(runs[k]) for k in (0.0, 0.2))

    assert smooth["events"] == [], smooth["events"]
    assert smooth["max_advance"] < 3.0
    assert smooth["v_max"] < 3.0

    assert len(stick["events"]) == 1     # one slip, at the peak; no cycle
    first = stick["events"][0]
    d = runs[0.2]
    peak = d[:, 4].max()
    i = int(np.argmin(np.abs(d[:, 0] - first["stage"])))
    assert d[max(i - 1, 0), 4] > 0.95 * peak          # slips at the static peak
    assert first["jump"] > 5 * run_spring.WINDOW
    assert stick["v_max"] > 3.0
    # the force drop against the smooth run (measured 0.0096 at dt = 0.1,
    # 1.4 times the quasi-static bound; the slip at kappa = 0.2 gives 0.026)
    qs_bound = 2 * 0.17425 * run_spring.WINDOW
    assert _drop_per_window(runs[0.0]) < 2 * qs_bound
    assert _drop_per_window(runs[0.2]) > 2 * _drop_per_window(runs[0.0])
    assert first["drop"] > 0.03          # onset drop F_s - F_min ~ 0.05 N k_c
    assert stick["max_advance"] > 1.5 * smooth["max_advance"]
