/* -*- c++ -*- ----------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories
   LAMMPS development team: developers@lammps.org

   Copyright (2003) Sandia Corporation.  Under the terms of Contract
   DE-AC04-94AL85000 with Sandia Corporation, the U.S. Government retains
   certain rights in this software.  This software is distributed under
   the GNU General Public License.

   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: FRICTION-EQ developers
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   FRICTION-EQ package: one lambda_c-block of the far zone at T > 0 with
   screening (spec: shared/notes/thermal-aging.md (a), (e); paper Eqs.
   crack.eq03x-crack.eq07, scr.eq01-scr.eq05).  LAMMPS-free.

   BlockModel is the interface fix eq/meso drives: the athermal MesoModel
   (eq_meso.h, through AthermalBlocks) and the thermal ThermalMesoModel
   below.  A block's state is a flat, position-independent array of
   width() doubles (memcpy-able: it migrates and goes into restarts).

   Model (ThermalMesoModel)
   ------------------------
   The N_lambda contacts of a block moved to X: a contact with anchor A
   (stretch u = X - A) and threshold x_s ~ P_c in a block with load factor
   eps (frozen over one call) sees the effective stretch y = (1 + eps)
   max(u, 0) (one-sided, as MesoModel and the master equation: a
   compressed contact is as loaded as an unstretched one, so that at
   theta -> 0 a backward move breaks nothing, as at theta = 0, except
   that a contact compressed beyond the largest threshold, u <= -top,
   breaks: this bounds the anchors held, where MesoModel keeps such
   contacts); it breaks
     * at once when y >= x_s (threshold picture: also when eps grows at
       fixed X), and
     * thermally at the rate nu(y; x_s) = omega w^q exp(-(x_s/x_c)^p
       w^{3/2}/theta), w = 1 - y/x_s, per unit TIME (ThermalModel of
       eq_thermal.h, theta = k_B T/eps_a).
   NOTE: MesoModel follows the master equation with the rate (1 + eps)
   P((1 + eps) u) instead, where a jump of eps at fixed X breaks nothing.
   The two are the same at constant eps (steady sliding, the T -> 0 test)
   and differ when eps jumps.
   A broken contact re-forms at once, unstretched (R = delta(0)), or never
   (R null, "reform none"), or, with a formation delay (spec (b) 1),
   waits and re-forms unstretched where the block is then, with a fresh
   threshold: "delay exp tau" at the rate 1/tau per unit time, "delay
   fixed tau" exactly tau after it broke.  Waiting contacts carry no
   force (attached + waiting = 1).  Threshold aging (spec (b) 2): a
   contact of age t (time since it formed) has the threshold x_s0 A(t)
   (ThermalModel::factor: log or exp law), the barrier taking x_s0 A(t);
   the contacts of init() have the age spec.rest.  Other R are not
   supported (SpecError).  Start: all contacts unstretched (relaxed; with
   R = delta(0) start reform is the same).  At constant eps this is a
   block of contacts loaded at w = (1 + eps) v: F(X) = F_1((1 + eps) X)/
   (1 + eps) with F_1 the single-slider master equation at velocity w.
   At theta = 0 it is the athermal block (MesoModel, constant eps).

   Scheme (after tools/eqtools/slider.py)
   --------------------------------------
   Contacts are stored by ANCHOR on the grid A_j = j du (nodes) and by
   threshold LABEL PANEL: nl equal panels [a_l, b_l] of the support of
   P_c (cut at its 1e-17 quantiles), weight = the panel's probability;
   within a panel the thresholds are uniform (uniform P_c is exact).  Each
   anchor row keeps y_j, the largest effective stretch (1 + eps) max(X - A_j, 0)
   its contacts have seen: the thresholds left in panel l are uniform on
   [max(a_l, y_j), b_l].  A call advance(X1, eps, h) is split into n = ceil(|X1 - X0|/du)
   equal sub-steps of the path (X linear in time); per sub-step:
     * thermal: hazard by Simpson's rule in time (rates at the sub-step's
       start, middle and end, at the midpoint threshold of what is left of
       the panel), broken m (1 - e^{-H}), at the Simpson-weighted mean
       position; what is left below 1e-20 of a (row, panel) is broken;
     * crossings: y_j -> (1 + eps) max(X0 - A_j, X1 - A_j, 0); the
       panel part below it breaks (uniform: a closed form), at the
       position where it is crossed on average (at X0 when eps grew);
     * re-formation: all mass broken in the sub-step re-forms unstretched
       at its mean break position (crossing exact; crossing step: at the
       sub-step's end), put on the two neighbouring anchor nodes with hat
       weights (mass and mean anchor exact), with fresh thresholds (P_c
       by panels).  Re-formed contacts do not break again within the
       sub-step (it moves at most du).
     * break times: substep() also accumulates the first moment of the
       break TIMES (from the sub-step's start): crossings when X passes
       them (X linear in time), those of an eps jump at 0 (also at rest),
       thermal breaks at the Simpson-weighted mean time, compressed rows
       when X passes A - top; t_b = their mass-weighted mean (crossing
       step: h).  Not inferred from the mean position (lost at rest, and
       cancelling when dX is tiny); the no-delay path does not use it.
     * delay exp tau (instead of re-forming at once): the pool W (one
       double after the rows) loses W (1 - e^{-h/tau}) over the sub-step
       of time h, exactly; the mass broken in the sub-step joins it at
       the mean time of its breaks t_b and (1 - e^{-(h - t_b)/tau}) of it
       re-forms before the
       end.  Both parts re-form at X at their mean re-forming time
       (truncated exponential), hat weights as above.  tau = 0 or delay
       none: the state and the numbers are those without the keyword.
     * delay fixed tau: a FIFO of bins (start, end, mass) after the rows,
       one per SUB-STEP in flight (MESO_DELAY_BINS: tau may be up to
       MESO_DELAY_BINS - 2 = 1022 sub-steps, i.e. 1022 calls where a
       block moves du or less per call, fewer where it moves more; more is
       a std::runtime_error naming tau, the sub-steps of the call and the
       remedies).  The mass broken in a sub-step is due uniformly over
       [tau + t_b - w, tau + t_b + w], w = min(t_b, h - t_b) (within the
       sub-step's window shifted by tau, the mean re-forming time is the
       mean break time + tau); each sub-step re-forms the part of every
       bin due within it at X at the middle of that part.  (Re-forming a
       bin at once at its mean time makes the attached fraction first
       order in the step: measured 20 du^2 at v tau/dX = 270.27; so did
       one bin per call spread over the hull of its sub-steps' windows,
       which moves the mean: 25 du^2 at dX = 4 du, 99 du^2 at 8 du.)
     * aging: each anchor row also holds the mass-weighted mean age of its
       contacts (an array of one double per ring row after the rows), all
       rows growing older by h per sub-step; fresh contacts put on a row
       (age: from their mean re-forming time to the sub-step's end) take
       the mean with those it holds.  The row's history y_j becomes the
       largest y/A(t) its contacts have seen (the labels x_s0 left lie
       above it), taken at the sub-step's start, middle and end (the
       middle places the crossings); a crossed part breaks where y/A,
       linear between those three points, passes its mean label.  The thermal
       rates use the threshold x_m A(t) at the three Simpson times.  One
       age per row is exact to second order in sliding (a row is filled
       within the sub-steps in which X passes it: ages differing by du/v,
       against ages of x_s/v when they break), an approximation where
       contacts re-form onto a row holding older ones (at rest, after a
       backward move).  The ages change by h per sub-step, which is split
       by displacement only: a step of time h long against the contacts'
       ages plus tau_a (a long rest in one call) is inaccurate (measured:
       a rest of 1000, tau_a = 1, after sliding at 1e-2: F 9 % low in one
       call, converged in 10).  The ring holds thresholds up to ytop
       A(MESO_AGING_RING tau_a) (log; exp: ytop (1 + beta)), whatever
       rest and tau_a (a rest beyond MESO_AGING_RING tau_a is a
       SpecError); contacts that survive beyond it throw
       std::runtime_error naming aging.
   Probability is conserved by construction (broken = re-formed, or
   detached, or waiting).  Errors: O(du^2) from the anchors, O(h_l^2) from the panels
   (midpoint threshold), O(dt^2) relative hazard per step from Simpson.
   Only the rows from the lowest to the highest one holding mass are
   visited (a ring of 2 ceil(top/du) + 8 rows: no contact survives
   |u| >= top).
   Approximation: fresh contacts put on a row share its y_j; rows near X
   (where they go) have y_j <= (1 + eps) du, below the thresholds while
   the grid resolves the screened thresholds, except after a backward move
   of the block beyond its lowest screened threshold.  Grid limits:
   eps_accurate() = sd/(4 du) - 1 (beyond it (1 + eps) du is coarser than
   a quarter of the thresholds' sd: measured 14 % error of F at (1 + eps)
   du = 0.6 for uniform [0.75, 1.25]; fix eq/meso warns) and eps_valid()
   = median/du - 1 (beyond it fresh contacts inherit a history above half
   of the thresholds and the force can exceed what any contact carries:
   advance() throws GridError).  y_j is evaluated at the sub-steps' ends (exact: |X - A| is
   largest at an end of a straight path).
   Sub-steps: a move of du (1 + 1e-9) or less is one sub-step, so that
   the count (and the discretization) does not flip with the rounding of
   displacements that are nominally du (measured in a screened chain with
   dX = du: 1 or 2 sub-steps shift the steady eps0 by 0.6 %).

   Accuracy (measured, test_eq_meso_thermal.cpp): against the slider
   master equation at (1 + eps) v (ThermalTransient), uniform [0.75,1.25],
   theta = 0.05 and 0.1, v = 1e-3 ... 1e-1, eps = 0 ... 2, steps dX =
   du/2, panels of 3.1 du_eff: max |F - F_ref| over X in [0, 4] is 2.95
   ... 3.35 du_eff^2 (du_eff = (1 + eps) du); halving du, dX and the
   panel width divides it by 3.8 ... 4.0.  At theta = 0: within 1.1 du^2
   of the exact renewal solution (constant eps, increments 0.37 du, du =
   0.005 ... 0.02; eps = 0: 0.66 ... 0.75 du^2, eps = 0.5: 1.03 ... 1.09
   du^2), and equal to MesoModel to rounding with crossing step.
   With a delay (tau = 3 ... 100, v tau = 0.3 ... 1; theta = 0.05, 0.1;
   eps = 0, 1; dX = du/2): F(X) within 2.8 ... 3.4 du_eff^2 of the slider
   master equation with the same delay, the attached fraction within
   3.4 ... 4.1 (exp) and 6.6 (fixed) du_eff^2, converging at second order
   (ratio 3.7 ... 4.1); with steps of 4 and 8 du (theta = 0.05, v = 1e-2,
   tau = 30, 16 panels) F within 3.2 (fixed) and 3.4 (exp) du^2, the
   attached fraction within 4.9 (fixed) and 4.3 (exp) du^2; at theta = 0 the steady F_k and n_a with delay exp
   within 0.17 du_eff^2 of the closed forms <x_s^2>/(2 (<x_s> + w tau))
   and <x_s>/(<x_s> + w tau), w = (1 + eps) v, and F(X), n_a(X) with delay
   fixed within 1.1 du_eff^2 of the renewal solution (dX = 0.37 du).
   With aging (log and exp, beta = 0.05 ... 0.3, tau_a = 1 ... 30; theta
   = 0.05, 0.1; v = 1e-2, 1e-1; eps = 0, 1): F(X) within 3.6 ... 3.7
   du_eff^2 (the same runs without aging 3.1 ... 3.2), at theta = 0.02, v
   = 1e-3 10.6 (without 8.0), after a rest 1e2, 1e4 3.8 ... 4.2 du^2,
   second order (ratio 3.7 ... 4.3); at theta = 0 the peak of F after a
   rest t_w = 0, 1e2, 1e4, 1e6 (beta 0.05, tau_a 1, v 0.01) 0.9200,
   0.9478, 1.0957, 1.2680, the spec's (d) 0.920, 0.948, 1.096, 1.268.

   Cost: 3 exponentials per (row, panel) holding mass per sub-step; rows
   holding mass ~ top/((1 + eps) du) or fewer (thermal breaking empties
   rows before their thresholds), e.g. uniform [0.75,1.25], eps = 5,
   du = 0.003, 32 panels: ~70 rows, ~7000 exponentials, ~70 us.
------------------------------------------------------------------------- */

#ifndef FEQ_MESO_THERMAL_H
#define FEQ_MESO_THERMAL_H

#include "eq_distribution.h"
#include "eq_master_equation.h"    // Crossing, MEStart
#include "eq_meso.h"
#include "eq_thermal.h"

#include <cmath>
#include <memory>
#include <vector>

namespace feq {

// what fix eq/meso needs of a block kernel
class BlockModel {
 public:
  virtual ~BlockModel() = default;
  virtual int width() const = 0;
  virtual void init(double *state, double X0) const = 0;
  // move to X1 over the time h (>= 0) with load factor eps (>= 0); returns
  // the broken mass; X1 == X and h == 0: nothing changes (bitwise)
  virtual double advance(double *state, double X1, double eps, double h) const = 0;
  virtual double position(const double *state) const = 0;
  virtual double mean_stretch(const double *state) const = 0;
  virtual double attached(const double *state) const = 0;
  virtual double normalization_error(const double *state) const = 0;
  virtual bool valid(const double *state) const = 0;
  virtual double grid() const = 0;
  virtual double min_grid() const = 0;
  virtual std::unique_ptr<BlockModel> regrid(double du) const = 0;
  // load factors beyond which the grid no longer resolves the screened
  // thresholds x_s/(1 + eps): eps_accurate(): (1 + eps) du exceeds a
  // quarter of their standard deviation (accuracy lost; the caller warns);
  // eps_valid(): advance() throws GridError beyond it.  Infinite for
  // kernels whose conditioning does not depend on eps.
  virtual double eps_accurate() const { return HUGE_VAL; }
  virtual double eps_valid() const { return HUGE_VAL; }
};

// the athermal MesoModel (h ignored: nothing happens at rest)
class AthermalBlocks : public BlockModel {
 public:
  explicit AthermalBlocks(std::unique_ptr<MesoModel> m) : model(std::move(m)) {}
  int width() const override { return model->width(); }
  void init(double *s, double X0) const override { model->init(s, X0); }
  double advance(double *s, double X1, double eps, double) const override
  {
    return model->advance(s, X1, eps);
  }
  double position(const double *s) const override { return model->position(s); }
  double mean_stretch(const double *s) const override { return model->mean_stretch(s); }
  double attached(const double *s) const override { return model->attached(s); }
  double normalization_error(const double *s) const override
  {
    return model->normalization_error(s);
  }
  bool valid(const double *s) const override { return model->valid(s); }
  double grid() const override { return model->grid(); }
  double min_grid() const override { return model->min_grid(); }
  std::unique_ptr<BlockModel> regrid(double du) const override
  {
    return std::unique_ptr<BlockModel>(new AthermalBlocks(model->regrid(du)));
  }

 private:
  std::unique_ptr<MesoModel> model;
};

// default number of threshold label panels (fix eq/meso keyword 'labels')
constexpr int MESO_THERMAL_LABELS = 32;
// bins of the FIFO of a fixed delay (one per advance() call in flight:
// tau may be up to MESO_DELAY_BINS - 2 time steps)
constexpr int MESO_DELAY_BINS = 1024;
// log aging: the anchor ring holds contacts whose thresholds grew to
// x_s A(MESO_AGING_RING tau_a) (exp aging: its bound 1 + beta)
constexpr double MESO_AGING_RING = 1e8;

class ThermalMesoModel : public BlockModel {
 public:
  // Pc: thresholds; R: delta(0) or nullptr (reform none), anything else a
  // SpecError; du: anchor grid; nlabels: threshold panels (1 for a point
  // P_c); spec: theta >= 0, omega, p, q, xc, delay exp or fixed tau (a
  // delay needs R), aging (beta >= 0, tau_a > 0, finite), rest >= 0.
  // GridError for a grid too coarse for P_c (as MesoModel) or too fine
  // (width() > MESO_MAX_WIDTH).
  ThermalMesoModel(DistributionPtr Pc, DistributionPtr R, double du, const ThermalSpec &spec,
                   int nlabels = MESO_THERMAL_LABELS, Crossing crossing = Crossing::EXACT,
                   MEStart start = MEStart::RELAXED);

  int width() const override { return nwidth; }
  void init(double *state, double X0) const override;
  // throws std::invalid_argument for non-finite X1, eps < 0 or h < 0
  double advance(double *state, double X1, double eps, double h) const override;
  double position(const double *state) const override;
  double mean_stretch(const double *state) const override;    // at the stored X
  double attached(const double *state) const override;
  double detached(const double *state) const;
  double waiting(const double *state) const;    // broken, re-forming after the delay
  double rate(const double *state) const;    // broken / |dX| of the last call (0: dX = 0)
  double normalization_error(const double *state) const override;
  bool valid(const double *state) const override;
  double grid() const override { return du; }
  double min_grid() const override;
  std::unique_ptr<BlockModel> regrid(double du) const override;

  int labels() const { return nl; }
  double eps_accurate() const override { return eps_acc; }
  double eps_valid() const override { return eps_max; }
  double top() const { return ytop; }
  // rows holding mass (cost measure)
  long rows(const double *state) const;

 private:
  DistributionPtr Pc, R;
  double du, inv_du;
  ThermalSpec spec;
  int nlabels_req;
  Crossing crossing;
  MEStart start;
  int nl = 0;    // panels
  std::vector<double> pa, pb, pw;    // panel ends and weights
  std::vector<double> coef0, invx0;  // (x_m/x_c)^p/theta and 1/x_m of whole panels
  double ytop = 0.0;
  double eps_acc = HUGE_VAL, eps_max = HUGE_VAL;
  int ncap = 0, nwidth = 0;
  DelayKind delay = DelayKind::NONE;    // NONE also for tau = 0
  ThermalModel law;    // the aging factor A(t)
  bool aging = false;
  double aring = 1.0;    // the ring holds thresholds up to ytop aring (see MESO_AGING_RING)
  int ages = 0;    // offset of the rows' ages (aging only: one per ring row, after the rows)
  int pool = 0;    // offset of the waiting pool or FIFO in the state (after the rows, ages)
  double tag = 0.0;

  void set_panels();
  double *row(double *s, long j) const;
  const double *row(const double *s, long j) const;
  double &age(double *s, long j) const;
  double rate_at(double y, double inv_xm, double coef) const;
  double coef_at(double xs) const;
  void substep(double *s, double X0, double X1, double eps, double h, double &D, double &MX,
               double &DT) const;
  int extra_width() const;
  double mean_wait(double L) const;
  double break_time(double h, double D, double DT) const;
  void fifo(double *s, double X0, double X1, double h, double &D, double &MX, double &MT,
            double DT, long nsub) const;
  void wait(double *s, double X0, double X1, double h, double &D, double &MX, double &MT,
            double DT) const;
  void grow_old(double *s, double h) const;
  void reform(double *s, double X0, double X1, double D, double MX, double age_new) const;
  void add_fresh(double *s, long j, double m, double age_new) const;
  void trim(double *s) const;
  void totals(double *s) const;
};

}    // namespace feq

#endif
