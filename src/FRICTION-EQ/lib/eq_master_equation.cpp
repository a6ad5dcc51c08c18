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
   FRICTION-EQ package: master-equation solver (see eq_master_equation.h)
------------------------------------------------------------------------- */

#include "eq_master_equation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace feq {

namespace {

const double INF = std::numeric_limits<double>::infinity();

// size limits (eq_me_job.cpp checks the same before any allocation, with
// the keyword's name): 2e8 grid points are 8 GB of solver arrays, 2e8
// steps 9.6 GB of F(X) table
const double ME_MAX_GRID_POINTS = 2e8;
const double ME_MAX_STEPS = 2e8;

std::string fmtg(double v)
{
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

struct GaussLegendre {
  std::vector<double> t, w;    // nodes on [-1,1], weights
  explicit GaussLegendre(int n) : t(n), w(n)
  {
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < (n + 1) / 2; ++i) {
      double z = std::cos(pi * (i + 0.75) / (n + 0.5)), pp = 0.0;
      for (int it = 0; it < 100; ++it) {
        double p1 = 1.0, p2 = 0.0;
        for (int j = 0; j < n; ++j) {
          const double p3 = p2;
          p2 = p1;
          p1 = ((2.0 * j + 1.0) * z * p2 - j * p3) / (j + 1);
        }
        pp = n * (z * p1 - p2) / (z * z - 1.0);
        const double dz = p1 / pp;
        z -= dz;
        if (std::fabs(dz) < 1e-16) break;
      }
      t[i] = -z;
      t[n - 1 - i] = z;
      w[i] = w[n - 1 - i] = 2.0 / ((1.0 - z * z) * pp * pp);
    }
  }
};

const GaussLegendre &gl10()
{
  static const GaussLegendre g(10);
  return g;
}

}    // namespace

double integrate(const std::function<double(double)> &f, double a, double b,
                 const std::vector<double> &breaks, int panels)
{
  if (!(b > a)) return 0.0;
  std::vector<double> pts{a};
  for (double p : breaks)
    if (p > a && p < b) pts.push_back(p);
  pts.push_back(b);
  std::sort(pts.begin(), pts.end());
  const GaussLegendre &g = gl10();
  double sum = 0.0;
  for (size_t s = 0; s + 1 < pts.size(); ++s) {
    const double h = (pts[s + 1] - pts[s]) / panels;
    for (int k = 0; k < panels; ++k) {
      const double c = pts[s] + (k + 0.5) * h;
      double part = 0.0;
      for (size_t i = 0; i < g.t.size(); ++i) part += g.w[i] * f(c + 0.5 * h * g.t[i]);
      sum += 0.5 * h * part;
    }
  }
  return sum;
}

/* ---------------------------------------------------------------------- */

MasterEquation::MasterEquation(DistributionPtr Pc_, DistributionPtr R_, double dx_, double tail,
                               Crossing crossing_) :
    Pc(std::move(Pc_)), R(std::move(R_)), dx(dx_), nstep(0), jlo(0), jhi(-1), wlo(0), whi(-1),
    w_rebreak(0.0), crossing(crossing_), last_rate(0.0)
{
  if (!Pc) throw SpecError("master equation: missing threshold distribution");
  if (!(dx > 0.0) || !std::isfinite(dx)) throw SpecError("master equation: dx must be > 0");

  // grid x_j = (j - j0) dx: 0 is a grid point; below it room for R
  double rlo = 0.0, rhi = 0.0;
  if (R) {
    rlo = R->lower();
    rhi = R->upper();
    if (!std::isfinite(rlo)) rlo = R->quantile(1e-17);
    if (!std::isfinite(rhi)) rhi = R->isf(1e-17);
  }
  double top = Pc->upper();
  if (!std::isfinite(top)) top = Pc->isf(tail);
  top = std::max(top, std::max(rhi, -rlo)) + 2.0 * dx;
  // the size in floating point first: a range of 1e300 must not overflow
  // the integer conversion (and pass as a negative size)
  const double jneg_d = std::ceil(-std::min(rlo, 0.0) / dx) + 2.0;
  const double jpos_d = std::ceil(top / dx) + 1.0;
  if (!(jneg_d + jpos_d + 1.0 <= ME_MAX_GRID_POINTS))
    throw SpecError("master equation: the stretch grid x in [" + fmtg(std::min(rlo, 0.0)) + ", " +
                    fmtg(top) + "] would need " + fmtg(jneg_d + jpos_d + 1.0) + " points at dx = " +
                    fmtg(dx) + " (at most " + fmtg(ME_MAX_GRID_POINTS) + "); raise dx");
  const long jneg = static_cast<long>(jneg_d);
  const long jpos = static_cast<long>(jpos_d);
  const long n = jneg + jpos + 1;
  x.resize(n);
  for (long j = 0; j < n; ++j) x[j] = double(j - jneg) * dx;

  // per-point break probability over one step and mean elapsed fraction
  brk.assign(n, 1.0);
  theta.assign(n, 0.5);
  for (long j = 0; j + 1 < n; ++j) {
    const double a = x[j], b = x[j + 1];
    const double sa = Pc->sf(a);
    if (!(sa > 0.0)) continue;    // beyond the support: everything breaks
    const double sb = Pc->sf(b);
    const double d = (sa > 0.5) ? Pc->cdf(b) - Pc->cdf(a) : sa - sb;
    brk[j] = std::min(1.0, std::max(0.0, d / sa));
    if (d > 0.0) {
      const double th = (Pc->sf_integral(a, b) - dx * sb) / (dx * d);
      theta[j] = std::min(1.0, std::max(0.0, th));
    }
  }
  brk[n - 1] = 1.0;
  // step convention: every break re-forms at the end of the step
  if (crossing == Crossing::STEP) std::fill(theta.begin(), theta.end(), 1.0);

  // re-injection weights (hat functions: mass and first moment exact)
  w.assign(n, 0.0);
  is_held.assign(n, 0);
  if (R) {
    if (R->is_point()) {
      const double x0 = R->mean();
      const double f = (x0 - x[0]) / dx;
      long k = std::min(static_cast<long>(std::floor(f)), n - 2);
      const double t = f - double(k);
      w[k] += 1.0 - t;
      w[k + 1] += t;
    } else {
      for (long k = 0; k + 1 < n; ++k) {
        const double a = x[k], b = x[k + 1];
        const double mass = R->cdf(b) - R->cdf(a);
        if (mass <= 0.0) continue;
        const double m1 = R->partial_mean(a, b);
        const double right = std::min(mass, std::max(0.0, (m1 - a * mass) / dx));
        w[k] += mass - right;
        w[k + 1] += right;
      }
    }
    double sum = 0.0;
    for (double v : w) sum += v;
    for (double &v : w) v /= sum;
    wlo = 0;
    while (wlo < n && w[wlo] == 0.0) ++wlo;
    whi = n - 1;
    while (whi > wlo && w[whi] == 0.0) --whi;
    for (long k = wlo; k <= whi; ++k) {
      // negative re-forming stretches that thresholds could lie below
      if (w[k] > 0.0 && x[k] < 0.0 && Pc->cdf(-x[k]) > 0.0) {
        Held h;
        h.k = k;
        h.len = std::lround(-2.0 * x[k] / dx);
        h.release = k + h.len;
        h.ring.assign(h.len, 0.0);
        h.M = h.A1 = h.A2 = h.A3 = 0.0;
        held.push_back(h);
        is_held[k] = 1;
      }
    }
    if (crossing == Crossing::EXACT)
      for (long k = wlo; k <= whi; ++k) w_rebreak += w[k] * brk[k];
  }
  m.assign(n, 0.0);
}

void MasterEquation::extend(long lo, long hi)
{
  if (jlo > jhi) {
    jlo = lo;
    jhi = hi;
  } else {
    jlo = std::min(jlo, lo);
    jhi = std::max(jhi, hi);
  }
}

// add mass of the given age (0 or 1 steps) to a delay line
void MasterEquation::hold(Held &h, double mass, long age)
{
  if (mass == 0.0) return;
  h.ring[((nstep - age) % h.len + h.len) % h.len] += mass;
  const double a = double(age);
  h.M += mass;
  h.A1 += mass * a;
  h.A2 += mass * a * a;
  h.A3 += mass * a * a * a;
}

void MasterEquation::start(MEStart how)
{
  std::fill(m.begin(), m.end(), 0.0);
  for (auto &h : held) {
    std::fill(h.ring.begin(), h.ring.end(), 0.0);
    h.M = h.A1 = h.A2 = h.A3 = 0.0;
  }
  nstep = 0;
  last_rate = 0.0;
  jlo = 0;
  jhi = -1;
  if (how == MEStart::REFORM && R) {
    for (long k = wlo; k <= whi; ++k)
      if (!is_held[k]) m[k] = w[k];
    for (auto &h : held) hold(h, w[h.k], 0);
    extend(wlo, whi);
  } else {
    // x = 0 is grid point j0
    long j0 = 0;
    while (x[j0] < -0.5 * dx) ++j0;
    m[j0] = 1.0;
    extend(j0, j0);
  }
}

void MasterEquation::step()
{
  const long n = static_cast<long>(m.size());
  ++nstep;
  double b0 = 0.0, b1 = 0.0;    // broken mass re-formed at r, at r + dx
  // transport by one grid point with survival; mass at the last point breaks
  if (jlo <= jhi && jhi == n - 1) {
    b0 += m[n - 1] * theta[n - 1];
    b1 += m[n - 1] * (1.0 - theta[n - 1]);
    m[n - 1] = 0.0;
    --jhi;
  }
  if (jlo <= jhi) {
    for (long j = jhi; j >= jlo; --j) {
      const double mj = m[j];
      const double b = mj * brk[j];
      b0 += b * theta[j];
      b1 += b * (1.0 - theta[j]);
      m[j + 1] = mj - b;
    }
    m[jlo] = 0.0;
    ++jlo;
    ++jhi;
  }
  // held contacts age by one step; those that reach |r_k| join the grid
  for (auto &h : held) {
    h.A3 += 3.0 * h.A2 + 3.0 * h.A1 + h.M;
    h.A2 += 2.0 * h.A1 + h.M;
    h.A1 += h.M;
    double &slot = h.ring[nstep % h.len];
    const double rel = slot;
    slot = 0.0;
    if (rel != 0.0) {
      const double L = double(h.len);
      h.M -= rel;
      h.A1 -= rel * L;
      h.A2 -= rel * L * L;
      h.A3 -= rel * L * L * L;
      m[h.release] += rel;
      extend(h.release, h.release);
    }
  }
  // A break at elapsed fraction theta leaves (1-theta) dx of travel after
  // re-forming at r: weight theta at r, 1-theta at r + dx.  The part that
  // travels survives that grid step (S_k); the part that breaks again
  // within the step (rebroken fraction of b1) re-forms once more at r.
  // Without this, contacts re-formed where P(x) > 0 would miss their
  // immediate re-breaks and the scheme would drop to first order.
  double again = 0.0;
  if (R && b0 + b1 > 0.0) {
    again = b1 * w_rebreak;
    const double b0t = b0 + again;
    for (long k = wlo; k <= whi; ++k) {
      if (is_held[k]) continue;
      m[k] += b0t * w[k];
      m[k + 1] += b1 * w[k] * (1.0 - brk[k]);
    }
    for (auto &h : held) {
      hold(h, b0t * w[h.k], 0);
      hold(h, b1 * w[h.k], 1);
    }
    extend(wlo, std::min(whi + 1, n - 1));
  }
  while (jlo <= jhi && m[jlo] == 0.0) ++jlo;
  last_rate = (b0 + b1 + again) / dx;
}

double MasterEquation::attached() const
{
  double s = 0.0;
  for (long j = jlo; j <= jhi; ++j) s += m[j];
  for (const auto &h : held) s += h.M;
  return s;
}

double MasterEquation::mean_stretch() const
{
  double s = 0.0;
  for (long j = jlo; j <= jhi; ++j) s += m[j] * x[j];
  for (const auto &h : held) s += x[h.k] * h.M + dx * h.A1;
  return s;
}

double MasterEquation::second_moment() const
{
  double s = 0.0;
  for (long j = jlo; j <= jhi; ++j) s += m[j] * x[j] * x[j];
  for (const auto &h : held) {
    const double r = x[h.k];
    s += r * r * h.M + 2.0 * r * dx * h.A1 + dx * dx * h.A2;
  }
  return s;
}

double MasterEquation::third_moment() const
{
  double s = 0.0;
  for (long j = jlo; j <= jhi; ++j) s += m[j] * x[j] * x[j] * x[j];
  for (const auto &h : held) {
    const double r = x[h.k];
    s += r * r * r * h.M + 3.0 * r * r * dx * h.A1 + 3.0 * r * dx * dx * h.A2 +
        dx * dx * dx * h.A3;
  }
  return s;
}

std::vector<double> MasterEquation::density() const
{
  std::vector<double> q(m.size());
  for (size_t j = 0; j < m.size(); ++j) q[j] = m[j] / dx;
  for (const auto &h : held)
    for (long i = 0; i < h.len; ++i) {
      if (h.ring[i] == 0.0) continue;
      const long age = ((nstep - i) % h.len + h.len) % h.len;
      q[h.k + age] += h.ring[i] / dx;
    }
  return q;
}

/* ---------------------------------------------------------------------- */

bool combine_richardson(MEResult &res, const MEResult &fine)
{
  if (fine.F.size() != 2 * res.F.size() - 1) return false;
  for (size_t k = 0; k < res.F.size(); ++k) {
    res.F[k] = (4.0 * fine.F[2 * k] - res.F[k]) / 3.0;
    res.sd[k] = fine.sd[2 * k];
    res.attached[k] = fine.attached[2 * k];
    res.skew[k] = fine.skew[2 * k];
  }
  return true;
}

MEResult solve_master_equation(DistributionPtr Pc, DistributionPtr R, const MEOptions &opt)
{
  if (!(opt.Xmax >= 0.0)) throw SpecError("master equation: xmax must be >= 0");
  if (!(opt.Xmax / opt.dx <= ME_MAX_STEPS))
    throw SpecError("master equation: xmax/dx = " + fmtg(opt.Xmax / opt.dx) + " steps (at most " +
                    fmtg(ME_MAX_STEPS) + "); lower xmax or raise dx");
  MasterEquation me(Pc, R, opt.dx, 1e-17, opt.crossing);
  me.start(opt.start);
  MEResult r;
  r.dx = opt.dx;
  r.x = me.grid();
  const long nsteps = static_cast<long>(std::llround(opt.Xmax / opt.dx));
  r.X.reserve(nsteps + 1);
  std::vector<long> snapk;
  for (double xs : opt.snapshots) snapk.push_back(static_cast<long>(std::llround(xs / opt.dx)));
  const double attached0 = me.attached();
  for (long k = 0; k <= nsteps; ++k) {
    if (k > 0) me.step();
    const double att = me.attached();
    const double mean = me.mean_stretch();
    r.X.push_back(k * opt.dx);
    r.F.push_back(mean);
    // sd of the stretch of one contact (detached contacts count as x = 0)
    const double m2 = me.second_moment();
    const double var = std::max(0.0, m2 - mean * mean);
    r.sd.push_back(std::sqrt(var));
    const double c3 = me.third_moment() - 3.0 * mean * m2 + 2.0 * mean * mean * mean;
    r.skew.push_back(var > 0.0 ? c3 / (var * std::sqrt(var)) : 0.0);
    r.Gamma.push_back(me.rate());
    r.attached.push_back(att);
    if (R) r.max_mass_error = std::max(r.max_mass_error, std::fabs(att - attached0));
    for (size_t s = 0; s < snapk.size(); ++s)
      if (snapk[s] == k) {
        r.snapX.push_back(k * opt.dx);
        r.snapQ.push_back(me.density());
      }
  }
  return r;
}

/* ---------------------------------------------------------------------- */

SteadyState steady_state(const Distribution &Pc, const Distribution &R, int npoints)
{
  SteadyState s;
  double top = Pc.upper();
  if (!std::isfinite(top)) top = Pc.isf(1e-17);
  double rlo = R.lower(), rhi = R.upper();
  if (!std::isfinite(rlo)) rlo = R.quantile(1e-17);
  if (!std::isfinite(rhi)) rhi = R.isf(1e-17);
  top = std::max(top, std::max(rhi, -rlo));
  const std::vector<double> pcb = Pc.breakpoints();

  // T1(y) = int_y^top x J(x) dx on a grid of [0, top] (cumulative from the
  // top, Gauss-Legendre per cell, cells split at the kinks of P_c)
  const int ncell = 4096;
  std::vector<double> g;
  for (int i = 0; i <= ncell; ++i) g.push_back(top * i / ncell);
  for (double b : pcb)
    if (b > 0.0 && b < top) g.push_back(b);
  std::sort(g.begin(), g.end());
  g.erase(std::unique(g.begin(), g.end()), g.end());
  auto xsf = [&](double xx) { return xx * Pc.sf(xx); };
  std::vector<double> T1(g.size(), 0.0);
  for (size_t i = g.size() - 1; i-- > 0;) T1[i] = T1[i + 1] + integrate(xsf, g[i], g[i + 1], {}, 1);
  auto tail1 = [&](double y) {
    if (y >= top) return 0.0;
    size_t i = std::upper_bound(g.begin(), g.end(), y) - g.begin();    // g[i-1] <= y < g[i]
    i = std::max<size_t>(i, 1);
    return T1[i] + integrate(xsf, y, g[i], {}, 1);
  };
  // A contact re-formed at r holds until its stretch reaches r+ = |r| (its
  // threshold lies above |r|), then breaks with the hazard of P_c:
  //   life(r)  = (r+ - r) + int_{r+} J / J(r+),
  //   xlife(r) = int_r^{r+} x dx + int_{r+} x J / J(r+).
  auto plus = [](double r) { return std::fabs(r); };
  auto life = [&](double r) {
    const double rp = plus(r), j = Pc.sf(rp);
    return j > 0.0 ? (rp - r) + Pc.sf_integral(rp, top) / j : 0.0;
  };
  auto xlife = [&](double r) {
    const double rp = plus(r), j = Pc.sf(rp);
    return j > 0.0 ? 0.5 * (rp * rp - r * r) + tail1(rp) / j : 0.0;
  };
  // kinks of the integrands: those of R and P_c, mirrored (r -> |r|)
  std::vector<double> breaks{0.0};
  for (double b : R.breakpoints()) {
    breaks.push_back(b);
    breaks.push_back(-b);
  }
  for (double b : pcb) {
    breaks.push_back(b);
    breaks.push_back(-b);
  }
  if (R.is_point()) {
    const double r0 = R.mean();
    s.lifetime = life(r0);
    s.F = s.lifetime > 0.0 ? xlife(r0) / s.lifetime : r0;
  } else {
    s.lifetime = integrate([&](double r) { return R.pdf(r) * life(r); }, rlo, rhi, breaks, 16);
    s.F = integrate([&](double r) { return R.pdf(r) * xlife(r); }, rlo, rhi, breaks, 16) /
        s.lifetime;
  }
  s.Gamma = s.lifetime > 0.0 ? 1.0 / s.lifetime : INF;

  // Q_s(x): contacts re-formed at r <= x, still held or surviving:
  //   x < 0:  Gamma P(r <= x)
  //   x >= 0: Gamma [ P(r < -x) + J(x) int_0^x (R(u) + R(-u)) / J(u) du ]
  const double xlo = std::min(rlo, 0.0);
  s.x.resize(npoints);
  s.Q.resize(npoints);
  double C = 0.0, xprev = 0.0;
  auto cf = [&](double u) {
    const double j = Pc.sf(u);
    return j > 0.0 ? (R.pdf(u) + R.pdf(-u)) / j : 0.0;
  };
  for (int i = 0; i < npoints; ++i) {
    const double xx = xlo + (top - xlo) * i / (npoints - 1);
    s.x[i] = xx;
    double q;
    if (R.is_point()) {
      const double r0 = R.mean(), rp = plus(r0);
      if (xx < r0) q = 0.0;
      else if (xx < rp) q = 1.0;
      else q = Pc.sf(rp) > 0.0 ? Pc.sf(xx) / Pc.sf(rp) : 0.0;
    } else if (xx < 0.0) {
      q = R.cdf(xx);
    } else {
      C += integrate(cf, xprev, xx, breaks, 1);
      xprev = xx;
      q = R.cdf(std::nextafter(-xx, -INF)) + Pc.sf(xx) * C;    // P(r < -x) + ...
    }
    s.Q[i] = s.Gamma * q;
  }
  return s;
}

/* ---------------------------------------------------------------------- */

Extremum critical_stiffness(const MEResult &r)
{
  Extremum e;
  for (size_t k = 0; k + 1 < r.F.size(); ++k) {
    const double slope = -(r.F[k + 1] - r.F[k]) / r.dx;
    if (slope > e.value) {
      e.value = slope;
      e.X = 0.5 * (r.X[k] + r.X[k + 1]);
      e.found = true;
    }
  }
  return e;
}

Extremum static_peak(const MEResult &r)
{
  Extremum e;
  const size_t n = r.F.size();
  size_t k = 0;
  while (k + 1 < n && r.F[k + 1] >= r.F[k]) ++k;
  // the largest value on the grid: below the true maximum by at most
  // |F''| dx^2 / 8 where F is smooth, exact at a kink on the grid (a
  // parabola through three points would overshoot a kink)
  e.value = r.F[k];
  e.X = r.X[k];
  e.found = k + 1 < n;
  return e;
}

}    // namespace feq
