/* ----------------------------------------------------------------------
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
   FRICTION-EQ package: break engine of the EQ model (see eq_contact.h)
------------------------------------------------------------------------- */

#include "eq_contact.h"
#include "eq_text.h"

#include "eq_random.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace feq {

namespace {
std::string num(double v) { return format_number(v, 10); }

constexpr double LN2 = 0.69314718055994530942;

// e with 2^e <= y < 2^(e+1), y positive and normal
int binary_exponent(double y)
{
  uint64_t bits;
  std::memcpy(&bits, &y, sizeof bits);
  return static_cast<int>((bits >> 52) & 0x7ff) - 1023;
}
}    // namespace

ContactModel::ContactModel(double kc, uint64_t seed_, const DistributionSpec &threshold_,
                           const DistributionSpec &reform_, const DistributionSpec &stiffness_,
                           bool exact_, bool reform_force_, bool start_reform_,
                           const ThermalSpec &thermal_) :
    k0(kc), seed(seed_), threshold(threshold_), reform(reform_), stiffness(stiffness_),
    exact(exact_), reform_force(reform_force_), start_reform(start_reform_), thermal(thermal_),
    thermal_on(thermal_.active()), thermal_T(thermal_.thermal()),
    aging_on(thermal_.active() && thermal_.aging != AgingLaw::NONE && thermal_.beta > 0.0)
{
  if (!threshold.dist) throw SpecError("threshold: missing distribution");
  if (!(k0 > 0.0) || !std::isfinite(k0)) throw SpecError("kc must be finite and > 0");
  if (!stiffness.dist) {
    stiffness.dist = make_delta(1.0);
    stiffness.text = "constant";
  }
  if (start_reform && !reform.dist)
    throw SpecError("start reform needs contacts that re-form (reform none given)");
  check_reform(*threshold.dist, reform);
  reform_point = reform.dist && reform.dist->is_point();
  reform_value = reform.dist ? reform.dist->mean() : 0.0;
  stiffness_const = stiffness.constant();
  // re-forming stretches are drawn from R truncated to |r| < max x_s (a
  // weight below REFORM_BEYOND_TOLERANCE, checked above), so that no draw
  // can abort a run
  reform_top = threshold.dist->effective_upper();
  if (reform.dist) {
    reform_cdf_lo = reform.dist->cdf(-reform_top);
    reform_cdf_hi = reform.dist->cdf(std::nextafter(reform_top, -reform_top));
  } else {
    reform_cdf_lo = 0.0;
    reform_cdf_hi = 1.0;
  }
}

double ContactModel::draw_reform(uint64_t tag, uint64_t event, uint32_t stream) const
{
  if (reform_point) return reform_value;
  const Uniform u = draw(seed, tag, event, stream);
  const double r = reform.dist->sample(u);
  if (std::fabs(r) < reform_top) return r;
  return reform.dist->quantile(reform_cdf_lo + u.u * (reform_cdf_hi - reform_cdf_lo));
}

/* ---------------------------------------------------------------------- */

void ContactModel::form(double *st, uint64_t tag, double xu) const
{
  const bool reentry = st[CS_STIFFNESS] < 0.0;
  const uint64_t event = reentry ? static_cast<uint64_t>(st[CS_NBREAK]) : 0;
  const uint32_t off = reentry ? static_cast<uint32_t>(STREAM_REENTRY) : 0u;
  const double s0 = start_reform ? draw_reform(tag, event, STREAM_REFORM + off) : 0.0;
  const double k = stiffness_const
      ? k0
      : k0 * stiffness.dist->sample(draw(seed, tag, event, STREAM_STIFFNESS + off));
  const double th = draw_threshold(st, tag, event, off, s0);
  if (!(th > 0.0))
    throw BreakError("initial stretch " + num(s0) + " of contact " + std::to_string(tag) +
                     " is not below the largest breaking threshold");
  st[CS_STRETCH] = s0;
  st[CS_THRESHOLD] = th;
  st[CS_FORCE] = k * s0;
  st[CS_NBREAK] = static_cast<double>(event);
  st[CS_STIFFNESS] = k;
  st[CS_ANCHOR] = xu - s0;
  st[CS_FIELD] = 0.0;
  if (thermal_on) start_life(st, off);
}

double ContactModel::draw_threshold(double *st, uint64_t tag, uint64_t event, uint32_t off,
                                    double r) const
{
  const uint32_t stream = STREAM_THRESHOLD + off;
  if (!thermal_on) return threshold.dist->sample_above(std::fabs(r), draw(seed, tag, event, stream));
  // the life's budget from the same Philox block (one block per life):
  // drawn at T = 0 too (never used there), so that a restart at T > 0 finds it
  const UniformPair u = draw_pair(seed, tag, event, stream);
  st[CT_BUDGET] = exponential(u.second);
  return threshold.dist->sample_above(std::fabs(r), u.first);
}

void ContactModel::start_life(double *st, uint32_t off) const
{
  st[CT_AGE] = 0.0;
  st[CT_WAIT] = 0.0;
  st[CT_PENDING] = 0.0;
  st[CT_BOUND_RATE] = 0.0;
  st[CT_BOUND_S] = NO_BOUND;
  st[CT_CANDIDATE] = off ? CANDIDATE_REENTRY : 0.0;
  st[CT_XS_LOW] = st[CS_THRESHOLD];
}

/* ----------------------------------------------------------------------
   the stored form of a thermal row (eq_contact.h).  The budget is counted
   down while a bound with a rate > 0 holds: the engine uses it only there
   (thin()), and every change of the bound or its rate is the engine's, in
   engine form, after which from_engine() sets the run-out time anew
------------------------------------------------------------------------- */

StoredForm to_engine(double *st, double t)
{
  StoredForm w;
  w.t = t;
  w.formed = st[CT_FORMED];
  w.runout = st[CT_RUNOUT];
  w.nbreak = st[CS_NBREAK];
  w.threshold = st[CS_THRESHOLD];
  w.wait = st[CT_WAIT];
  w.candidate = st[CT_CANDIDATE];
  w.rate = st[CT_BOUND_RATE];
  w.bound = st[CT_BOUND_S];
  // a waiting contact is of age 0 until it re-forms (as advance() keeps it)
  w.age = w.wait > 0.0 ? 0.0 : std::max(0.0, t - w.formed);
  w.budget = std::signbit(w.runout) ? -w.runout : std::max(0.0, (w.runout - t) * w.rate);
  st[CT_AGE] = w.age;
  st[CT_BUDGET] = w.budget;
  return w;
}

void from_engine(double *st, double t, const StoredForm &was)
{
  const double age = st[CT_AGE], budget = st[CT_BUDGET];
  const bool waiting = st[CT_WAIT] > 0.0;
  const bool life = st[CS_NBREAK] == was.nbreak && st[CS_THRESHOLD] == was.threshold &&
      waiting == (was.wait > 0.0);
  st[CT_FORMED] = life ? was.formed : waiting ? t + st[CT_WAIT] : t - age;
  if (life && st[CT_CANDIDATE] == was.candidate && st[CT_BOUND_RATE] == was.rate &&
      st[CT_BOUND_S] == was.bound) {
    st[CT_RUNOUT] = was.runout;
    return;
  }
  const double rate = st[CT_BOUND_RATE];
  const double out = st[CT_BOUND_S] >= 0.0 && rate > 0.0 ? t + budget / rate : HUGE_VAL;
  st[CT_RUNOUT] = std::isfinite(out) ? out : -budget;
}

void from_engine(double *st, double t)
{
  StoredForm none;    // NaN differs from every value: everything is set anew
  none.t = none.formed = none.runout = NAN;
  none.nbreak = none.threshold = none.wait = none.candidate = none.rate = none.bound = NAN;
  none.age = none.budget = NAN;
  from_engine(st, t, none);
}

void ContactModel::new_run(double *st) const
{
  // no bound for a contact not attached (quick_attached()), whatever wrote the row
  if (!(st[CS_THRESHOLD] > 0.0) || st[CT_WAIT] > 0.0) st[CT_BOUND_S] = NO_BOUND;
  if (!(st[CS_THRESHOLD] > 0.0)) return;
  // the threshold now, with this run's aging (the same as the writing
  // run's, or the lower bound would be kept to the bit)
  const double xs = st[CS_THRESHOLD] * thermal.factor(st[CT_AGE]);
  if (!(st[CT_XS_LOW] >= st[CS_THRESHOLD] && st[CT_XS_LOW] <= xs * (1.0 + 1e-12)))
    st[CT_XS_LOW] = xs;
  if (!thermal_T) {
    st[CT_BOUND_S] = NO_BOUND;
    st[CT_BOUND_RATE] = 0.0;
  } else if (st[CT_BOUND_S] >= 0.0) {
    // kept where it holds for this run's rate (made with a lower bound of
    // the threshold, it is at least the bound made now), else made anew
    const double bound = thermal.rate_bound(st[CT_BOUND_S], st[CT_XS_LOW]);
    if (!(st[CT_BOUND_RATE] >= bound * (1.0 - 1e-12))) st[CT_BOUND_RATE] = bound;
  }
}

void ContactModel::depart(double *st) const
{
  if (st[CS_THRESHOLD] > 0.0) {
    st[CS_THRESHOLD] = 0.0;
    st[CS_STIFFNESS] = -1.0;    // marks a re-entry for form()
    st[CS_STRETCH] = st[CS_FORCE] = st[CS_FIELD] = 0.0;
    if (thermal_on) st[CT_BOUND_S] = NO_BOUND;    // not attached: no bound (quick_attached())
  }
}

/* ----------------------------------------------------------------------
   event `event` happened: new threshold above |r| (and stiffness);
   returns r (NaN: the contact detached for good)
------------------------------------------------------------------------- */

double ContactModel::renew(double *st, uint64_t tag, uint64_t event) const
{
  st[CS_NBREAK] = static_cast<double>(event);
  if (!reform.dist) {    // never re-forms: detached for good
    st[CS_THRESHOLD] = -1.0;
    st[CS_STIFFNESS] = 0.0;
    st[CS_STRETCH] = st[CS_FORCE] = st[CS_FIELD] = 0.0;
    return NAN;
  }
  const double r = draw_reform(tag, event, STREAM_REFORM);
  if (!stiffness_const)
    st[CS_STIFFNESS] = k0 * stiffness.dist->sample(draw(seed, tag, event, STREAM_STIFFNESS));
  const double th = draw_threshold(st, tag, event, 0u, r);
  if (!(th > 0.0))    // only if the survival function underflows at |r|
    throw BreakError("contact " + std::to_string(tag) + " re-formed with stretch " + num(r) +
                     ", where no breaking threshold of " + threshold.text +
                     " lies above it; check the reform distribution");
  st[CS_THRESHOLD] = th;
  return r;
}

double ContactModel::break_once(double *st, uint64_t tag, double e, double h, double K,
                                double e_break, double age) const
{
  if (!std::isfinite(e))
    throw BreakError("force of contact " + std::to_string(tag) + " is " + num(e * st[CS_STIFFNESS]) +
                     " (numerical instability: check the timestep, the forces, the integrator "
                     "and the pair eq/elastic coefficients" +
                     (reform_force ? std::string(")")
                                   : std::string("; with reform_as stretch a re-formed contact can "
                                                 "carry its partners' force beyond its threshold "
                                                 "and break without end: use reform_as force or "
                                                 "a smaller ftilde)")));
  // (a thermal break: on the side where it broke, as advance(); at e = 0
  // the positive one.  A break at the threshold has |e| >= x_s > 0)
  const bool hot = !std::isnan(e_break) && exact;
  const double sign = (hot && e_break != 0.0 ? e_break : e) >= 0.0 ? 1.0 : -1.0;
  const double over = !exact ? 0.0 : hot ? e - e_break : e - sign * threshold_now(st);
  const double s_old = st[CS_STRETCH];
  const uint64_t event = static_cast<uint64_t>(st[CS_NBREAK]) + 1;
  const double r = renew(st, tag, event);
  if (std::isnan(r)) {
    if (thermal_on) {    // detached for good: no bound (quick_attached())
      st[CT_AGE] = st[CT_WAIT] = st[CT_PENDING] = 0.0;
      st[CT_BOUND_S] = NO_BOUND;
    }
    return 0.0;
  }
  if (thermal_on) {
    start_life(st, 0u);
    if (hot) st[CT_AGE] = age;
  }
  const double wait = leaves_field() ? delay_wait(tag, event) : 0.0;
  if (wait > 0.0) {
    // it leaves the field and waits (a thermal break `age` ago has waited
    // that long: a wait shorter than that ends at the next step's start),
    // its anchor at its atom; rejoin() re-forms it with force k r
    st[CT_WAIT] = hot && exact ? std::max(wait - age, std::numeric_limits<double>::min()) : wait;
    st[CT_PENDING] = sign * r;
    st[CT_AGE] = 0.0;
    st[CS_STRETCH] = st[CS_FORCE] = 0.0;
    st[CS_ANCHOR] += s_old;
    return 0.0;
  }
  const double target = sign * r + over;    // new force / k
  double s_new = target;
  if (reform_force && K != 0.0) {
    const double k = st[CS_STIFFNESS];
    const double m = s_old * K - h;    // sum_j k_ij x_j
    s_new = (k * target + m) / (k + K);
  }
  st[CS_STRETCH] = s_new;
  st[CS_ANCHOR] += s_old - s_new;
  return s_new;
}

/* ----------------------------------------------------------------------
   one step of a contact with temperature, aging or delays.  The step is
   walked in pieces [f, 1] of its duration: an attached piece ends at a
   break (threshold crossing, or an accepted candidate of the thermal
   break process: see thin()) or at the end of the step; a waiting piece ends when the delay is over or at
   the end of the step.  With crossing step every break and every
   re-formation happens at the end of the step.
------------------------------------------------------------------------- */

void ContactModel::not_finite(const double *st, uint64_t tag, double m, bool waiting) const
{
  throw BreakError((waiting ? "motion of the atom of waiting contact " : "stretch of contact ") +
                   std::to_string(tag) + " is " + num(m) + " (threshold " +
                   num(st[CS_THRESHOLD]) +
                   "; numerical instability: check the timestep, the forces and the integrator)");
}

// a piece in which the stretch goes linearly from s_a to s_b and the age
// from a_a to a_a + h: true where |s| reaches the aged threshold within it
// (g: the fraction where; |s| taken linear), else false with xs_end the
// threshold at the end (0 where the lower bound CT_XS_LOW decides)
inline bool ContactModel::threshold_crossing(const double *st, double s_a, double s_b,
                                             double a_a, double h, double &g,
                                             double &xs_end) const
{
  if (std::fabs(s_b) < st[CT_XS_LOW]) return false;
  const double xs0 = st[CS_THRESHOLD];
  const double xs_b = xs0 * thermal.factor(a_a + h);
  const double d_b = std::fabs(s_b) - xs_b;
  if (d_b < 0.0) {
    xs_end = xs_b;
    return false;
  }
  const double d_a = std::fabs(s_a) - xs0 * thermal.factor(a_a);
  g = d_a < 0.0 ? d_a / (d_a - d_b) : 0.0;
  return true;
}

// a thermal break of the piece within its first fraction g (up to the
// crossing): thinning; true with g the fraction of the break
inline bool ContactModel::thermal_break(double *st, uint64_t tag, double s_a, double s_b,
                                        double a_a, double h, double &g) const
{
  if (!(thermal_T && h > 0.0 && g > 0.0)) return false;
  const double x_g = g == 1.0 ? s_b : s_a + (s_b - s_a) * g;
  double g_t = 1.0;
  if (!thin(st, tag, s_a, x_g, a_a, h * g, g_t)) return false;
  g *= g_t;
  return true;
}

ThermalStepResult ContactModel::advance(double *st, uint64_t tag, double m, double dt,
                                        long &nbreaks) const
{
  ThermalStepResult res;
  // an attached contact whose stretch stays below its threshold's lower
  // bound: one piece, the whole step, tested for a thermal break alone
  // (as the loop's first piece); tested: it broke, at the fraction g0
  bool tested = false;
  double g0 = 1.0;
  if (dt > 0.0 && st[CS_THRESHOLD] > 0.0 && !(st[CT_WAIT] > 0.0) &&
      std::fabs(m) < st[CT_XS_LOW]) {
    double g = 1.0;
    if (!thermal_break(st, tag, st[CS_STRETCH], m, st[CT_AGE], dt, g)) {
      st[CT_AGE] += dt;
      hold(st, m);
      res.stretch = m;
      res.attached = true;
      return res;
    }
    tested = true;
    g0 = g;
  }
  const bool waiting0 = st[CT_WAIT] > 0.0;
  if (!std::isfinite(m)) not_finite(st, tag, m, waiting0);
  // motion of the atom per unit fraction of the step, and the stretch at f
  const double motion = waiting0 ? m : m - st[CS_STRETCH];
  double s_a = waiting0 ? 0.0 : st[CS_STRETCH];
  double f = 0.0;
  int nb = 0;
  while (true) {
    if (st[CS_THRESHOLD] < 0.0) return res;    // detached for good
    const double h = (1.0 - f) * dt;
    if (st[CT_WAIT] > 0.0) {    // waiting: re-forms when the delay is over
      // (with crossing step at the end of the first step by which it is
      // over, a delay of a whole number of steps not lengthened by rounding)
      if (st[CT_WAIT] > (exact ? h : h + 1e-9 * dt)) {
        st[CT_WAIT] -= h;
        st[CS_STRETCH] = 0.0;
        return res;
      }
      f = exact ? f + st[CT_WAIT] / dt : 1.0;
      if (!(f < 1.0)) f = 1.0;
      st[CT_WAIT] = 0.0;
      s_a = st[CT_PENDING];
      st[CT_PENDING] = 0.0;
      res.renewed = true;    // a new anchor
      continue;
    }
    // attached over [f, 1]: the stretch goes from s_a to s_b, the age from a_a to a_a + h
    // (the end of a whole step: the stretch m itself)
    const double s_b = (f == 0.0 && !waiting0) ? m : s_a + motion * (1.0 - f);
    const double a_a = st[CT_AGE];
    double g = 1.0;         // fraction of the piece at which it breaks
    double xs_end = 0.0;    // > 0: the threshold at the end, not reached
    bool broke = true;
    if (tested) {    // (the first piece, tested above)
      g = g0;
      tested = false;
    } else {
      broke = threshold_crossing(st, s_a, s_b, a_a, h, g, xs_end);
      // a thermal break first, up to the crossing: thinning
      if (thermal_break(st, tag, s_a, s_b, a_a, h, g)) broke = true;
    }
    if (!broke) {
      st[CT_AGE] = a_a + h;    // (a_a + dt for a whole step, as step())
      hold(st, s_b);
      if (xs_end > 0.0) raise_xs_low(st, xs_end);
      res.stretch = s_b;
      res.attached = true;
      return res;
    }
    // the break, at fraction fb of the step (the end with crossing step)
    const double fb = exact ? std::min(1.0, f + g * (1.0 - f)) : 1.0;
    const double s_break = s_a + motion * (fb - f);
    const double sign = (s_break != 0.0 ? s_break : s_b) >= 0.0 ? 1.0 : -1.0;
    if (++nb > MAX_BREAKS_PER_STEP)
      throw BreakError("contact " + std::to_string(tag) + " broke more than " +
                       std::to_string(MAX_BREAKS_PER_STEP) + " times in one step (stretch " +
                       num(m) + " at the end of the step, threshold " + num(st[CS_THRESHOLD]) +
                       "); reduce the timestep or check the reform and threshold distributions" +
                       (thermal.params().thermal()
                            ? " and the thermal keyword (its attempt frequency omega: breaking "
                              "rate " + num(thermal.rate(0.0, st[CS_THRESHOLD])) +
                              " for an unstretched contact)"
                            : std::string()));
    ++nbreaks;
    res.renewed = true;
    const uint64_t event = static_cast<uint64_t>(st[CS_NBREAK]) + 1;
    const double r = renew(st, tag, event);
    if (std::isnan(r)) {    // detached for good: no bound (quick_attached())
      st[CT_AGE] = st[CT_WAIT] = st[CT_PENDING] = 0.0;
      st[CT_BOUND_S] = NO_BOUND;
      return res;
    }
    start_life(st, 0u);
    const double wait = delay_wait(tag, event);
    f = fb;
    if (wait > 0.0) {
      st[CT_WAIT] = wait;
      st[CT_PENDING] = sign * r;
      st[CS_STRETCH] = 0.0;
    } else {
      s_a = sign * r;
    }
  }
}

// the wait after break `event` (0: no delay)
double ContactModel::delay_wait(uint64_t tag, uint64_t event) const
{
  const ThermalSpec &sp = thermal.params();
  if (sp.delay == DelayKind::FIXED) return sp.tau;
  if (sp.delay == DelayKind::EXPONENTIAL)
    return sp.tau * exponential(draw(seed, tag, event, STREAM_DELAY));
  return 0.0;
}

double ContactModel::rejoin(double *st, double m, double dt) const
{
  // the fraction of the step at which the delay ends, as advance()
  double f = exact && dt > 0.0 ? st[CT_WAIT] / dt : 1.0;
  if (!(f < 1.0)) f = 1.0;
  const double s = st[CT_PENDING] + m * (1.0 - f);
  st[CT_WAIT] = st[CT_PENDING] = 0.0;
  st[CT_AGE] = (1.0 - f) * dt;
  return s;
}

ContactModel::ThermalProbe ContactModel::probe(double *st, uint64_t tag, double e0, double e1,
                                               double dt) const
{
  ThermalProbe res;
  if (!std::isfinite(e1)) not_finite(st, tag, e1, false);
  const double a_a = st[CT_AGE];
  // up to where e crosses the aged threshold (the avalanche breaks it there)
  double g = 1.0, xs_end = 0.0;
  threshold_crossing(st, e0, e1, a_a, dt, g, xs_end);
  if (thermal_break(st, tag, e0, e1, a_a, dt, g)) {
    res.broke = true;
    res.frac = g;
    return res;
  }
  st[CT_AGE] = a_a + dt;
  if (xs_end > 0.0) raise_xs_low(st, xs_end);
  // the bound covers the effective stretch (the next step's start) or is dropped
  if (!(std::fabs(e1) <= st[CT_BOUND_S])) st[CT_BOUND_S] = NO_BOUND;
  return res;
}

/* ----------------------------------------------------------------------
   thinning (Lewis & Shedler 1979): the break process of rate nu(t) is
   the candidate process of rate nu_bar >= nu(t) with each candidate kept
   with probability nu(t)/nu_bar.  The candidates are counted by a budget
   Exp(1) of the bound's hazard (memoryless: the bound may change at any
   time, the budget left goes on); each candidate draws its acceptance
   and the next budget from (seed, tag, life, candidate index).  Exact in
   law for a stretch linear within the step, whatever dt.
------------------------------------------------------------------------- */

void ContactModel::candidate_draw(uint64_t tag, uint64_t life, double k_d, double &accept,
                                  double &next) const
{
  const CandidateDraws d = draw_candidate(seed, tag, life, static_cast<uint64_t>(k_d));
  accept = d.accept;
  next = d.next;
}

void ContactModel::raise_xs_low(double *st, double xs) const
{
  if (xs > st[CT_XS_LOW]) st[CT_XS_LOW] = xs;
}

// the level L of a new bound at stretch x: the band ends where the
// barrier's log rate (the log rate without the prefactor u^q <= 1, which
// increases with |x|: bound_stretch() solves it) has risen by r.  With
// the prefactor in psi (q > 0) the band could end below x near the
// threshold and the bound crept on by 1e-6 (tens of thousands of bounds
// per life at q = 1); rate_bound() covers the prefactor's peak.
double ContactModel::level(double x, double w, double xs) const
{
  double slope = 0.0;
  const double psi = thermal.log_barrier_rate_at(x, xs, slope);
  const double d = thermal.log_omega() - psi;
  if (!(d > 0.5 * BOUND_LOG_STEP)) return HUGE_VAL;
  const double r = bound_rise(BOUND_CANDIDATES * w * slope, psi, d);
  return d - r < 0.5 * BOUND_LOG_STEP ? HUGE_VAL : psi + r;
}

// r e^r = K e^-psi (K = BOUND_CANDIDATES w (d psi/d|x|)): r ~ lk - ln lk,
// lk = ln K - psi, at least BOUND_LOG_STEP and at most the ladder's
// (1 - 1/BOUND_LADDER) d.  The cap decides most bounds (a life's first
// bound, the last below the top); where the exponents of K and of a lower
// bound of lk show lk - ln lk above it (with a margin far beyond the
// rounding of the logs), the logs are skipped: the same r to the bit.
double ContactModel::bound_rise(double k, double psi, double d)
{
  const double cap = d - d / BOUND_LADDER;
  if (cap <= BOUND_LOG_STEP) return cap;    // min(max(step, ...), cap)
  if (std::isnormal(k) && k > 0.0 && k < HUGE_VAL) {
    // ln K >= e ln 2 for K in [2^e, 2^(e+1)); f(y) = y - ln y grows for
    // y > 1, and ln y < (e' + 1) ln 2 for y in [2^e', 2^(e'+1))
    const double y = binary_exponent(k) * LN2 - psi;
    if (std::isnormal(y) && y > 2.0 &&
        y - (binary_exponent(y) + 1) * LN2 >= cap + 1e-9 * (1.0 + std::fabs(cap)))
      return cap;
  }
  const double lk = std::log(k) - psi;
  double r = BOUND_LOG_STEP;
  if (lk > 1.0) r = std::max(r, lk - std::log(lk));
  return std::min(r, cap);
}

void ContactModel::rebound(double *st, double need, double xs, double L) const
{
  ++counts.refreshes;
  raise_xs_low(st, xs);
  const double reach = thermal.bound_stretch(L, st[CT_XS_LOW]);
  st[CT_BOUND_S] = reach == HUGE_VAL ? BOUND_ALL : std::max(need, reach);
  st[CT_BOUND_RATE] = thermal.rate_bound(st[CT_BOUND_S], st[CT_XS_LOW]);
}

bool ContactModel::thin(double *st, uint64_t tag, double x0, double x1, double a0, double h,
                        double &frac) const
{
  const bool aging = thermal.params().aging != AgingLaw::NONE;
  const double xs0 = st[CS_THRESHOLD];
  auto xs_at = [&](double t) { return aging ? xs0 * thermal.factor(a0 + t) : xs0; };
  const double w = std::fabs(x1 - x0) / h;    // speed of the stretch
  if (!(std::fabs(x0) <= st[CT_BOUND_S])) {    // a new life (or a stretch moved while held)
    const double xs = xs_at(0.0);
    rebound(st, std::fabs(x0), xs, level(x0, w, xs));
  }
  double t = 0.0;    // time into the piece
  while (true) {
    // where the path leaves the bound (h: not within the piece)
    const double sb = st[CT_BOUND_S];
    double t_out = h;
    if (!(std::fabs(x1) <= sb)) {
      const double edge = x1 > 0.0 ? sb : -sb;
      t_out = std::min(h, std::max(t, h * ((edge - x0) / (x1 - x0))));
    }
    const double nu_bar = st[CT_BOUND_RATE];
    const double avail = nu_bar * (t_out - t);    // (nu_bar dt for a whole step, as step())
    if (avail < st[CT_BUDGET]) {
      st[CT_BUDGET] -= avail;
      if (t_out == h) return false;
      // a higher bound from where the path left this one
      t = t_out;
      const double xs = xs_at(t);
      rebound(st, sb, xs, level(sb, w, xs));
      if (!(st[CT_BOUND_S] > sb)) {    // (rounding, extreme exponents): some way beyond
        st[CT_BOUND_S] = sb + 1e-6 * (sb + xs);
        st[CT_BOUND_RATE] = thermal.rate_bound(st[CT_BOUND_S], st[CT_XS_LOW]);
      }
      continue;
    }
    t = std::min(t_out, t + st[CT_BUDGET] / nu_bar);    // a candidate
    const double x = x0 + (x1 - x0) * (t / h);
    const double xs = xs_at(t);
    const double nu = thermal.point(x, xs).nu;
    double accept, next;
    candidate_draw(tag, static_cast<uint64_t>(st[CS_NBREAK]), st[CT_CANDIDATE], accept, next);
    st[CT_CANDIDATE] += 1.0;
    ++counts.candidates;
    if (accept * nu_bar < nu) {
      frac = t / h;
      return true;
    }
    // rejected: the next budget, and a bound fitted to the rate here
    st[CT_BUDGET] = next;
    rebound(st, std::fabs(x), xs, level(x, w, xs));
  }
}

/* ----------------------------------------------------------------------
   LAMMPS keeps the image count in IMGBITS bits: after IMGMAX periodic
   crossings it wraps, and the unwrapped coordinate jumps by 2 IMGMAX box
   lengths.  No stretch can be that large: the caller undoes the jump
   (EQUtil::Unwrap::stretch() in eq_lammps_util) before calling resolve().
------------------------------------------------------------------------- */

double ContactModel::resolve(double *st, uint64_t tag, double s, double tol, long &nbreaks) const
{
  int nb = 0;
  const double s_step = s;
  while (!(std::fabs(s) < st[CS_THRESHOLD] - tol)) {
    if (!std::isfinite(s))
      throw BreakError("stretch of contact " + std::to_string(tag) + " is " + num(s) +
                       " (numerical instability: check the timestep, the forces and the "
                       "integrator)");
    if (++nb > MAX_BREAKS_PER_STEP)
      throw BreakError("contact " + std::to_string(tag) + " broke more than " +
                       std::to_string(MAX_BREAKS_PER_STEP) + " times in one step (stretch " +
                       num(s_step) + " at the end of the step, " + num(s) + " after " +
                       std::to_string(MAX_BREAKS_PER_STEP) + " breaks, threshold " +
                       num(st[CS_THRESHOLD]) + "); reduce the timestep or check the reform and "
                       "threshold distributions");
    const double sign = s > 0.0 ? 1.0 : -1.0;
    const double over = exact ? s - sign * st[CS_THRESHOLD] : 0.0;
    ++nbreaks;
    const double r = renew(st, tag, static_cast<uint64_t>(st[CS_NBREAK]) + 1);
    if (std::isnan(r)) return 0.0;
    s = sign * r + over;
  }
  return s;
}

/* ---------------------------------------------------------------------- */

namespace {
// over its threshold in the field h (the breaking test of every round);
// clock: NaN for a row in engine form, else the time of a stored row
inline bool over(const ContactModel &model, const double *st, double h, double tol, double clock)
{
  const double th0 = st[CS_THRESHOLD];
  if (th0 <= 0.0 || model.waiting(st)) return false;
  // below x_s0, below the aged threshold too (no A(age) to evaluate)
  if (std::fabs(st[CS_STRETCH] + h / st[CS_STIFFNESS]) < th0 - ContactModel::tolerance(st, tol))
    return false;
  const double th =
      std::isnan(clock) ? model.threshold_now(st) : model.threshold_stored(st, clock);
  const double e = st[CS_STRETCH] + h / st[CS_STIFFNESS];
  return !(std::fabs(e) < th - ContactModel::tolerance(st, tol));
}

// over() for a model without temperature or aging (no waiting, x_s =
// x_s0) and tol = 0: the same test to the bit, without the loads and
// branches of the general one (the test of every member in a round's
// first pass, and of every partner of a break after it)
inline bool over_plain(const double *st, double h)
{
  const double th0 = st[CS_THRESHOLD];
  if (th0 <= 0.0) return false;
  return !(std::fabs(st[CS_STRETCH] + h / st[CS_STIFFNESS]) < th0);
}

template <bool PLAIN>
inline bool over_as(const ContactModel &model, const double *st, double h, double tol,
                    double clock)
{
  return PLAIN ? over_plain(st, h) : over(model, st, h, tol, clock);
}

// the contacts over their thresholds at the start of a round, in the
// order of their rows: among every member, or among the rows whose h
// changed (tested as named, the few found sorted)
template <bool PLAIN>
void candidates_as(const ContactModel &model, const double *const *rows, const int *members,
                   int nmembers, double tol, const AvalancheField &f, bool all,
                   const double *thermal, double clock, std::vector<int> &list)
{
  list.clear();
  if (all || !f.changed) {
    for (int m = 0; m < nmembers; ++m) {
      const int i = members[m];
      if ((!PLAIN && thermal && !std::isnan(thermal[i])) ||
          over_as<PLAIN>(model, rows[i], f.h[i], tol, clock))
        list.push_back(i);
    }
    return;
  }
  for (int m = 0; m < f.nchanged; ++m) {
    const int i = f.changed[m];
    if (over_as<PLAIN>(model, rows[i], f.h[i], tol, clock)) list.push_back(i);
  }
  std::sort(list.begin(), list.end());
  list.erase(std::unique(list.begin(), list.end()), list.end());
}

void candidates(const ContactModel &model, const double *const *rows, const int *members,
                int nmembers, double tol, const AvalancheField &f, bool all, const double *thermal,
                double clock, std::vector<int> &list)
{
  if (tol == 0.0 && !model.thermal_active() && !thermal)
    candidates_as<true>(model, rows, members, nmembers, tol, f, all, nullptr, clock, list);
  else
    candidates_as<false>(model, rows, members, nmembers, tol, f, all, thermal, clock, list);
}
}    // namespace

AvalancheResult avalanche(const ContactModel &model, double *const *rows, const int *members,
                          int nmembers, double tol, AvalancheHooks &hooks, std::vector<int> &list,
                          std::vector<double> &ds, const double *thermal, const double *thermal_age,
                          double clock)
{
  const bool stored = !std::isnan(clock) && model.thermal_active();
  AvalancheResult res;
  list.reserve(nmembers);
  AvalancheField f = hooks.field();
  while (true) {
    // the contacts over their thresholds at the start of the round: in
    // the order of their rows, whichever candidates were tested
    // (the thermal breaks of the step in the first round only)
    const double *hot = res.rounds == 0 ? thermal : nullptr;
    candidates(model, rows, members, nmembers, tol, f, res.rounds == 0, hot,
               stored ? clock : NAN, list);
    // their breaks (this rank's own contacts: nothing global yet), and
    // whether an incremental field can follow them; then the round's
    // counts over all ranks, in one reduction
    const int top = list.empty() ? -1 : *std::max_element(list.begin(), list.end());
    if (static_cast<int>(ds.size()) <= top) ds.resize(top + 1);
    // (with a model whose breaks leave the field, a contact that does not
    // leave, re-formed at once after a wait that rounded to 0, is a
    // change the field cannot follow as a leave: counted with those)
    const bool leave = !model.reforms() || model.leaves_field();
    long sums[2] = {static_cast<long>(list.size()), 0};
    for (const int i : list) {
      double *st = rows[i];
      const double h = f.h[i];
      const double e = st[CS_STRETCH] + h / st[CS_STIFFNESS];
      const double s_old = st[CS_STRETCH];
      const bool th = hot && !std::isnan(hot[i]);
      const auto once = [&] {
        return model.break_once(st, hooks.tag(i), e, h, f.k[i], th ? hot[i] : NAN,
                                th ? thermal_age[i] : 0.0);
      };
      ds[i] = (stored ? engine_call(st, clock, clock, once) : once()) - s_old;
      if (!change_followable(ds[i], st[CS_STRETCH])) ++sums[1];
      if (leave && st[CS_THRESHOLD] > 0.0 && !model.waiting(st)) ++sums[1];
    }
    hooks.global_sum(sums, 2);
    const long all = sums[0];
    if (all == 0) break;
    if (++res.rounds > AVALANCHE_MAX_ROUNDS)
      throw BreakError("avalanche did not stop after " + std::to_string(AVALANCHE_MAX_ROUNDS) +
                       " rounds (" + std::to_string(res.size) +
                       " breaks); the interaction is too strong for the contacts (check the pair "
                       "eq/elastic coefficients against k_i" +
                       (model.reform_as_force()
                            ? std::string(")")
                            : std::string("; with reform_as stretch use reform_as force or a "
                                          "smaller ftilde)")));
    if (res.rounds == 1) res.trigger = all;
    res.size += all;
    res.local += static_cast<long>(list.size());
    if (leave) f = hooks.detached(list.data(), static_cast<int>(list.size()), sums[1] == 0);
    else f = hooks.changed(list.data(), static_cast<int>(list.size()), ds.data(), sums[1] == 0);
  }
  return res;
}

}    // namespace feq
