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
   FRICTION-EQ package: steady state and transient of thermally activated,
   aging contacts on a rigid slider (see eq_thermal_steady.h)
------------------------------------------------------------------------- */

#include "eq_thermal_steady.h"
#include "eq_text.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace feq {

namespace {

const double INF = std::numeric_limits<double>::infinity();
const double PI = 3.14159265358979323846;
// unbounded threshold tails are cut at this probability
const double TAIL = 1e-18;
// a hazard beyond this survives with e^-60 ~ 1e-26: taken as broken
const double H_CUT = 60.0;
// tolerances: the hazard (per quadrature), the survival of one y (over
// the thresholds), the moments of one life per unit length (of the
// life's scale), and the moments averaged over the thresholds (relative)
const double TOL_H = 1e-13;
const double TOL_S = 1e-12;
const double TOL_LIFE = 1e-13;
const double TOL_STEADY = 1e-12;
const size_t MAX_INTERVALS = 400;    // per adaptive quadrature (beyond the initial ones)
// the survival at y leaves out the thresholds where h P(x_s0 > x) is
// negligible, looked for on this many steps
const int CUT_STEPS = 32;
// a kink of S whose jump of slope is below this (relative) is smoothed
const double KINK_NEGLIGIBLE = 1e-14;
// the most a panel of a life may add to the hazard H
const double DH_PANEL = 2.0;
// a life's march that needs more panels than this stops with an error (a
// guard: a life takes tens to hundreds of panels, no known case more
// than some thousand since the grading of ContactLife::moments())
const long MAX_LIFE_PANELS = 2000000;

/* ---------------------------------------------------------------------- */

// Gauss-Legendre rule on [-1, 1] and its integration matrix:
// integ[i][j] = int_{-1}^{t_i} l_j(t) dt (l_j: Lagrange basis of the nodes)
struct GaussRule {
  int n;
  std::vector<double> t, w;
  std::vector<std::vector<double>> integ;
  explicit GaussRule(int n_);
};

// Legendre polynomials P_0..P_n at z
void legendre(int n, double z, std::vector<double> &P)
{
  P.assign(n + 1, 0.0);
  P[0] = 1.0;
  if (n > 0) P[1] = z;
  for (int k = 1; k < n; ++k) P[k + 1] = ((2.0 * k + 1.0) * z * P[k] - k * P[k - 1]) / (k + 1);
}

GaussRule::GaussRule(int n_) : n(n_), t(n_), w(n_), integ(n_, std::vector<double>(n_))
{
  std::vector<double> P;
  for (int i = 0; i < n; ++i) {
    double z = std::cos(PI * (i + 0.75) / (n + 0.5));
    for (int it = 0; it < 100; ++it) {
      legendre(n, z, P);
      const double dz = P[n] / (n * (z * P[n] - P[n - 1]) / (z * z - 1.0));
      z -= dz;
      if (std::fabs(dz) < 1e-16) break;
    }
    legendre(n, z, P);
    const double dp = n * (z * P[n] - P[n - 1]) / (z * z - 1.0);
    t[n - 1 - i] = z;
    w[n - 1 - i] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
  // l_j = sum_k c_jk P_k, c_jk = (2k+1)/2 w_j P_k(t_j); int_{-1}^{x} P_k =
  // (P_{k+1} - P_{k-1})(x)/(2k+1) for k >= 1, x + 1 for k = 0
  std::vector<double> Pj, Pi;
  for (int j = 0; j < n; ++j) {
    legendre(n, t[j], Pj);
    for (int i = 0; i < n; ++i) {
      legendre(n, t[i], Pi);
      double s = 0.5 * w[j] * (t[i] + 1.0);
      for (int k = 1; k < n; ++k) s += 0.5 * w[j] * Pj[k] * (Pi[k + 1] - Pi[k - 1]);
      integ[i][j] = s;
    }
  }
}

const GaussRule &gauss12()
{
  static const GaussRule rule(12);
  return rule;
}

// Gauss-Kronrod 7-15 (QUADPACK qk15): Kronrod nodes, weights, and the
// Gauss weights of the odd nodes
const double XGK[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                       0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                       0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                       0.207784955007898467600689403773245, 0.0};
const double WGK[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                       0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                       0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                       0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
const double WG[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                      0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

template <size_t K> using Vec = std::array<double, K>;

template <size_t K> struct Interval {
  double a, b, err;
  Vec<K> val;
};

// one Gauss-Kronrod 15 estimate on [a, b] with QUADPACK's error estimate
// (|K15 - G7| scaled by the variation of f: (200 |K15 - G7| / resasc)^1.5,
// at least 50 eps of int |f|), the largest over the K components
template <size_t K, class F> Interval<K> gk15(const F &f, double a, double b)
{
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  Vec<K> y[15];
  for (int i = 0; i < 7; ++i) {
    y[2 * i] = f(c + h * XGK[i]);
    y[2 * i + 1] = f(c - h * XGK[i]);
  }
  y[14] = f(c);
  Interval<K> r{a, b, 0.0, {}};
  for (size_t q = 0; q < K; ++q) {
    double k15 = WGK[7] * y[14][q], g7 = WG[3] * y[14][q], abs = WGK[7] * std::fabs(y[14][q]);
    for (int i = 0; i < 7; ++i) {
      const double pair = y[2 * i][q] + y[2 * i + 1][q];
      k15 += WGK[i] * pair;
      abs += WGK[i] * (std::fabs(y[2 * i][q]) + std::fabs(y[2 * i + 1][q]));
      if (i % 2) g7 += WG[i / 2] * pair;
    }
    const double mean = 0.5 * k15;
    double asc = WGK[7] * std::fabs(y[14][q] - mean);
    for (int i = 0; i < 7; ++i)
      asc += WGK[i] * (std::fabs(y[2 * i][q] - mean) + std::fabs(y[2 * i + 1][q] - mean));
    double err = std::fabs((k15 - g7) * h);
    asc *= std::fabs(h);
    if (asc != 0.0 && err != 0.0) err = asc * std::min(1.0, std::pow(200.0 * err / asc, 1.5));
    err = std::max(err, 50.0 * std::numeric_limits<double>::epsilon() * std::fabs(h) * abs);
    r.val[q] = h * k15;
    r.err = std::max(r.err, err);
  }
  return r;
}

// Globally adaptive Gauss-Kronrod over the pieces [pts_i, pts_i+1]:
// splits the interval of largest error until the summed error is below
// tol(total) (infinite to stop early) or max_intervals are used
template <size_t K, class F, class Tol>
Vec<K> adaptive(const F &f, const std::vector<double> &pts, const Tol &tol,
                size_t max_intervals = MAX_INTERVALS)
{
  std::vector<Interval<K>> iv;
  for (size_t i = 0; i + 1 < pts.size(); ++i)
    if (pts[i + 1] > pts[i]) iv.push_back(gk15<K>(f, pts[i], pts[i + 1]));
  Vec<K> total{};
  while (true) {
    total = Vec<K>{};
    double err = 0.0;
    size_t worst = 0;
    for (size_t i = 0; i < iv.size(); ++i) {
      for (size_t q = 0; q < K; ++q) total[q] += iv[i].val[q];
      err += iv[i].err;
      if (iv[i].err > iv[worst].err) worst = i;
    }
    if (iv.empty() || err <= tol(total) || iv.size() >= max_intervals)
      return total;
    const Interval<K> w = iv[worst];
    const double m = 0.5 * (w.a + w.b);
    if (!(m > w.a && m < w.b)) return total;    // no room left to split
    iv[worst] = gk15<K>(f, w.a, m);
    iv.push_back(gk15<K>(f, m, w.b));
  }
}

// the survival contributions of one panel [a, b] of a life: hazard
// increment, int e^-H and int x e^-H (H = H0 at a)
struct Panel {
  double dH, L, M;
};

}    // namespace

/* ---------------------------------------------------------------------- */

double ThermalSlider::delay_length() const
{
  return spec.delay == DelayKind::NONE ? 0.0 : v * spec.tau;
}

ContactLife::ContactLife(const ThermalSlider &s, double r0_, double age0_) :
    Pc(s.Pc), model(s.spec), v(s.v), r0(r0_), age0(age0_), norm(1.0), ytop(0.0), point(false)
{
  if (!Pc) throw SpecError("thermal: missing threshold distribution");
  if (!(v > 0.0) || !std::isfinite(v)) throw SpecError("velocity: must be > 0");
  const Distribution &P = *Pc;
  const double r = std::fabs(r0);
  point = P.is_point();
  if (point) {
    pieces = {P.mean(), P.mean()};
  } else {
    double lo = std::max(P.lower(), r), hi = P.upper();
    if (!std::isfinite(P.lower())) lo = std::max(lo, P.quantile(TAIL));
    if (!std::isfinite(hi)) hi = P.isf(TAIL);
    pieces.push_back(lo);
    for (double b : P.breakpoints())
      if (b > lo && b < hi) pieces.push_back(b);
    pieces.push_back(hi);
    std::sort(pieces.begin(), pieces.end());
    pieces.erase(std::unique(pieces.begin(), pieces.end()), pieces.end());
    norm = P.sf(r);
  }
  if (!(pieces.back() > r) || !(norm > 0.0))
    throw SpecError("reform: no threshold lies above the re-forming stretch |r| = " +
                    std::to_string(r));
  ytop = breakpoint(pieces.back());
}

// y*(x_s0): the root of x_s0 A(a0 + y/v) = |r0 + y| beyond y = -r0 (the
// left side minus the right one is concave there and positive at -r0)
double ContactLife::breakpoint(double xs0) const
{
  if (model.params().aging == AgingLaw::NONE) return xs0 - r0;
  const double y0 = std::max(0.0, -r0);
  auto g = [&](double y) { return xs0 * factor(y) - std::fabs(r0 + y); };
  double d = std::max(xs0, std::fabs(r0)), hi = y0 + d;
  for (int k = 0; k < 2000 && g(hi) > 0.0; ++k) {
    d *= 2.0;
    hi = y0 + d;
  }
  double lo = y0;
  for (int k = 0; k < 200; ++k) {
    const double m = 0.5 * (lo + hi);
    if (!(m > lo && m < hi)) break;
    (g(m) > 0.0 ? lo : hi) = m;
  }
  return lo;
}

double ContactLife::threshold_at(double y) const
{
  return std::fabs(r0 + y) / factor(y);
}

// S' jumps where s(y) crosses a kink b of P_c, by the jump of P_c times
// the survival e^-H of the threshold b up to its break point: at T > 0
// only the kinks where that survival is not negligible are kept
std::vector<double> ContactLife::kinks() const
{
  std::vector<double> k{0.0};
  if (r0 < 0.0) k.push_back(-r0);
  for (double b : pieces) {
    const double yb = breakpoint(b);
    if (b == pieces.back() || !(std::exp(-exponent(yb, b)) < KINK_NEGLIGIBLE)) k.push_back(yb);
  }
  std::sort(k.begin(), k.end());
  k.erase(std::unique(k.begin(), k.end()), k.end());
  return k;
}

namespace {
// the hazard's tolerance; none once H is beyond H_CUT for sure
double hazard_tol(const Vec<1> &H)
{
  return H[0] > 2.0 * H_CUT ? INF : TOL_H * (1.0 + H[0]);
}
}    // namespace

// H(y; x_s0): the rate grows toward y (u falls), the initial intervals
// are graded toward it; stops once H is beyond H_CUT for sure.  With a
// prefactor u^q (q > 0) the rate is not smooth where u reaches 0: at the
// end y of the threshold x_s0 = s(y), a node of every interpolant in
// x_s0 of survival().  There u = 1 - x/x_s0 near the end lost its digits
// to cancellation (relative noise 1e-16/u), and with the prefactor's
// kink the panels' errors did not fall below the tolerance: 400 panels
// per H (gaussian thresholds re-forming at 0.5, theta = 1e-3, q = 0.25:
// the transient did not end in minutes).  Without aging (x_s = x_s0)
// and r0 >= 0, the rate is taken at u = (g + d)/x_s0, g = (x_s0 - r0) - y
// the gap at the end and d = y - eta, in t with d = y t^4: no
// cancellation, and the rate goes as t^(4q+3) near the end (smooth at q
// = 1/4, C^3 for any q > 0)
double ContactLife::exponent(double y, double xs0) const
{
  if (!(model.params().theta > 0.0) || !(y > 0.0)) return 0.0;
  if (model.params().q > 0.0 && model.params().aging == AgingLaw::NONE && r0 >= 0.0)
    return exponent_kinked(y, xs0);
  // with aging the threshold rises over the aging length from the start
  // of the life: points graded from there (a first pass of 45 rates
  // could miss a rise 1e-4 of y wide, and H jumped by 1e-4 between
  // neighbouring x_s0: survival()'s interpolant in x_s0 then halved its
  // pieces to the smallest width, millions of H per y)
  std::vector<double> pts{0.0};
  for (double e = aging_length(); e > 0.0 && e < 0.5 * y; e *= 4.0) pts.push_back(e);
  pts.insert(pts.end(), {0.5 * y, 0.875 * y, y});
  auto f = [&](double eta) { return Vec<1>{{rate(eta, xs0)}}; };
  return adaptive<1>(f, pts, hazard_tol)[0];
}

// exponent() for q > 0 without aging and r0 >= 0: in t, eta = y (1 - t^4) (see there)
double ContactLife::exponent_kinked(double y, double xs0) const
{
  // (x_s0 - r0 exact for x_s0 within a factor 2 of r0, and so is its
  // difference with y there).  A gap below 0 (x_s0 = r0 + y rounded
  // down, the first node of survival()'s interpolant): the rate is 0
  // beyond x_s0, so the life ends there, u = 0 (a kink of u^q within the
  // life fooled the quadrature's error estimate: 8.6e-8 off)
  double gap = (xs0 - r0) - y;
  if (gap < 0.0) {
    y = xs0 - r0;
    gap = 0.0;
    if (!(y > 0.0)) return 0.0;
  }
  const double inv_v = 1.0 / v;
  const std::vector<double> pts{0.0, 0.5, 0.75, 0.875, 1.0};
  auto f = [&](double t) {
    const double t3 = t * t * t;
    const double u = (gap + y * (t3 * t)) / xs0;
    return Vec<1>{{4.0 * y * t3 * model.point_u(u, xs0).nu * inv_v}};
  };
  return adaptive<1>(f, pts, hazard_tol)[0];
}

double ContactLife::survival(double y) const
{
  if (!(y > 0.0)) return 1.0;
  const double s = threshold_at(y);
  const Distribution &P = *Pc;
  if (point) {
    const double x0 = pieces[0];
    return x0 > s ? std::exp(-exponent(y, x0)) : 0.0;
  }
  const double lo = std::max(s, pieces.front());
  if (!(lo < pieces.back())) return 0.0;
  const double alive = P.sf(lo) - P.sf(pieces.back());
  if (!(model.params().theta > 0.0)) return alive / norm;
  // minus the thresholds above s(y) that broke by activation before y:
  // h = 1 - e^-H(y; x_s0) falls as x_s0 grows (u grows), smoothly (the
  // kinks of P_c do not enter it): a Chebyshev interpolant on [lo, cut],
  // beyond which h P(x_s0 > x) is negligible, then int P_c h over the
  // pieces of P_c
  auto h = [&](double xs0) { return -std::expm1(-exponent(y, xs0)); };
  const double top = pieces.back();
  double cut = top;
  for (int k = 1; k < CUT_STEPS; ++k) {
    const double x = lo + (top - lo) * k / CUT_STEPS;
    if (h(x) * P.sf(x) < 1e-3 * TOL_S) {
      cut = x;
      break;
    }
  }
  PiecewiseChebyshev hc;
  hc.build(h, lo, cut, TOL_S, 1e-12 * std::max(1.0, top));
  std::vector<double> pts = hc.starts();
  for (double b : pieces)
    if (b > lo && b < cut) pts.push_back(b);
  pts.push_back(cut);
  std::sort(pts.begin(), pts.end());
  auto f = [&](double xs0) { return Vec<1>{{P.pdf(xs0) * hc(xs0)}}; };
  auto tol = [](const Vec<1> &) { return TOL_S; };
  const double broken = adaptive<1>(f, pts, tol, MAX_INTERVALS + pts.size())[0];
  // what is left below the accuracy of broken (TOL_S, of the normalised
  // S) is 0: beyond the lives S(y) would otherwise stay at that noise,
  // which the transient sums over its cells, each weighted by the
  // re-formations per cell, dx/<L> (lives of 4e-8: F(X) 1e-8 off at X = 8)
  const double left = alive - broken;
  return left > TOL_S * norm ? left / norm : 0.0;
}

namespace {

// one panel [a, b] of a life of threshold xs0 whose hazard is H0 at a:
// the rate at the Gauss nodes, H at the nodes by the integration matrix
template <class Rate> Panel life_panel(const Rate &rate, double r0, double a, double b, double H0)
{
  const GaussRule &g = gauss12();
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double nu[12];
  Panel p{0.0, 0.0, 0.0};
  for (int i = 0; i < g.n; ++i) {
    nu[i] = rate(c + h * g.t[i]);
    p.dH += h * g.w[i] * nu[i];
  }
  for (int i = 0; i < g.n; ++i) {
    double H = H0;
    for (int j = 0; j < g.n; ++j) H += h * g.integ[i][j] * nu[j];
    const double e = std::exp(-H);
    p.L += h * g.w[i] * e;
    p.M += h * g.w[i] * (r0 + c + h * g.t[i]) * e;
  }
  return p;
}

}    // namespace

// where the barrier at the break point's threshold x_s falls to
// ln(omega x_s / v), the level where a contact breaks within a slide of
// the order of x_s: u_z = (theta ln(omega x_s/v) / (x_s/x_c)^p)^(2/3).  The
// zone of breaking before the break point is a few u_z x_s wide; 0 where
// that is the whole life (T large for the velocity)
double ContactLife::zone_start(double xs0, double ys) const
{
  const ThermalSpec &sp = model.params();
  const double xs = xs0 * factor(ys);
  const double level = std::log(sp.omega * xs / v);
  if (!(level > 0.0)) return 0.0;
  const double scale = sp.p != 0.0 ? std::pow(xs / sp.xc, sp.p) : 1.0;
  const double width = 4.0 * std::pow(sp.theta * level / scale, 2.0 / 3.0) * xs;
  return width < ys ? ys - width : 0.0;
}

// the relative rounding of the rate at y: u = 1 - x/x_s loses eps/u, and
// the barrier B = ln(omega/nu) multiplies a relative change of u by 1.5 B
double ContactLife::rate_noise(double y, double xs0) const
{
  const double eps = std::numeric_limits<double>::epsilon();
  const double xs = xs0 * factor(y);
  const double u = 1.0 - std::fabs(r0 + y) / xs;
  const double nu = v * rate(y, xs0);
  const double B = nu > 0.0 ? std::fmax(0.0, std::log(model.params().omega / nu)) : 0.0;
  return 64.0 * eps * (1.0 + 1.5 * B / std::fmax(u, eps));
}

// Marches along y in panels: a panel is accepted when H grows by at most
// DH_PANEL over it (so that its nodes see e^-H fall) and its two halves
// agree with it: the moments, and H weighted by what is left to survive
// (e^-H times the shorter of the rest of the life and v/nu, nu growing)
void ContactLife::moments(double xs0, double &L, double &M) const
{
  const double ys = breakpoint(xs0);
  if (!(model.params().theta > 0.0)) {
    L = ys;
    M = r0 * ys + 0.5 * ys * ys;
    return;
  }
  auto nu = [&](double y) { return rate(y, xs0); };
  L = M = 0.0;
  // the first panel within the aging length v (tau_a + age0), over which
  // the threshold rises fastest: a burst of breaking right after formation
  // (re-forming close to the threshold) lives there; the march then
  // doubles the panels where they are accurate.  It lands on the start
  // of the zone of breaking before the break point, yz, and enters it
  // with panels of the zone's width
  const double hmin = 1e-13 * ys;
  double a = 0.0, H = 0.0, h = std::fmax(hmin, std::fmin(ys / 16.0, aging_length()));
  const double yz = zone_start(xs0, ys);
  const double scale = std::fmax(1.0, ys + std::fabs(r0));
  long panels = 0;
  while (a < ys && H < H_CUT) {
    if (++panels > MAX_LIFE_PANELS)
      throw SpecError("thermal: the steady state's quadrature of one contact life (threshold " +
                      format_number(xs0, 6) + ", theta " + format_number(model.params().theta, 6) +
                      ", velocity " + format_number(v, 6) + ") does not converge within " +
                      std::to_string(MAX_LIFE_PANELS) + " panels (not known to happen: please "
                      "report these parameters; lengths in units of the mean threshold may help)");
    double b = a + h;
    if (b > ys - 0.01 * h) b = ys;
    if (a < yz && b > yz) b = yz;
    const double m = 0.5 * (a + b);
    const Panel one = life_panel(nu, r0, a, b, H);
    const Panel p1 = life_panel(nu, r0, a, m, H);
    const Panel p2 = life_panel(nu, r0, m, b, H + p1.dH);
    const double dH = p1.dH + p2.dH;
    const double rest = std::min(ys - b, 1.0 / std::max(nu(b), 1e-300));
    // the two halves' hazards differ by the rate's own rounding at least
    // (rate_noise()): only what is beyond it counts
    const double ddH = std::fmax(0.0, std::fabs(one.dH - dH) - rate_noise(b, xs0) * dH);
    const double err = std::fabs(one.L - p1.L - p2.L) + std::fabs(one.M - p1.M - p2.M) +
        std::exp(-H - dH) * rest * (1.0 + ys) * ddH;
    // per unit length of the life's own scale (lengths far from 1 in
    // their unit ask for the same relative accuracy)
    const double allowed = TOL_LIFE * (b - a) * scale;
    if (b - a > hmin && one.dH > DH_PANEL) {
      h = 0.5 * (b - a);
    } else if (err <= allowed || b - a <= hmin) {
      L += p1.L + p2.L;
      M += p1.M + p2.M;
      H += dH;
      if (a < yz && b == yz) h = std::min(h, (ys - yz) / 16.0);
      // (a panel taken at the smallest width is no reason to stay there)
      if (err < allowed / 64.0 || b - a <= hmin) h *= 2.0;
      a = b;
    } else {
      h = 0.5 * (b - a);
    }
  }
}

/* ---------------------------------------------------------------------- */

ThermalSteady thermal_steady_state(const ThermalSlider &s)
{
  if (!s.reform) throw SpecError("steady: contacts that never re-form have no steady state");
  const ContactLife life(s, s.r0, 0.0);
  Vec<2> LM{};
  const std::vector<double> &pts = life.threshold_pieces();
  if (life.point_thresholds()) {
    life.moments(pts[0], LM[0], LM[1]);
  } else {
    auto f = [&](double xs0) {
      Vec<2> r{};
      life.moments(xs0, r[0], r[1]);
      const double p = s.Pc->pdf(xs0);
      r[0] *= p;
      r[1] *= p;
      return r;
    };
    // relative: lifetimes far below 1 (activation long before the
    // threshold at small velocities) ask for the same accuracy
    auto tol = [](const Vec<2> &I) { return TOL_STEADY * (std::fabs(I[0]) + std::fabs(I[1])); };
    LM = adaptive<2>(f, pts, tol, MAX_INTERVALS + pts.size());
    LM[0] /= life.weight_norm();
    LM[1] /= life.weight_norm();
  }
  if (!(LM[0] > 0.0) || !std::isfinite(LM[1]))
    throw SpecError("velocity " + format_number(s.v, 6) + ": the contacts' lifetime " +
                    format_number(LM[0], 6) + " underflows (they break by activation long "
                    "before the slider moves them: the creep limit); use a larger velocity");
  ThermalSteady out;
  out.lifetime = LM[0];
  const double cycle = LM[0] + s.delay_length();
  out.Gamma = 1.0 / cycle;
  out.F = LM[1] / cycle;
  out.attached = LM[0] / cycle;
  return out;
}

double screened_load_factor(const ThermalSlider &s, double pi0)
{
  if (!(pi0 >= 0.0 && pi0 < 1.0))
    throw SpecError("screened load factor: Pi0 must be in [0, 1), got " + format_number(pi0, 6));
  if (pi0 == 0.0) return 0.0;
  const double xc = s.Pc->mean();
  auto h = [&](double lw) {
    ThermalSlider t = s;
    t.v = std::exp(lw);
    return 1.0 - s.v / t.v - pi0 * xc * thermal_steady_state(t).Gamma;
  };
  const double lv = std::log(s.v);
  double a = lv, b = lv + 1.0;
  while (!(h(b) > 0.0)) {
    a = b;
    b += 1.0;
    if (b - lv > 60.0)
      throw SpecError("screened load factor: eps0 beyond e^60 at velocity " +
                      format_number(s.v, 6) +
                      " (Pi0 x_c Gamma_s stays >= 1 - v/w up to w = e^60 v: the contacts break "
                      "faster at rest than the velocity loads them)");
  }
  for (int it = 0; it < 200 && b - a > 4e-16 * std::max(1.0, std::fabs(b)); ++it) {
    const double c = 0.5 * (a + b);
    if (!(c > a && c < b)) break;
    if (h(c) > 0.0) b = c;
    else a = c;
  }
  return std::exp(0.5 * (a + b) - lv) - 1.0;
}

double kinetic_slope(const ThermalSlider &s)
{
  const double h = 0.05;
  double F[4];
  const int k[4] = {-2, -1, 1, 2};
  for (int i = 0; i < 4; ++i) {
    ThermalSlider t = s;
    t.v = s.v * std::exp(k[i] * h);
    F[i] = thermal_steady_state(t).F;
  }
  return (8.0 * (F[2] - F[1]) - (F[3] - F[0])) / (12.0 * h);
}

std::vector<KineticPoint> kinetic_table(const ThermalSlider &s, double vlo, double vhi, int n)
{
  std::vector<KineticPoint> out;
  for (int i = 0; i < n; ++i) {
    ThermalSlider t = s;
    t.v = n > 1 ? vlo * std::pow(vhi / vlo, static_cast<double>(i) / (n - 1)) : vlo;
    const ThermalSteady ss = thermal_steady_state(t);
    out.push_back({t.v, ss.F, kinetic_slope(t), ss.attached, ss.Gamma});
  }
  return out;
}

/* ---------------------------------------------------------------------- */

void PiecewiseChebyshev::build(const std::function<double(double)> &f, double a, double b,
                               double tol, double min_width)
{
  const int n = DEGREE;
  std::vector<double> v(n + 1);
  for (int k = 0; k <= n; ++k) v[k] = f(0.5 * (a + b) + 0.5 * (b - a) * std::cos(PI * k / n));
  double tail = 0.0;
  for (int j = n - 1; j <= n; ++j) {
    double c = 0.0;
    for (int k = 0; k <= n; ++k) c += (k == 0 || k == n ? 0.5 : 1.0) * v[k] * std::cos(PI * j * k / n);
    tail = std::max(tail, std::fabs(c * (j == n ? 1.0 : 2.0) / n));
  }
  // the floor set by the nodes' own rounding: the test above takes the
  // values for f at the exact Chebyshev nodes, but they are f at the
  // nodes rounded to doubles, which differ by up to |f'| eps |x| / 2 and
  // put up to twice that into each coefficient.  Where f is steep the
  // test cannot see below 4 |f'| eps |x| (|f'| from the nodes'
  // differences), and without this floor the pieces were halved to the
  // smallest width (a kink of survival()'s h in x_s0 at the end of a
  // life with the prefactor u^q: slopes of 1e6, 36000 pieces per y).
  // Such a piece may miss tol pointwise (the interpolant uses the same
  // rounded nodes): it is narrow (f steep), and survival() only
  // integrates it (S(y) the same to the bit with and without the floor
  // at 72 (case, y) points of a review, stop 41)
  double slope = 0.0;
  for (int k = 0; k < n; ++k) {
    const double dx = 0.5 * (b - a) * (std::cos(PI * k / n) - std::cos(PI * (k + 1) / n));
    slope = std::max(slope, std::fabs(v[k] - v[k + 1]) / dx);
  }
  const double floor = 4.0 * slope * std::numeric_limits<double>::epsilon() *
      std::max(std::fabs(a), std::fabs(b));
  if (tail > std::max(tol, floor) && b - a > min_width) {
    const double m = 0.5 * (a + b);
    build(f, a, m, tol, min_width);
    build(f, m, b, tol, min_width);
    return;
  }
  lo.push_back(a);
  hi.push_back(b);
  values.push_back(v);
}

double PiecewiseChebyshev::interpolate(size_t i, double x) const
{
  const int n = DEGREE;
  const double a = lo[i], b = hi[i];
  double num = 0.0, den = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double xk = 0.5 * (a + b) + 0.5 * (b - a) * std::cos(PI * k / n);
    if (x == xk) return values[i][k];
    const double w = (k % 2 ? -1.0 : 1.0) * (k == 0 || k == n ? 0.5 : 1.0) / (x - xk);
    num += w * values[i][k];
    den += w;
  }
  return num / den;
}

double PiecewiseChebyshev::operator()(double x) const
{
  const size_t i = std::upper_bound(lo.begin(), lo.end(), x) - lo.begin();
  return interpolate(i > 0 ? i - 1 : 0, x);
}

SurvivalTable::SurvivalTable(const ContactLife &life_) :
    life(life_), direct(!(life_.params().theta > 0.0)), yend(life_.ymax())
{
  const std::vector<double> k = life.kinks();
  if (direct) {
    breaks.assign(k.begin(), k.end() - 1);
    return;
  }
  auto S = [&](double y) { return life.survival(y); };
  for (size_t i = 0; i + 1 < k.size(); ++i) {
    cheb.build(S, k[i], k[i + 1], TOLERANCE, 1e-12 * std::max(1.0, k.back()));
    // S is monotone: nothing left to tabulate once it is negligible
    if (cheb.last_value() < NEGLIGIBLE) {
      yend = cheb.end();
      break;
    }
  }
  breaks = cheb.starts();
}

double SurvivalTable::operator()(double y) const
{
  if (!(y > 0.0)) return 1.0;
  if (!(y < yend)) return 0.0;
  return direct ? life.survival(y) : cheb(y);
}

void SurvivalTable::cell_moments(double a, double b, double r0, double m[4]) const
{
  for (int p = 0; p < 4; ++p) m[p] = 0.0;
  const double width = b - a;
  b = std::min(b, yend);
  if (!(b > a)) return;
  // split at the pieces' ends inside [a, b]
  std::vector<double> pts{a};
  for (size_t i = std::upper_bound(breaks.begin(), breaks.end(), a) - breaks.begin();
       i < breaks.size() && breaks[i] < b; ++i)
    pts.push_back(breaks[i]);
  pts.push_back(b);
  const GaussRule &g = gauss12();
  for (size_t s = 0; s + 1 < pts.size(); ++s) {
    const double c = 0.5 * (pts[s] + pts[s + 1]), h = 0.5 * (pts[s + 1] - pts[s]);
    for (int i = 0; i < g.n; ++i) {
      const double y = c + h * g.t[i], x = r0 + y, w = h * g.w[i] * (*this)(y);
      m[0] += w;
      m[1] += w * x;
      m[2] += w * x * x;
      m[3] += w * x * x * x;
    }
  }
  for (int p = 0; p < 4; ++p) m[p] /= width;
}

/* ---------------------------------------------------------------------- */

namespace {

// cell-to-cell kernel of the re-formation delay: a break spread uniformly
// over cell k re-forms in cell k + n with probability g[n]; an
// exponential tail beyond g is geometric (factor q per cell, weight tail
// in the first cell beyond g)
struct DelayKernel {
  std::vector<double> g;
  double tail = 0.0, q = 0.0;
};

// (a fixed delay of cells_max cells or more re-forms nothing within the
// cells_max - 1 cells of the window: the kernel is cut there)
DelayKernel delay_kernel(const ThermalSlider &s, double dx, long cells_max)
{
  DelayKernel d;
  const double len = s.delay_length();
  if (!(len > 0.0)) {
    d.g = {1.0};
  } else if (s.spec.delay == DelayKind::FIXED && !(len / dx < static_cast<double>(cells_max))) {
    d.g = {0.0};
  } else if (s.spec.delay == DelayKind::FIXED) {
    const double cells = len / dx;
    const long n0 = static_cast<long>(std::floor(cells));
    const double f = cells - n0;
    d.g.assign(n0 + 2, 0.0);
    d.g[n0] = 1.0 - f;
    d.g[n0 + 1] = f;
  } else {
    // g0 = 1 - (1 - e^-h)/h, g_n = e^-(n-1)h (1 - e^-h)^2 / h (n >= 1), h = dx/len
    const double h = dx / len, em = -std::expm1(-h);
    const double g0 = h < 1e-3 ? h / 2.0 - h * h / 6.0 + h * h * h / 24.0 : 1.0 - em / h;
    d.g = {g0};
    d.tail = em * em / h;
    d.q = std::exp(-h);
  }
  return d;
}

// the kernels of later lives: alive at a node m cells after the cell of
// re-formation (S[m]) and the moments (r0 + y)^p there (V[p][m]);
// breaks m cells later: W[m] = S[m] - S[m+1]
struct LifeKernels {
  std::vector<double> S, W;
  std::vector<double> V[4];
};

LifeKernels life_kernels(const SurvivalTable &table, double r0, double dx, long cells)
{
  LifeKernels k;
  k.S.assign(cells + 2, 0.0);
  for (int p = 0; p < 4; ++p) k.V[p].assign(cells + 2, 0.0);
  k.S[0] = 1.0;
  for (long m = 1; m <= cells; ++m) {
    double mom[4];
    table.cell_moments((m - 1) * dx, m * dx, r0, mom);
    k.S[m] = mom[0];
    for (int p = 1; p < 4; ++p) k.V[p][m] = mom[p];
  }
  k.W.assign(cells + 1, 0.0);
  for (long m = 0; m <= cells; ++m) k.W[m] = k.S[m] - k.S[m + 1];
  return k;
}

// the moments of one contact's stretch at a node (detached: x = 0)
void push_moments(MEResult &r, const double m[4])
{
  const double mean = m[1], var = std::max(0.0, m[2] - mean * mean);
  r.F.push_back(mean);
  r.sd.push_back(std::sqrt(var));
  const double c3 = m[3] - 3.0 * mean * m[2] + 2.0 * mean * mean * mean;
  r.skew.push_back(var > 0.0 ? c3 / (var * std::sqrt(var)) : 0.0);
  r.attached.push_back(m[0]);
}

// sum_{q=1}^{n} past[-q] kernel[q] for the kernels S, V1, V2, V3, W (in
// this order): what the re-formations of the n cells before a node
// contribute there (one pass over past)
void convolve(const double *past, const LifeKernels &K, long n, double sums[5])
{
  const double *k0 = K.S.data(), *k1 = K.V[1].data(), *k2 = K.V[2].data(), *k3 = K.V[3].data(),
               *kw = K.W.data();
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0, s4 = 0.0;
  for (long q = 1; q <= n; ++q) {
    const double r = past[-q];
    s0 += r * k0[q];
    s1 += r * k1[q];
    s2 += r * k2[q];
    s3 += r * k3[q];
    s4 += r * kw[q];
  }
  sums[0] = s0;
  sums[1] = s1;
  sums[2] = s2;
  sums[3] = s3;
  sums[4] = s4;
}

}    // namespace

double thermal_kernel_cells(const ThermalSlider &s, double dx)
{
  if (!s.reform) return 0.0;
  return std::ceil(ContactLife(s, s.r0, 0.0).ymax() / dx);
}

ThermalTransient::ThermalTransient(const ThermalSlider &s) : slider(s)
{
  if (s.reform) S = std::make_shared<const SurvivalTable>(ContactLife(s, s.r0, 0.0));
  const bool same = S && s.start == s.r0 && !(s.spec.rest > 0.0);
  S1 = same ? S : std::make_shared<const SurvivalTable>(ContactLife(s, s.start, s.spec.rest));
}

MEResult ThermalTransient::solve(double dx, double Xmax) const
{
  const ThermalSlider &s = slider;
  const long N = std::lround(Xmax / dx);
  LifeKernels K;
  long cells = 0;
  if (S) {
    cells = std::min<long>(N, static_cast<long>(std::ceil(S->end() / dx)));
    K = life_kernels(*S, s.r0, dx, cells);
  }
  const DelayKernel D = delay_kernel(s, dx, N + 1);
  const double G0 = D.g[0], W0 = S ? K.W[0] : 0.0;
  // 1 - W0 G0 without its cancellation: W0 = 1 - S1 (S1: alive a cell
  // after re-forming), and where lives are far shorter than a cell S1 is
  // small and 1 - W0 kept only the digits S1 has above 1e-16: the
  // attached fraction drifted by 8e-13 per cell, F(X) by 5e-16/<L>
  // (lives of 4e-8: 1.4e-8 at X = 8)
  const double denom = S ? (1.0 - G0) + G0 * K.S[1] : 1.0;

  MEResult r;
  r.dx = dx;
  std::vector<double> b(N, 0.0), rf(N, 0.0);    // breaks, re-formations per cell
  double acc = 0.0, broken = 0.0, reformed = 0.0;
  for (long j = 0; j <= N; ++j) {
    // node j: the first life and the re-formations of cells j-m (m >= 1)
    const double X = j * dx, a1j = (*S1)(X), x1 = s.start + X;
    double m[4] = {a1j, x1 * a1j, x1 * x1 * a1j, x1 * x1 * x1 * a1j};
    const long qn = std::min(j, cells);
    double sums[5];
    convolve(rf.data() + j, K, qn, sums);
    for (int p = 0; p < 4; ++p) m[p] += sums[p];
    r.X.push_back(X);
    push_moments(r, m);
    r.Gamma.push_back(j > 0 ? b[j - 1] / dx : 0.0);
    r.max_mass_error = std::max(r.max_mass_error, std::fabs(m[0] + broken - reformed - 1.0));
    if (j == N) break;
    // cell j: breaks B from what is there, re-formations R from earlier
    // breaks; b = B + W0 r and r = R + G0 b within the cell
    double B = a1j - (*S1)(X + dx) + sums[4], R = 0.0;
    if (S) {
      for (size_t q = 1; q < D.g.size() && static_cast<long>(q) <= j; ++q) R += b[j - q] * D.g[q];
      R += D.tail * acc;
      b[j] = (B + W0 * R) / denom;
      rf[j] = R + G0 * b[j];
      acc = acc * D.q + b[j];
    } else {
      b[j] = B;
    }
    broken += b[j];
    reformed += rf[j];
  }
  return r;
}

MEResult ThermalTransient::solve(double dx, double Xmax, bool richardson) const
{
  MEResult res = solve(dx, Xmax);
  if (!richardson) return res;
  const MEResult fine = solve(0.5 * dx, Xmax);
  if (!combine_richardson(res, fine))
    throw SpecError("richardson: xmax is not a whole number of steps dx");
  res.max_mass_error = std::max(res.max_mass_error, fine.max_mass_error);
  return res;
}

MEResult thermal_transient(const ThermalSlider &s, double dx, double Xmax, bool richardson)
{
  return ThermalTransient(s).solve(dx, Xmax, richardson);
}

}    // namespace feq
