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
   FRICTION-EQ package: far-zone block at T > 0 (see eq_meso_thermal.h)
------------------------------------------------------------------------- */

#include "eq_meso_thermal.h"
#include "eq_text.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace feq {

namespace {

const double TAIL = 1e-17;      // P_c cut at these quantiles (as MesoModel)
const double EMPTY = 1e-20;     // what is left of a (row, panel) below this breaks
const double SPLIT_SLACK = 1e-9;    // relative excess of du a sub-step may have

enum Slot { TAG, XPOS, JLO, JHI, RATE, DET, MASS, STRETCH, NHEAD };
// after the rows, with an exponential delay only: the waiting mass
enum PoolSlot { WAIT, NPOOL };
// after the rows, with a fixed delay only: a ring of MESO_DELAY_BINS bins
// (start, end, mass: due uniformly over [start, end] from now), oldest
// first from HEAD, COUNT of them in flight
enum FifoSlot { FHEAD, FCOUNT, NFIFO };

std::string fmt(double v) { return format_number(v, 6); }

}    // namespace

ThermalMesoModel::ThermalMesoModel(DistributionPtr Pc_, DistributionPtr R_, double du_,
                                   const ThermalSpec &spec_, int nlabels, Crossing crossing_,
                                   MEStart start_) :
    Pc(std::move(Pc_)), R(std::move(R_)), du(du_), inv_du(1.0 / du_), spec(spec_),
    nlabels_req(nlabels), crossing(crossing_), start(start_), law(spec_)
{
  if (!Pc) throw SpecError("threshold: missing threshold distribution");
  if (!(Pc->lower() >= 0.0))
    throw SpecError("threshold " + Pc->describe() + ": breaking thresholds must be >= 0");
  if (R && !(R->is_point() && R->mean() == 0.0))
    throw SpecError("reform " + R->describe() + ": with the thermal kernel (thermal at T > 0, aging or "
                    "delay), contacts re-form unstretched "
                    "(reform delta 0) or never (reform none)");
  if (start == MEStart::REFORM && !R)
    throw SpecError("start: 'reform' needs a reform distribution (reform none given); allowed: "
                    "relaxed");
  if (spec.aging != AgingLaw::NONE &&
      !(spec.beta >= 0.0 && std::isfinite(spec.beta) && spec.tau_a > 0.0 && std::isfinite(spec.tau_a)))
    throw SpecError("aging: need a finite beta >= 0 and a finite tau_a > 0 (got beta " +
                    fmt(spec.beta) + ", tau_a " + fmt(spec.tau_a) + ")");
  if (!(spec.rest >= 0.0) || !std::isfinite(spec.rest))
    throw SpecError("rest: t_w must be finite and >= 0 (got " + fmt(spec.rest) + ")");
  aging = spec.aging != AgingLaw::NONE && spec.beta > 0.0;
  // the ring holds thresholds up to ytop A(MESO_AGING_RING tau_a) (log;
  // exp: its bound): the width depends on neither rest nor tau_a
  if (aging && spec.aging == AgingLaw::LOG && spec.rest > MESO_AGING_RING * spec.tau_a)
    throw SpecError("rest: t_w = " + fmt(spec.rest) + " is more than " + fmt(MESO_AGING_RING) +
                    " tau_a (tau_a = " + fmt(spec.tau_a) + "), the oldest contacts a block's "
                    "anchors hold with aging log; use a larger tau_a or a shorter rest");
  if (aging)
    aring = 1.0 + spec.beta * (spec.aging == AgingLaw::EXP ? 1.0 : std::log1p(MESO_AGING_RING));
  if (!(spec.tau >= 0.0) || !std::isfinite(spec.tau))
    throw SpecError("delay: tau must be finite and >= 0 (got " + fmt(spec.tau) + ")");
  if (spec.tau > 0.0) delay = spec.delay;
  if (delay != DelayKind::NONE && !R)
    throw SpecError("delay: needs re-forming contacts (reform delta 0), not reform none");
  if (!(spec.theta >= 0.0) || !(spec.omega > 0.0) || !std::isfinite(spec.omega) ||
      !(spec.xc > 0.0))
    throw SpecError("thermal: need theta >= 0, a finite omega > 0 and x_c > 0");
  if (!(nlabels >= 1)) throw SpecError("labels: the number of panels must be >= 1");
  if (!(du > 0.0) || !std::isfinite(du))
    throw GridError("grid: spacing must be a finite number > 0 (got " + fmt(du) + ")");
  set_panels();
  const double sd = std::sqrt(std::max(0.0, Pc->variance()));
  const double dmax = Pc->is_point() ? 0.25 * Pc->mean() : MesoModel::max_grid(*Pc);
  if (!(dmax > 0.0)) throw GridError("grid: thresholds of zero width at 0");
  if (du > dmax)
    throw GridError("grid: spacing " + fmt(du) + " is too coarse for threshold " + Pc->describe() +
                    " (sd " + fmt(sd) + "); the largest allowed value is " + fmt(dmax));
  const double rows = 2.0 * std::ceil(ytop * aring * inv_du) + 8.0;
  const int nextra = extra_width(), per_row = nl + 1 + (aging ? 1 : 0);
  if (!(NHEAD + rows * per_row + nextra <= MESO_MAX_WIDTH))
    throw GridError("grid: spacing " + fmt(du) + " needs about " +
                    fmt(NHEAD + rows * per_row + nextra) + " doubles per block with " +
                    std::to_string(nl) + " threshold panels" +
                    (aging ? " and thresholds aged up to " + fmt(aring) + " times" : "") +
                    " (limit " + std::to_string(MESO_MAX_WIDTH) + "); use a spacing >= " +
                    fmt(min_grid()) + " or fewer labels");
  ncap = int(rows);
  ages = NHEAD + ncap * (nl + 1);
  pool = ages + (aging ? ncap : 0);
  nwidth = pool + nextra;
  if (!Pc->is_point()) {
    eps_acc = std::max(0.0, 0.25 * sd * inv_du - 1.0);
    eps_max = std::max(0.0, Pc->quantile(0.5) * inv_du - 1.0);
  }
  tag = 9.0e9 + double(nwidth) + 1e-3 * double(nl);
}

// nl equal panels of the support of P_c (cut at TAIL), weights the panel
// probabilities; one panel for a point P_c
void ThermalMesoModel::set_panels()
{
  double lo = Pc->lower(), hi = Pc->upper();
  if (Pc->is_point() || !(hi > lo)) {
    nl = 1;
    pa = pb = {Pc->mean()};
    pw = {1.0};
  } else {
    lo = std::max({lo, 0.0, Pc->quantile(TAIL)});
    hi = std::min(hi, Pc->isf(TAIL));
    nl = nlabels_req;
    pa.resize(nl);
    pb.resize(nl);
    pw.resize(nl);
    double sum = 0.0;
    for (int l = 0; l < nl; ++l) {
      pa[l] = lo + (hi - lo) * l / nl;
      pb[l] = l + 1 == nl ? hi : lo + (hi - lo) * (l + 1) / nl;
      pw[l] = std::max(0.0, Pc->cdf(pb[l]) - (l == 0 ? 0.0 : Pc->cdf(pa[l])));
      sum += pw[l];
    }
    for (double &w : pw) w /= sum;
  }
  ytop = pb.back();
  coef0.resize(nl);
  invx0.resize(nl);
  for (int l = 0; l < nl; ++l) {
    const double xm = 0.5 * (pa[l] + pb[l]);
    invx0[l] = 1.0 / xm;
    coef0[l] = spec.theta > 0.0 ? std::pow(xm / spec.xc, spec.p) / spec.theta : 0.0;
  }
}

// doubles after the rows: the waiting pool or the FIFO of a fixed delay
int ThermalMesoModel::extra_width() const
{
  switch (delay) {
    case DelayKind::EXPONENTIAL: return NPOOL;
    case DelayKind::FIXED: return NFIFO + 3 * MESO_DELAY_BINS;
    default: return 0;
  }
}

double ThermalMesoModel::min_grid() const
{
  const int per_row = nl + 1 + (aging ? 1 : 0);
  const double room = MESO_MAX_WIDTH - NHEAD - extra_width() - 10.0 * per_row;
  return room > 0.0 ? 2.0 * ytop * aring * per_row / room : HUGE_VAL;
}

std::unique_ptr<BlockModel> ThermalMesoModel::regrid(double du_new) const
{
  return std::unique_ptr<BlockModel>(
      new ThermalMesoModel(Pc, R, du_new, spec, nlabels_req, crossing, start));
}

double *ThermalMesoModel::row(double *s, long j) const
{
  long k = j % ncap;
  if (k < 0) k += ncap;
  return s + NHEAD + k * (nl + 1);
}

const double *ThermalMesoModel::row(const double *s, long j) const
{
  return row(const_cast<double *>(s), j);
}

// the mean age of row j's contacts (aging only)
double &ThermalMesoModel::age(double *s, long j) const
{
  long k = j % ncap;
  if (k < 0) k += ncap;
  return s[ages + k];
}

/* ---------------------------------------------------------------------- */

void ThermalMesoModel::init(double *s, double X0) const
{
  std::memset(s, 0, nwidth * sizeof(double));
  s[TAG] = tag;
  s[XPOS] = X0;
  const double f = X0 * inv_du;
  const long j = static_cast<long>(std::floor(f));
  s[JLO] = s[JHI] = double(j);
  const double t = f - double(j);
  double *r = row(s, j);
  for (int l = 0; l < nl; ++l) r[1 + l] = (1.0 - t) * pw[l];
  if (aging) age(s, j) = age(s, j + 1) = spec.rest;
  if (t > 0.0) {
    s[JHI] = double(j + 1);
    r = row(s, j + 1);
    for (int l = 0; l < nl; ++l) r[1 + l] = t * pw[l];
  }
  totals(s);
}

// nu at effective stretch y of a panel with midpoint threshold 1/inv_xm
double ThermalMesoModel::rate_at(double y, double inv_xm, double coef) const
{
  const double w = 1.0 - y * inv_xm;
  if (!(w > 0.0)) return spec.q > 0.0 ? 0.0 : spec.omega;
  double nu = spec.omega * std::exp(-coef * w * std::sqrt(w));
  if (spec.q != 0.0) nu *= std::pow(w, spec.q);
  return nu;
}

// the barrier's coefficient (x_s/x_c)^p/theta at threshold xs
double ThermalMesoModel::coef_at(double xs) const
{
  return (spec.p == 0.0 ? 1.0 : std::pow(xs / spec.xc, spec.p)) / spec.theta;
}

namespace {

// the fraction of a sub-step at which z, piecewise linear through z0, zm,
// z1 at its start, middle and end, first reaches x (0 when z0 >= x)
double crossing_fraction(double x, double z0, double zm, double z1)
{
  if (!(x > z0)) return 0.0;
  if (zm >= x) return 0.5 * (x - z0) / (zm - z0);
  if (z1 > zm) return 0.5 + 0.5 * std::min(1.0, (x - zm) / (z1 - zm));
  return 1.0;
}

}    // namespace

// one sub-step X0 -> X1 (|X1 - X0| <= du) over the time h: the thermal
// breaks, then the threshold crossings; D, MX: broken mass and its first
// moment of the break positions; DT: its first moment of the break times
// from the sub-step's start (crossings when X passes them, those of an
// eps jump at 0, thermal breaks at their Simpson-weighted mean time).
// Aging: a row's contacts (mean age a at the start) have the thresholds
// x_s0 A(t); its history r[0] is the largest y/A(t) seen (the labels x_s0
// left lie above it), the ratio taken at the start, middle and end.
void ThermalMesoModel::substep(double *s, double X0, double X1, double eps, double h, double &D,
                               double &MX, double &DT) const
{
  const double g = 1.0 + eps, Xm = 0.5 * (X0 + X1);
  const double dX = X1 - X0;
  // the time at which X passes pos (at rest: the start)
  auto when = [&](double pos) {
    return dX == 0.0 ? 0.0 : h * std::min(1.0, std::max(0.0, (pos - X0) / dX));
  };
  const double Xlo = std::min(X0, X1), Xhi = std::max(X0, X1);
  const bool thermal = spec.theta > 0.0 && h > 0.0;
  const long jlo = long(s[JLO]), jhi = long(s[JHI]);
  for (long j = jlo; j <= jhi; ++j) {
    double *r = row(s, j);
    const double A = double(j) * du;
    // the threshold factors at the start, middle and end (1 without aging)
    double f0 = 1.0, fm = 1.0, f1 = 1.0;
    if (aging) {
      const double a = age(s, j);
      f0 = law.factor(a);
      fm = law.factor(a + 0.5 * h);
      f1 = law.factor(a + h);
    }
    if (std::min(X0, X1) - A <= -ytop * f1) {    // compressed beyond every threshold
      const double pos = std::min(Xhi, std::max(Xlo, A - ytop * f1)), tp = when(pos);
      for (int l = 0; l < nl; ++l) {
        D += r[1 + l];
        MX += r[1 + l] * pos;
        DT += r[1 + l] * tp;
        r[1 + l] = 0.0;
      }
      continue;
    }
    // one-sided: a compressed contact is loaded as an unstretched one
    const double d0 = std::max(X0 - A, 0.0), d1 = std::max(X1 - A, 0.0);
    const double y0 = g * d0, y1 = g * d1, ym = g * std::max(Xm - A, 0.0);
    const double yj = r[0];    // the thresholds (labels) left lie above y_j
    if (thermal) {
      for (int l = 0; l < nl; ++l) {
        const double m = r[1 + l];
        if (!(m > 0.0)) continue;
        double inv = invx0[l], coef = coef0[l];
        if (yj > pa[l]) {    // partly crossed: the midpoint of what is left
          const double xm = 0.5 * (std::min(yj, pb[l]) + pb[l]);
          inv = 1.0 / xm;
          coef = coef_at(xm);
        }
        double n0, nm, n1;
        if (!aging) {
          n0 = rate_at(y0, inv, coef);
          nm = rate_at(ym, inv, coef);
          n1 = rate_at(y1, inv, coef);
        } else {    // the threshold x_m A(t) at the three times
          const double xm = 1.0 / inv;
          n0 = rate_at(y0, inv / f0, coef_at(xm * f0));
          nm = rate_at(ym, inv / fm, coef_at(xm * fm));
          n1 = rate_at(y1, inv / f1, coef_at(xm * f1));
        }
        const double sum = n0 + 4.0 * nm + n1;
        if (!(sum > 0.0)) continue;
        double b = -m * std::expm1(-h / 6.0 * sum);
        if (m - b < EMPTY) b = m;
        r[1 + l] = b == m ? 0.0 : m - b;
        D += b;
        MX += b * ((n0 * X0 + 4.0 * nm * Xm + n1 * X1) / sum);
        DT += b * (h * ((2.0 * nm + n1) / sum));
      }
    }
    // the history: y (aging: y/A) at the start, middle and end
    const double z0 = y0 / f0, zm = ym / fm, z1 = y1 / f1;
    const double ynew = aging ? std::max({z0, zm, z1}) : g * std::max(d0, d1);
    if (!(ynew > yj)) continue;
    const bool at_start = d0 > d1;    // eps grew: crossed at X0
    for (int l = 0; l < nl; ++l) {
      const double m = r[1 + l];
      if (!(m > 0.0)) continue;
      const double lb = std::max(pa[l], yj);
      double b, xb;
      if (ynew >= pb[l]) {
        b = m;
        xb = 0.5 * (lb + pb[l]);
      } else if (ynew > lb) {
        b = m * ((ynew - lb) / (pb[l] - lb));
        xb = 0.5 * (lb + ynew);
      } else {
        continue;
      }
      double pos, tb;
      if (aging) {    // where the history passes xb (linear between the three points)
        const double c = crossing_fraction(xb, z0, zm, z1);
        pos = X0 + dX * c;
        tb = h * c;
      } else {
        pos = at_start ? X0 : std::min(Xhi, std::max(Xlo, A + xb / g));
        tb = at_start ? 0.0 : when(pos);
      }
      r[1 + l] = b == m ? 0.0 : m - b;
      D += b;
      MX += b * pos;
      DT += b * tb;
    }
    r[0] = ynew;
  }
}

// mean of t in [0, L] under the density ~ exp(-t/tau) (the mean time at
// which the mass re-forming within a time L does so)
double ThermalMesoModel::mean_wait(double L) const
{
  const double x = L / spec.tau;
  if (x < 1e-4) return L * (0.5 - x / 12.0);    // next term L x^3/720: below 1e-16 L
  return spec.tau - L / std::expm1(x);
}

// exponential delay over a sub-step X0 -> X1 of time h: the waiting mass
// re-forms at the rate 1/tau, exactly over h; the mass D broken in the
// sub-step joins the pool at the mean time of its breaks (DT/D; crossing
// step: at the end) and the part of it that re-forms within the
// sub-step does so from then on.  On return D, MX are the mass re-forming
// in the sub-step and the first moment of its positions (X at the mean
// re-forming times: X is linear in time), MT that of its times.
void ThermalMesoModel::wait(double *s, double X0, double X1, double h, double &D, double &MX,
                            double &MT, double DT) const
{
  const double W = s[pool + WAIT], dX = X1 - X0;
  const double tb = break_time(h, D, DT);
  const double aW = -W * std::expm1(-h / spec.tau);
  const double aD = -D * std::expm1(-(h - tb) / spec.tau);
  s[pool + WAIT] = (W - aW) + (D - aD);
  const double inv_h = h > 0.0 ? 1.0 / h : 0.0;
  const double tW = mean_wait(h), tD = tb + mean_wait(h - tb);
  const double xW = X0 + dX * (tW * inv_h);
  const double xD = X0 + dX * (tD * inv_h);
  D = aW + aD;
  MX = aW * xW + aD * xD;
  MT = aW * tW + aD * tD;
}

// the mean time, from the sub-step's start, of the breaks of mass D with
// first moment DT of their times in a sub-step of time h (crossing step:
// at the end)
double ThermalMesoModel::break_time(double h, double D, double DT) const
{
  if (crossing == Crossing::STEP) return h;
  if (!(D > 0.0)) return 0.5 * h;
  return std::min(h, std::max(0.0, DT / D));
}

// fixed delay over a sub-step X0 -> X1 of time h: the mass D broken in it
// is due tau later, spread uniformly over [tau + t_b - w, tau + t_b + w]
// (t_b = DT/D the mean time of its breaks, w = min(t_b, h - t_b): within
// the sub-step's window shifted by tau, the mean exact); one bin per
// sub-step (std::runtime_error when MESO_DELAY_BINS are in flight).  Each
// bin re-forms the part of it due within the
// sub-step, at X at the middle of that part (X linear in time); the rest
// stays uniform over what is left of its window.  On return D, MX, MT as
// wait().  Bin: (start, end, mass), times from the sub-step's start.
void ThermalMesoModel::fifo(double *s, double X0, double X1, double h, double &D, double &MX,
                            double &MT, double DT, long nsub) const
{
  double *q = s + pool;
  long head = long(q[FHEAD]), count = long(q[FCOUNT]);
  auto bin = [&](long k) { return q + NFIFO + 3 * ((head + k) % MESO_DELAY_BINS); };
  if (D > 0.0) {
    const double tb = break_time(h, D, DT), w = std::max(0.0, std::min(tb, h - tb));
    if (count == MESO_DELAY_BINS)
      throw std::runtime_error(
          "delay fixed: tau = " + fmt(spec.tau) + " needs more than " +
          std::to_string(MESO_DELAY_BINS) + " bins of broken contacts in flight, the most a " +
          "block holds (one per sub-step of the grid du = " + fmt(du) + ": a step moving the "
          "block by n > 1 du holds n; this step moved it " + std::to_string(nsub) +
          " du in sub-steps of time " + fmt(h) + ", tau = " + fmt(spec.tau / h) +
          " of them); the bins in flight are about max(tau/dt, |v| tau/du): use a larger "
          "timestep or a larger grid, a shorter delay, or delay exp");
    double *b = bin(count++);
    b[0] = spec.tau + tb - w;
    b[1] = spec.tau + tb + w;
    b[2] = D;
  }
  const double dX = X1 - X0, inv_h = h > 0.0 ? 1.0 / h : 0.0;
  double Dr = 0.0, MXr = 0.0, MTr = 0.0;
  for (long k = 0; k < count; ++k) {
    double *b = bin(k);
    if (!(b[0] < h || b[1] <= h)) break;    // the windows are in order
    const double a = std::max(b[0], 0.0), e = b[1];
    const bool all = e <= h;
    const double part = all ? b[2] : b[2] * ((h - a) / (e - a));
    const double tm = 0.5 * (a + std::min(e, h));
    Dr += part;
    MXr += part * (X0 + dX * (tm * inv_h));
    MTr += part * tm;
    b[2] = all ? 0.0 : b[2] - part;
    b[0] = h;
  }
  while (count > 0 && bin(0)[2] == 0.0) {
    head = (head + 1) % MESO_DELAY_BINS;
    --count;
  }
  for (long k = 0; k < count; ++k) {
    bin(k)[0] -= h;
    bin(k)[1] -= h;
  }
  q[FHEAD] = double(head);
  q[FCOUNT] = double(count);
  D = Dr;
  MX = MXr;
  MT = MTr;
}

// every row's contacts grow older by h (aging)
void ThermalMesoModel::grow_old(double *s, double h) const
{
  for (long j = long(s[JLO]); j <= long(s[JHI]); ++j) age(s, j) += h;
}

// the mass D broken in a sub-step re-forms unstretched at its mean break
// position (crossing step: at X1), hat weights on the anchor nodes;
// aging: a row's age becomes the mass-weighted mean of its contacts' and
// the fresh ones' age_new
void ThermalMesoModel::reform(double *s, double X0, double X1, double D, double MX,
                              double age_new) const
{
  if (!(D > 0.0)) return;
  if (!R) {
    s[DET] += D;
    return;
  }
  double a = crossing == Crossing::STEP ? X1 : MX / D;
  a = std::min(std::max(X0, X1), std::max(std::min(X0, X1), a));
  const double f = a * inv_du;
  const long j = static_cast<long>(std::floor(f));
  const double t = f - double(j);
  long lo = long(s[JLO]), hi = long(s[JHI]);
  if (lo > hi) {    // empty (every contact waiting in a delay): nothing to keep
    lo = j;
    hi = j - 1;
  }
  const long want_lo = std::min(lo, j), want_hi = std::max(hi, t > 0.0 ? j + 1 : j);
  if (want_hi - want_lo + 1 > ncap) {
    if (aging)    // contacts older than the ring allows for (log aging)
      throw std::runtime_error(
          "aging: contacts older than " + fmt(MESO_AGING_RING) + " tau_a survive over " +
          fmt(double(want_hi - want_lo) * du) + " of anchors, more than the block's ring holds "
          "(thresholds up to " + fmt(ytop * aring) + ", aged by A(" + fmt(MESO_AGING_RING) +
          " tau_a) = " + fmt(aring) + "); use a larger tau_a");
    throw std::logic_error("eq/meso thermal: anchor ring overflow (" +
                           std::to_string(want_hi - want_lo + 1) + " rows > " +
                           std::to_string(ncap) + ")");
  }
  for (long k = want_lo; k < lo; ++k) std::memset(row(s, k), 0, (nl + 1) * sizeof(double));
  for (long k = hi + 1; k <= want_hi; ++k) std::memset(row(s, k), 0, (nl + 1) * sizeof(double));
  s[JLO] = double(want_lo);
  s[JHI] = double(want_hi);
  add_fresh(s, j, D * (1.0 - t), age_new);
  if (t > 0.0) add_fresh(s, j + 1, D * t, age_new);
}

// mass m of fresh contacts (age age_new) onto row j, by panels
void ThermalMesoModel::add_fresh(double *s, long j, double m, double age_new) const
{
  double *r = row(s, j);
  if (aging) {
    double old = 0.0;
    for (int l = 0; l < nl; ++l) old += r[1 + l];
    double &a = age(s, j);
    a = old > 0.0 ? (old * a + m * age_new) / (old + m) : age_new;
  }
  for (int l = 0; l < nl; ++l) r[1 + l] += m * pw[l];
}

// drop the empty rows at both ends of the occupied range
void ThermalMesoModel::trim(double *s) const
{
  long lo = long(s[JLO]), hi = long(s[JHI]);
  auto empty = [&](long j) {
    const double *r = row(s, j);
    for (int l = 0; l < nl; ++l)
      if (r[1 + l] != 0.0) return false;
    return true;
  };
  while (lo <= hi && empty(lo)) ++lo;
  while (hi >= lo && empty(hi)) --hi;
  s[JLO] = double(lo);
  s[JHI] = double(hi);
}

// attached mass and mean stretch from the rows (ascending j: the same sums
// wherever the state is)
void ThermalMesoModel::totals(double *s) const
{
  const double X = s[XPOS];
  double mass = 0.0, str = 0.0;
  for (long j = long(s[JLO]); j <= long(s[JHI]); ++j) {
    const double *r = row(s, j);
    double m = 0.0;
    for (int l = 0; l < nl; ++l) m += r[1 + l];
    mass += m;
    str += m * (X - double(j) * du);
  }
  s[MASS] = mass;
  s[STRETCH] = str;
}

double ThermalMesoModel::advance(double *s, double X1, double eps, double h) const
{
  if (!std::isfinite(X1)) throw std::invalid_argument("non-finite block displacement " + fmt(X1));
  if (!(eps >= 0.0) || !std::isfinite(eps))
    throw std::invalid_argument("screening eps must be finite and >= 0 (got " + fmt(eps) + ")");
  if (!(h >= 0.0) || !std::isfinite(h))
    throw std::invalid_argument("time step must be finite and >= 0 (got " + fmt(h) + ")");
  // beyond 4e15 cells the anchor index loses integer precision (as MesoModel)
  if (std::fabs(X1) * inv_du > 4e15)
    throw std::invalid_argument("block displacement " + fmt(X1) +
                                " is too large for the anchor grid " + fmt(du));
  if (eps > eps_max)
    throw GridError("grid: the load factor eps = " + fmt(eps) + " makes the effective grid (1 + eps) du = " +
                    fmt((1.0 + eps) * du) + " coarser than the median threshold " +
                    fmt(Pc->quantile(0.5)) +
                    ": the screened thresholds x_s/(1 + eps) are not resolved (fresh contacts "
                    "would inherit the history of older ones); use grid " +
                    fmt(0.25 * std::sqrt(std::max(0.0, Pc->variance())) / (1.0 + eps)) + " or less");
  const double X0 = s[XPOS];
  if (X1 == X0 && h == 0.0) return 0.0;
  // sub-steps of at most du (1 + 1e-9): a step of du that rounding made
  // a little longer is not split (the count, hence the discretization, must
  // not flip with the rounding of the displacements)
  const long n =
      std::max(1L, static_cast<long>(std::ceil(std::fabs(X1 - X0) * inv_du - SPLIT_SLACK)));
  double total = 0.0, xa = X0;
  for (long k = 1; k <= n; ++k) {
    const double xb = k == n ? X1 : X0 + (X1 - X0) * (double(k) / double(n));
    const double hs = h / double(n);
    double D = 0.0, MX = 0.0, DT = 0.0;
    substep(s, xa, xb, eps, hs, D, MX, DT);
    total += D;
    // MT: the first moment of the re-forming times (no delay: the breaks')
    double MT = DT;
    if (delay == DelayKind::EXPONENTIAL) wait(s, xa, xb, hs, D, MX, MT, DT);
    else if (delay == DelayKind::FIXED) fifo(s, xa, xb, hs, D, MX, MT, DT, n);
    double age_new = 0.0;    // of the fresh contacts at the sub-step's end
    if (aging) {
      grow_old(s, hs);
      const double tr = crossing == Crossing::STEP || !(D > 0.0) ? hs : MT / D;
      age_new = std::min(hs, std::max(0.0, hs - tr));
    }
    reform(s, xa, xb, D, MX, age_new);
    trim(s);
    xa = xb;
  }
  s[XPOS] = X1;
  s[RATE] = X1 != X0 ? total / std::fabs(X1 - X0) : 0.0;
  totals(s);
  return total;
}

/* ---------------------------------------------------------------------- */

double ThermalMesoModel::position(const double *s) const
{
  return s[XPOS];
}
double ThermalMesoModel::mean_stretch(const double *s) const
{
  return s[STRETCH];
}
double ThermalMesoModel::attached(const double *s) const
{
  return s[MASS];
}
double ThermalMesoModel::detached(const double *s) const
{
  return s[DET];
}
double ThermalMesoModel::waiting(const double *s) const
{
  if (delay == DelayKind::EXPONENTIAL) return s[pool + WAIT];
  if (delay != DelayKind::FIXED) return 0.0;
  const double *q = s + pool;
  const long head = long(q[FHEAD]), count = long(q[FCOUNT]);
  double w = 0.0;
  for (long k = 0; k < count; ++k) w += q[NFIFO + 3 * ((head + k) % MESO_DELAY_BINS) + 2];
  return w;
}
double ThermalMesoModel::rate(const double *s) const
{
  return s[RATE];
}

long ThermalMesoModel::rows(const double *s) const
{
  return std::max(0L, long(s[JHI]) - long(s[JLO]) + 1);
}

double ThermalMesoModel::normalization_error(const double *s) const
{
  double mass = 0.0;
  for (long j = long(s[JLO]); j <= long(s[JHI]); ++j) {
    const double *r = row(s, j);
    for (int l = 0; l < nl; ++l) mass += r[1 + l];
  }
  return std::fabs(mass + s[DET] + waiting(s) - 1.0);
}

bool ThermalMesoModel::valid(const double *s) const
{
  if (s[TAG] != tag) return false;
  const double lo = s[JLO], hi = s[JHI];
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo == std::floor(lo) && hi == std::floor(hi)))
    return false;
  if (!(std::fabs(lo) < 4e15 && hi - lo + 1.0 <= ncap && hi - lo >= -1.0)) return false;
  if (delay == DelayKind::FIXED) {
    const double head = s[pool + FHEAD], count = s[pool + FCOUNT];
    if (!(head >= 0.0 && head < MESO_DELAY_BINS && head == std::floor(head) && count >= 0.0 &&
          count <= MESO_DELAY_BINS && count == std::floor(count)))
      return false;
    // each bin in flight: a finite window and a mass in [0, 1] (a NaN
    // window would hold its mass for ever)
    for (long k = 0; k < long(count); ++k) {
      const double *b = s + pool + NFIFO + 3 * ((long(head) + k) % MESO_DELAY_BINS);
      if (!(std::isfinite(b[0]) && std::isfinite(b[1]) && b[2] >= 0.0 && b[2] <= 1.0 + 1e-12))
        return false;
    }
  }
  if (aging)    // the rows' ages: finite and >= 0 (a NaN age would never break by crossing)
    for (long j = long(lo); j <= long(hi); ++j) {
      const double a = s[ages + ((j % ncap) + ncap) % ncap];
      if (!(a >= 0.0 && std::isfinite(a))) return false;
    }
  const double w = waiting(s);
  if (!(w >= 0.0 && w <= 1.0 + 1e-12)) return false;
  return std::isfinite(s[XPOS]) && s[DET] >= 0.0;
}

}    // namespace feq
