/* ----------------------------------------------------------------------
   FRICTION-EQ package: master-equation solver (see eq_master_equation.h)
------------------------------------------------------------------------- */

#include "eq_master_equation.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace feq {

namespace {

const double INF = std::numeric_limits<double>::infinity();

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
    Pc(std::move(Pc_)), R(std::move(R_)), dx(dx_), nstep(0), jlo(0), jhi(0), wlo(0), whi(0),
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
  top = std::max(top, rhi) + 2.0 * dx;
  const long jneg = std::max(0L, (long) std::ceil(-std::min(rlo, 0.0) / dx)) + 2;
  const long jpos = (long) std::ceil(top / dx) + 1;
  const size_t n = size_t(jneg + jpos + 1);
  if (n > 200000000) throw SpecError("master equation: grid too large; increase dx");
  x.resize(n);
  for (size_t j = 0; j < n; ++j) x[j] = double(long(j) - jneg) * dx;

  // per-point break probability over one step and mean elapsed fraction
  brk.assign(n, 1.0);
  theta.assign(n, 0.5);
  for (size_t j = 0; j + 1 < n; ++j) {
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
  if (R) {
    if (R->is_point()) {
      const double x0 = R->mean();
      const double f = (x0 - x[0]) / dx;
      size_t k = size_t(std::floor(f));
      k = std::min(k, n - 2);
      const double t = f - double(k);
      w[k] += 1.0 - t;
      w[k + 1] += t;
    } else {
      for (size_t k = 0; k + 1 < n; ++k) {
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
    if (crossing == Crossing::EXACT)
      for (size_t k = wlo; k <= whi; ++k) w_rebreak += w[k] * brk[k];
  }
  m.assign(n, 0.0);
}

void MasterEquation::start(MEStart how)
{
  std::fill(m.begin(), m.end(), 0.0);
  nstep = 0;
  last_rate = 0.0;
  if (how == MEStart::REFORM && R) {
    m = w;
    jlo = wlo;
    jhi = whi;
  } else {
    // x = 0 is grid point j0
    size_t j0 = 0;
    while (x[j0] < -0.5 * dx) ++j0;
    m[j0] = 1.0;
    jlo = jhi = j0;
  }
}

void MasterEquation::step()
{
  const size_t n = m.size();
  double b0 = 0.0, b1 = 0.0;    // broken mass re-formed at r, at r + dx
  // transport by one grid point with survival; mass at the last point breaks
  if (jhi == n - 1) {
    b0 += m[n - 1] * theta[n - 1];
    b1 += m[n - 1] * (1.0 - theta[n - 1]);
    m[n - 1] = 0.0;
    --jhi;
  }
  for (size_t j = jhi + 1; j-- > jlo;) {
    const double mj = m[j];
    const double b = mj * brk[j];
    b0 += b * theta[j];
    b1 += b * (1.0 - theta[j]);
    m[j + 1] = mj - b;
  }
  m[jlo] = 0.0;
  ++jlo;
  ++jhi;
  // A break at elapsed fraction theta leaves (1-theta) dx of travel after
  // re-forming at r: weight theta at r, 1-theta at r + dx.  The part that
  // travels survives that grid step (S_k); the part that breaks again
  // within the step (rebroken fraction of b1) re-forms once more at r.
  // Without this, contacts re-formed where P(x) > 0 would miss their
  // immediate re-breaks and the scheme would drop to first order.
  double again = 0.0;
  if (R) {
    again = b1 * w_rebreak;
    const double b0t = b0 + again;
    for (size_t k = wlo; k <= whi; ++k) {
      m[k] += b0t * w[k];
      m[k + 1] += b1 * w[k] * (1.0 - brk[k]);
    }
    jlo = std::min(jlo, wlo);
    jhi = std::max(jhi, whi + 1);
  }
  jhi = std::min(jhi, n - 1);
  while (jlo < jhi && m[jlo] == 0.0) ++jlo;
  last_rate = (b0 + b1 + again) / dx;
  ++nstep;
}

double MasterEquation::attached() const
{
  double s = 0.0;
  for (size_t j = jlo; j <= jhi; ++j) s += m[j];
  return s;
}

double MasterEquation::mean_stretch() const
{
  double s = 0.0;
  for (size_t j = jlo; j <= jhi; ++j) s += m[j] * x[j];
  return s;
}

double MasterEquation::second_moment() const
{
  double s = 0.0;
  for (size_t j = jlo; j <= jhi; ++j) s += m[j] * x[j] * x[j];
  return s;
}

double MasterEquation::third_moment() const
{
  double s = 0.0;
  for (size_t j = jlo; j <= jhi; ++j) s += m[j] * x[j] * x[j] * x[j];
  return s;
}

std::vector<double> MasterEquation::density() const
{
  std::vector<double> q(m.size());
  for (size_t j = 0; j < m.size(); ++j) q[j] = m[j] / dx;
  return q;
}

/* ---------------------------------------------------------------------- */

MEResult solve_master_equation(DistributionPtr Pc, DistributionPtr R, const MEOptions &opt)
{
  if (!(opt.Xmax >= 0.0)) throw SpecError("master equation: xmax must be >= 0");
  MasterEquation me(Pc, R, opt.dx, 1e-17, opt.crossing);
  me.start(opt.start);
  MEResult r;
  r.dx = opt.dx;
  r.x = me.grid();
  const long nsteps = (long) std::llround(opt.Xmax / opt.dx);
  r.X.reserve(nsteps + 1);
  std::vector<long> snapk;
  for (double xs : opt.snapshots) snapk.push_back((long) std::llround(xs / opt.dx));
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
  top = std::max(top, rhi);
  std::vector<double> breaks = Pc.breakpoints();
  for (double b : R.breakpoints()) breaks.push_back(b);

  // survival of a contact formed at r up to stretch x: J(x)/J(r)
  auto surv_from = [&](double r, double xx) {
    const double jr = Pc.sf(r);
    return jr > 0.0 ? Pc.sf(xx) / jr : 0.0;
  };
  // mean lifetime and mean of int x dx over a life formed at r
  auto life = [&](double r) {
    const double jr = Pc.sf(r);
    return jr > 0.0 ? Pc.sf_integral(r, top) / jr : 0.0;
  };
  auto xlife = [&](double r) {
    const double jr = Pc.sf(r);
    if (!(jr > 0.0)) return 0.0;
    return integrate([&](double xx) { return xx * Pc.sf(xx); }, r, top, breaks, 64) / jr;
  };
  if (R.is_point()) {
    const double r0 = R.mean();
    s.lifetime = life(r0);
    s.F = s.lifetime > 0.0 ? xlife(r0) / s.lifetime : r0;
  } else {
    s.lifetime = integrate([&](double r) { return R.pdf(r) * life(r); }, rlo, rhi, breaks, 32);
    const double num = integrate([&](double r) { return R.pdf(r) * xlife(r); }, rlo, rhi, breaks, 8);
    s.F = num / s.lifetime;
  }
  s.Gamma = s.lifetime > 0.0 ? 1.0 / s.lifetime : INF;

  // density on a grid: Q_s(x) = Gamma int_{-inf}^{x} R(r) J(x)/J(r) dr
  const double xlo = std::min(rlo, 0.0);
  s.x.resize(npoints);
  s.Q.resize(npoints);
  for (int i = 0; i < npoints; ++i) {
    const double xx = xlo + (top - xlo) * i / (npoints - 1);
    s.x[i] = xx;
    double q;
    if (R.is_point()) {
      q = (xx >= R.mean()) ? surv_from(R.mean(), xx) : 0.0;
    } else {
      q = integrate([&](double r) { return R.pdf(r) * surv_from(r, xx); }, rlo, std::min(xx, rhi),
                    breaks, 4);
    }
    s.Q[i] = s.Gamma * q;
  }
  return s;
}

/* ---------------------------------------------------------------------- */

Extremum critical_stiffness(const MEResult &r)
{
  Extremum e;
  e.value = -INF;
  for (size_t k = 0; k + 1 < r.F.size(); ++k) {
    const double slope = -(r.F[k + 1] - r.F[k]) / r.dx;
    if (slope > e.value) {
      e.value = slope;
      e.X = 0.5 * (r.X[k] + r.X[k + 1]);
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
  e.value = r.F[k];
  e.X = r.X[k];
  if (k > 0 && k + 1 < n) {
    const double fm = r.F[k - 1], f0 = r.F[k], fp = r.F[k + 1];
    const double den = fm - 2.0 * f0 + fp;
    if (den < 0.0) {
      const double t = 0.5 * (fm - fp) / den;
      e.X = r.X[k] + t * r.dx;
      e.value = f0 - 0.25 * (fm - fp) * t;
    }
  }
  return e;
}

}    // namespace feq
