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
   FRICTION-EQ package: the break engine of the EQ model (paper Sec. II,
   and Sec. IV for interacting contacts).  LAMMPS-free: fix eq/contacts
   keeps one row of CS_NCOL doubles per contact (its per-atom array) and
   hands the rows to this engine, for the stepping path (a slider step,
   breaks resolved at the end of it) and for the quasi-static path (the
   slider advanced exactly to the next break) alike.

   A contact is a spring of stiffness k between the slider (an atom, its
   top end) and an anchor on the substrate.  Its stretch is s = x - anchor
   along the sliding direction.  It breaks when its effective stretch
   e = s + h/k (h: the elastic field of the other contacts, 0 without
   interaction) reaches its threshold x_s ~ P_c in absolute value, and
   re-forms with a stretch r ~ R (mirrored, -r, when it broke with e < 0);
   its new threshold is drawn above |r| and, with per-contact stiffness,
   its new k.  All draws are stateless (seed, atom tag, break count,
   stream), so a contact's history does not depend on where it is
   computed.

   crossing exact: the load that took the contact past its threshold is
   continuous, so the contact broke where e reached x_s and the overshoot
   e - x_s goes on into the new contact (Abelian cascades; fixed slider
   steps are exact at their ends).  crossing step: nothing is carried (the
   cellular-automaton convention).

   reform_as force (interacting contacts): the new contact carries force
   k r (+ carry) with the interaction included: its stretch solves
   k s' + h' = k target with h' = h + K (s' - s), K = sum_j k_ij;
   reform_as stretch: the new spring simply has stretch target.

   Avalanche (interacting contacts): synchronous rounds; in each round all
   contacts over their thresholds at its start break at once, then the
   field changes by the scattered stretch changes, until no contact is
   over its threshold anywhere (independent of the decomposition).
------------------------------------------------------------------------- */

#ifndef FEQ_CONTACT_H
#define FEQ_CONTACT_H

#include "eq_distribution.h"
#include "eq_thermal.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace feq {

// columns of a contact's state row (the per-atom array of fix eq/contacts)
enum ContactColumn : int {
  CS_STRETCH,      // s = x - anchor (0 while detached)
  CS_THRESHOLD,    // x_s; 0: no contact formed yet; < 0: detached for good
  CS_FORCE,        // k s of the last force evaluation
  CS_NBREAK,       // breaks so far (the event counter of the draws)
  CS_STIFFNESS,    // k; < 0 marks an atom that left the group (re-entry)
  CS_ANCHOR,       // anchor on the substrate (unwrapped coordinate along dir)
  CS_FIELD,        // h of the elastic field at the last force evaluation
  CS_NCOL
};

// further columns of a contact's row with temperature, aging or delays
// (eq_thermal.h): the row is then CT_NCOL wide.  Thermal breaking is
// sampled by thinning: candidate breaks come at the constant rate
// CT_BOUND_RATE >= nu while |s| <= CT_BOUND_S (and x_s >= CT_XS_LOW); a
// candidate at time t is accepted with probability nu(t)/CT_BOUND_RATE
// (see ContactModel::advance())
enum ThermalColumn : int {
  CT_BUDGET = CS_NCOL,    // hazard of the bound left until the next candidate break (Exp(1))
  CT_AGE,                 // time since the contact formed
  CT_WAIT,                // > 0: broken, re-forms after this time (stretch CS_STRETCH is 0)
  CT_PENDING,             // the stretch it re-forms with, while it waits
  CT_OUTPUTS,             // (the columns above are the per-atom output)
  // the sampler's state (restart data like the rest: the break times depend on it)
  CT_BOUND_RATE = CT_OUTPUTS,    // nu_bar >= nu while |s| <= CT_BOUND_S (0 without a bound)
  CT_BOUND_S,                    // the bound holds while |s| <= this; < 0: no bound yet
  CT_CANDIDATE,                  // candidates drawn in this life (their draws' counter)
  // a lower bound of the current threshold x_s0 A(age) (A >= 1 and grows
  // with age): x_s0 at formation
  CT_XS_LOW,
  CT_NCOL
};

// the stored form of a thermal row (fix eq/contacts' per-atom state
// between its calls into this engine): the budget and the age as times on
// a clock the owner keeps, so that a step that keeps a contact within its
// bound writes neither (stored_quick()).  The engine's functions take rows
// in engine form: to_engine() before a call, from_engine() after it.
enum StoredColumn : int {
  // the time at which the budget runs out at the bound's rate, while a
  // bound with a rate > 0 counts it down (|s| <= CT_BOUND_S: time spent
  // within the bound uses it), >= 0; otherwise minus the budget (a sign
  // bit set: -0.0 for a budget of 0), which no time changes
  CT_RUNOUT = CT_BUDGET,
  // the time at which the contact formed (age = clock - this); for one
  // that waits to re-form, the time at which it re-forms
  CT_FORMED = CT_AGE
};
// the width of the thermal row before thinning (a restart file of that
// layout cannot be continued; one with the budget and the age in engine
// form between steps, the same width as now, is known by its fix's record)
constexpr int CT_NCOL_HAZARD_BUDGET = 16;

// what to_engine() found and made of a stored row at time t
struct StoredForm {
  double t, formed, runout;                              // the stored times
  double nbreak, threshold, wait, candidate, rate, bound;    // the life and its bound
  double age, budget;                                    // as made
};
// a thermal row from stored to engine form at time t
StoredForm to_engine(double *st, double t);
// back to stored form at time t (the end of what the engine did).  The
// formation time changes only with a new life (a break, a formation, the
// end of a wait), the run-out time only with a new bound, rate or
// candidate: between those the engine's age and budget moved with the
// clock alone, so that a contact's stored times do not depend on when it
// was converted (they keep their bits)
void from_engine(double *st, double t, const StoredForm &was);
// a row the engine made (no stored form before: a contact formed now)
void from_engine(double *st, double t);
// f(), the engine's work on a stored row st, with st in engine form from
// time t0 and back in stored form at time t1 (the end of what f did).
// (C++11: LAMMPS 29 Sep 2021 builds the package with -std=c++11)
template <class F> auto engine_call(double *st, double t0, double t1, F &&f) -> decltype(f())
{
  struct Back {
    double *st;
    double t;
    StoredForm was;
    ~Back() { from_engine(st, t, was); }
  } back{st, t1, to_engine(st, t0)};
  return f();
}


// one step of a contact with temperature, aging or delays
struct ThermalStepResult {
  double stretch = 0.0;    // at the end of the step (0: absent)
  bool attached = false;   // formed at the end of the step
  bool renewed = false;    // broke or re-formed during the step: its anchor is new
};

// a contact cannot be handled (numerical instability, runaway breaking):
// the message names the contact and what to change
class BreakError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ContactModel {
 public:
  // thresholds P_c, re-forming stretches R (dist null: never re-form) and
  // per-contact stiffness factors (text "constant": all k = kc)
  ContactModel(double kc, uint64_t seed, const DistributionSpec &threshold,
               const DistributionSpec &reform, const DistributionSpec &stiffness, bool exact,
               bool reform_force, bool start_reform, const ThermalSpec &thermal = ThermalSpec());

  // doubles per contact row: CS_NCOL, or CT_NCOL with temperature, aging or delays
  int columns() const { return thermal_on ? static_cast<int>(CT_NCOL) : static_cast<int>(CS_NCOL); }
  // the columns that are per-atom output
  int outputs() const { return thermal_on ? static_cast<int>(CT_OUTPUTS) : static_cast<int>(CS_NCOL); }
  // a new run (the parameters may differ from those of the run that
  // wrote a restart file): the threshold's lower bound and the rate
  // bound made valid for this run's parameters; unchanged (to the bit)
  // when they are those that made them
  void new_run(double *st) const;
  // no bound of the rate yet (the next step chooses one)
  static constexpr double NO_BOUND = -1.0;
  // a bound that holds at any stretch
  static constexpr double BOUND_ALL = 1.0e308;
  bool thermal_active() const { return thermal_on; }
  const ThermalModel &thermal_model() const { return thermal; }

  // a contact forms at an atom with unwrapped coordinate xu: its first
  // formation (event 0), or a re-entry into the group (row marked by
  // CS_STIFFNESS < 0: the re-entry streams at its current break count)
  void form(double *st, uint64_t tag, double xu) const;
  // an atom left the group: no contact until it comes back
  void depart(double *st) const;

  // one break of a contact whose effective stretch e reached its
  // threshold; h, K: its field and coupling (0, 0 without interaction).
  // e_break finite: it broke thermally within the step where its
  // effective stretch was e_break (with crossing exact the new contact
  // re-forms on that side, the motion since, e - e_break, carried, and
  // its life is `age` old; with crossing step at the end of the step, as
  // advance()); NaN: at its threshold (threshold_now()).  Returns the new
  // stretch (0 when it detached for good: CS_THRESHOLD < 0, or waits to
  // re-form with a delay: leaves_field(), CT_WAIT > 0).
  double break_once(double *st, uint64_t tag, double e, double h, double K,
                    double e_break = NAN, double age = 0.0) const;

  // the threshold of a formed contact now: x_s, with aging x_s0 A(age)
  double threshold_now(const double *st) const
  {
    return aging_on ? st[CS_THRESHOLD] * thermal.factor(st[CT_AGE]) : st[CS_THRESHOLD];
  }
  // threshold_now() of an attached contact's row in stored form at time t
  double threshold_stored(const double *st, double t) const
  {
    return aging_on ? st[CS_THRESHOLD] * thermal.factor(std::max(0.0, t - st[CT_FORMED]))
                    : st[CS_THRESHOLD];
  }

  // interacting contacts at T > 0 (no delay): the thermal part of one time
  // step dt of an attached contact whose effective stretch goes linearly
  // from e0 to e1.  Samples the thermal break up to where e would cross
  // the aged threshold (thinning, as advance()); the crossing itself and
  // everything after a break is the avalanche's.  Without a thermal break
  // the contact ages by dt; with one, the row is left at the break (its
  // sampler state consumed up to it) for break_once().
  struct ThermalProbe {
    bool broke = false;
    double frac = 1.0;    // fraction of the step at which it broke
  };
  ThermalProbe probe(double *st, uint64_t tag, double e0, double e1, double dt) const;

  // probe()'s common case inline (the same numbers): e stays below the
  // lower bound of the threshold and, THERMAL (the model's T > 0), within
  // the rate bound at both ends (so along the whole step), with no
  // candidate break within the step: the contact ages by dt.  False (the
  // row untouched) otherwise
  template <bool THERMAL> bool quick_probe(double *st, double e0, double e1, double dt) const
  {
    const double a = std::fabs(e1);
    if (!(a < st[CT_XS_LOW])) return false;
    if (THERMAL) {
      if (!(a <= st[CT_BOUND_S]) || !(std::fabs(e0) <= st[CT_BOUND_S])) return false;
      const double dH = st[CT_BOUND_RATE] * dt;
      if (!(dH < st[CT_BUDGET])) return false;
      st[CT_BUDGET] -= dH;
    }
    st[CT_AGE] += dt;
    return true;
  }

  // quick_attached() of a row in stored form, the step ending at time
  // t_end on its clock: the same choice (to rounding: the budget runs out
  // at a time instead of after a sum of decrements), and only the stretch
  // is written (the contact ages and uses its budget as the clock goes on)
  template <bool THERMAL> static bool stored_quick(double *st, double m, double t_end)
  {
    const double a = std::fabs(m);
    if (!(a < st[CT_XS_LOW])) return false;
    if (THERMAL && !(a <= st[CT_BOUND_S] && t_end < st[CT_RUNOUT])) return false;
    st[CS_STRETCH] = m;
    return true;
  }
  // quick_probe() of a row in stored form (it writes nothing)
  template <bool THERMAL>
  static bool stored_quick_probe(const double *st, double e0, double e1, double t_end)
  {
    const double a = std::fabs(e1);
    if (!(a < st[CT_XS_LOW])) return false;
    return !THERMAL ||
        (a <= st[CT_BOUND_S] && std::fabs(e0) <= st[CT_BOUND_S] && t_end < st[CT_RUNOUT]);
  }

  // without interaction: every break of one contact within a step, until
  // |s| < x_s - tol; returns the new stretch and adds to nbreaks
  double resolve(double *st, uint64_t tag, double s, double tol, long &nbreaks) const;

  // the breaking test, |e| >= x_s - tol, with the tolerance of quasi-static
  // driving (relative; 0 for a plain test) scaled by the magnitudes involved
  static double tolerance(const double *st, double rel)
  {
    return tolerance(st[CS_ANCHOR], st[CS_STRETCH], rel);
  }
  // the same for a row with this anchor and stretch
  static double tolerance(double anchor, double s, double rel)
  {
    return rel > 0.0 ? rel * (1.0 + std::abs(anchor) + std::abs(s)) : 0.0;
  }

  // with temperature, aging or delays (row of CT_NCOL): one time step dt
  // of a contact.  m: for an attached contact its stretch at the end of
  // the step (the slider's position minus the anchor), for a waiting one
  // the distance its atom moved in the step; the motion is taken linear in
  // time.  The contact breaks when |s| reaches x_s0 A(age) or at the first
  // accepted candidate of the thermal break process (thinning: exact in
  // law for any dt); with crossing exact at that instant within the step,
  // the rest of the motion going into the next life (with crossing step:
  // at the end of the step).  A broken contact waits its delay, then
  // re-forms.
  ThermalStepResult advance(double *st, uint64_t tag, double m, double dt, long &nbreaks) const;

  // advance(), with its most common case inline: an attached contact that
  // stays below the lower bound of its threshold, within its rate bound,
  // and has no candidate break within the step (the same numbers as
  // advance())
  ThermalStepResult step(double *st, uint64_t tag, double m, double dt, long &nbreaks) const
  {
    ThermalStepResult res;
    if (st[CT_WAIT] > 0.0 && dt > 0.0 && quick_wait(st, m, dt)) return res;
    if (!quick_step(st, m, dt)) return advance(st, tag, m, dt, nbreaks);
    res.stretch = m;
    res.attached = true;
    return res;
  }

  // step()'s common case alone: true when it applied (the row updated as
  // advance() would), false when it does not (the row untouched)
  bool quick_step(double *st, double m, double dt) const
  {
    if (st[CT_WAIT] > 0.0 || !(dt > 0.0)) return false;
    return thermal_T ? quick_attached<true>(st, m, dt) : quick_attached<false>(st, m, dt);
  }

  // quick_step() for a contact known to be attached (CT_WAIT <= 0), dt > 0,
  // THERMAL: the model's temperature is > 0.  An attached contact's
  // stretch is within its bound (|s| <= CT_BOUND_S) or it has none: the
  // whole step is, when its end is.  THERMAL: true for no contact that is
  // not attached (no bound: CT_BOUND_S < 0 while a contact is not formed,
  // detached for good or waiting, see NO_BOUND), so that the caller may
  // skip those tests
  template <bool THERMAL> bool quick_attached(double *st, double m, double dt) const
  {
    const double a = std::fabs(m);
    if (!(a < st[CT_XS_LOW])) return false;
    if (THERMAL) {
      if (!(a <= st[CT_BOUND_S])) return false;
      const double dH = st[CT_BOUND_RATE] * dt;
      if (!(dH < st[CT_BUDGET])) return false;
      st[CT_BUDGET] -= dH;
    }
    st[CT_AGE] += dt;
    st[CS_STRETCH] = m;
    return true;
  }

  // the stretch of an attached contact set outside a step (no time
  // passes: minimization, a new anchor): its bound dropped when it no
  // longer covers it
  void hold(double *st, double s) const
  {
    st[CS_STRETCH] = s;
    if (!(std::fabs(s) <= st[CT_BOUND_S])) st[CT_BOUND_S] = NO_BOUND;
  }

  // a waiting contact whose delay lasts beyond this step (m: its atom's
  // motion): the delay shortened by dt, stretch 0, as advance() does
  // (which then leaves the contact absent); false (the row untouched)
  // otherwise
  bool quick_wait(double *st, double m, double dt) const
  {
    if (!wait_goes_on(st[CT_WAIT], m, dt)) return false;
    st[CT_WAIT] -= dt;
    st[CS_STRETCH] = 0.0;
    return true;
  }
  // quick_wait()'s test: a wait of this length left goes on over the
  // step (the atom's motion m finite); it is then wait - dt
  bool wait_goes_on(double wait, double m, double dt) const
  {
    return wait > (exact ? dt : dt + 1e-9 * dt) && std::isfinite(m);
  }

  // the thinning sampler's choice of bound, from the contact's path and
  // draws alone (not the step: for a stretch linear in time the break
  // times do not depend on dt).  A bound made at stretch x, where the
  // stretch changes at speed w, holds up to where the rate (its barrier
  // term) reaches e^L, L = ln nu(x) + r: the largest r with about
  // BOUND_CANDIDATES candidates expected before the stretch gets there
  // (ln nu taken linear in |x|), at least BOUND_LOG_STEP, at most
  // (1 - 1/BOUND_LADDER) d, d = ln omega - ln nu(x); the top (any
  // stretch) once d is below BOUND_LOG_STEP/2 or would be.  It is made
  // anew for a new life, where the path leaves it, and at a rejected
  // candidate.
  static constexpr double BOUND_CANDIDATES = 0.5;
  static constexpr double BOUND_LADDER = 16.0;
  static constexpr double BOUND_LOG_STEP = 1.0;
  // the rise r of a bound's log rate above psi (level()): K = BOUND_CANDIDATES
  // w (d psi/d|x|), d = ln omega - psi > BOUND_LOG_STEP/2
  static double bound_rise(double k, double psi, double d);
  // a contact formed again at a re-entry counts its candidates from here
  // (its draws differ from those of the life before it left)
  static constexpr double CANDIDATE_REENTRY = 1099511627776.0;    // 2^40

  // counts of the sampler's work on this model (diagnostics, not state)
  struct SamplerCounts {
    long candidates = 0, refreshes = 0;
  };
  const SamplerCounts &sampler_counts() const { return counts; }

  bool reforms() const { return reform.dist != nullptr; }
  bool reform_as_force() const { return reform_force; }

  // interacting contacts with a formation delay (delay fixed or exp with
  // tau > 0): a broken contact leaves the field while it waits, and
  // re-forms relaxed in the field of the contacts attached then
  bool leaves_field() const
  {
    return thermal_on && thermal.params().delay != DelayKind::NONE && thermal.params().tau > 0.0;
  }
  // a formed contact waiting to re-form (thermal rows only)
  bool waiting(const double *st) const
  {
    return thermal_on && st[CS_THRESHOLD] > 0.0 && st[CT_WAIT] > 0.0;
  }
  // an interacting contact whose delay ends within this step of dt
  // (quick_wait() was false; m: its atom's motion in the step): it
  // re-forms at that instant with crossing exact, the rest of the motion
  // carried and its age the time since (at the end of the step with
  // crossing step).  Returns its effective stretch at the end of the step
  // (the stretch it re-forms with, plus the motion carried): the caller
  // places it in the field of its partners
  double rejoin(double *st, double m, double dt) const;

  // at most this many breaks of one contact within one step
  static constexpr int MAX_BREAKS_PER_STEP = 1000;

 private:
  double k0;
  uint64_t seed;
  DistributionSpec threshold, reform, stiffness;
  bool exact, reform_force, start_reform;
  bool reform_point, stiffness_const;
  double reform_value;
  double reform_cdf_lo, reform_cdf_hi;    // R truncated to |r| < max threshold
  double reform_top;                      // max threshold (effective for unbounded P_c)
  ThermalModel thermal;
  bool thermal_on, thermal_T, aging_on;

  mutable SamplerCounts counts;

  // a new life of a contact with temperature, aging or delays (its budget
  // drawn with its threshold, draw_threshold()): age 0, no bound
  void start_life(double *st, uint32_t off) const;
  // the candidates within a piece of duration h in which the stretch goes
  // linearly from x0 to x1 and the age from a0: true, with the fraction of
  // the piece at which one was accepted, or false (budget used)
  bool thin(double *st, uint64_t tag, double x0, double x1, double a0, double h,
            double &frac) const;
  // a new bound covering at least |s| <= need, with threshold xs now,
  // up to where the rate reaches e^L
  void rebound(double *st, double need, double xs, double L) const;
  // the level L of a new bound made at stretch x, threshold xs, the
  // stretch changing at speed w (see BOUND_CANDIDATES)
  double level(double x, double w, double xs) const;
  // the threshold's lower bound raised to xs (and the rate bound with it)
  void raise_xs_low(double *st, double xs) const;
  // the wait after break `event` of contact `tag` (0: no delay)
  double delay_wait(uint64_t tag, uint64_t event) const;
  // a piece of a step (see advance()): the crossing of the aged threshold,
  // and a thermal break before it
  bool threshold_crossing(const double *st, double s_a, double s_b, double a_a, double h,
                          double &g, double &xs_end) const;
  bool thermal_break(double *st, uint64_t tag, double s_a, double s_b, double a_a, double h,
                     double &g) const;
  // the draws of candidate k of the current life: acceptance uniform, next budget
  void candidate_draw(uint64_t tag, uint64_t life, double k, double &accept, double &next) const;
  // a stretch m (of a waiting contact: its atom's motion) that is not finite
  [[noreturn]] void not_finite(const double *st, uint64_t tag, double m, bool waiting) const;

  double draw_reform(uint64_t tag, uint64_t event, uint32_t stream) const;
  // the threshold above |r| of the life after event `event` (stream
  // STREAM_THRESHOLD + off); with temperature, aging or delays also the
  // life's hazard budget (CT_BUDGET), from the other half of the same block
  double draw_threshold(double *st, uint64_t tag, uint64_t event, uint32_t off, double r) const;
  // new threshold (and stiffness) after event `event`; returns the re-forming stretch r
  double renew(double *st, uint64_t tag, uint64_t event) const;
};

/* ----------------------------------------------------------------------
   avalanche rounds over contacts coupled by an elastic field
------------------------------------------------------------------------- */

// the field as the avalanche reads it, by row index: h_i, K_i = sum_j
// k_ij, and the rows whose h_i changed in the update that produced it
// (changed == nullptr: any row may have changed)
struct AvalancheField {
  const double *h = nullptr;
  const double *k = nullptr;
  const int *changed = nullptr;
  int nchanged = 0;
};

// what the avalanche needs from its surroundings (LAMMPS: MPI, the field
// of pair eq/elastic, the atoms of the group)
class AvalancheHooks {
 public:
  virtual ~AvalancheHooks() = default;
  virtual void global_sum(long *v, int n) = 0;    // v[0..n) over all ranks, in place
  // the field at the start
  virtual AvalancheField field() = 0;
  // contacts list[0..n) changed their stretch by ds[list[m]] at fixed
  // positions: the field after that change.  exact: on every rank every
  // change is at most AVALANCHE_CHANGE_MAX (1 + |new stretch|), so that
  // an incremental update follows it to rounding (false: recompute; the
  // same verdict on all ranks)
  virtual AvalancheField changed(const int *list, int n, const double *ds, bool exact) = 0;
  // contacts list[0..n) detached for good, or broke and wait to re-form
  // (ContactModel::leaves_field()): the field without them, at fixed
  // positions.  exact: on every rank every stretch they left with is at
  // most AVALANCHE_CHANGE_MAX, so that the partners' fields can follow
  // their leaving incrementally (false: recompute; the same on all ranks)
  virtual AvalancheField detached(const int *list, int n, bool exact) = 0;
  virtual uint64_t tag(int i) const = 0;
};

struct AvalancheResult {
  long size = 0;       // breaks (a contact breaking in several rounds counts each time)
  long trigger = 0;    // breaks of the first round
  int rounds = 0;      // rounds with breaks
  long local = 0;      // breaks of the contacts given to this call (this rank)
};

// the contacts are rows[members[m]], m < nmembers (detached ones are
// skipped).  The first round tests them all; a later round tests only the
// rows whose h changed in the last update (those that broke among them),
// when the field names them: the others stay below their thresholds.
// The field names rows of the contacts only (rows[i] and h[i] exist).
// tol: relative tolerance of the breaking test (see tolerance()).  list,
// ds: scratch (ds indexed by row).  thermal (by row, or nullptr): not
// NaN for a contact that broke thermally within the step (ContactModel::
// probe()) where its effective stretch was thermal[i], its new life then
// of age thermal_age[i]: it breaks in the first round, there.  clock: NaN
// for rows in engine form; the time of rows in stored form (thermal rows
// of fix eq/contacts: see to_engine()), which stay in it
AvalancheResult avalanche(const ContactModel &model, double *const *rows, const int *members,
                          int nmembers, double tol, AvalancheHooks &hooks, std::vector<int> &list,
                          std::vector<double> &ds, const double *thermal = nullptr,
                          const double *thermal_age = nullptr, double clock = NAN);

// an avalanche may take at most this many rounds
constexpr int AVALANCHE_MAX_ROUNDS = 100000;
// a change of a stretch by more than this many times the stretch it
// leads to (plus 1) leaves more than rounding in a field updated
// incrementally (a stretch of 1e300 that breaks to 0.3)
constexpr double AVALANCHE_CHANGE_MAX = 1.0e6;
// a change ds of a stretch to s_new that an incremental field follows to rounding
inline bool change_followable(double ds, double s_new)
{
  return std::fabs(ds) <= AVALANCHE_CHANGE_MAX * (1.0 + std::fabs(s_new));
}

}    // namespace feq

#endif
