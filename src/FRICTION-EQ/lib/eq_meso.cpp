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
   FRICTION-EQ package: far-zone lambda_c-block kernel (see eq_meso.h)
------------------------------------------------------------------------- */

#include "eq_meso.h"
#include "eq_text.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace feq {

namespace {

const double TAIL = 1e-17;      // J_c below which an unbounded P_c is cut (as the ME solver)
const int TABLE_REFINE = 4;     // table spacing du / TABLE_REFINE
const long REBASE = 1024;       // cells between rebases

// block state layout
enum Slot {
  TAG,         // model fingerprint
  XABS,        // X, exactly as passed
  HABS,        // H = max X so far
  BASE,        // integer base index b: positions are stored as (. - b du)
  GH,          // cell of H: p_GH <= H < p_GH+1, p_g = (g - b) du
  JLO,         // lowest / highest anchor index that may carry mass
  JHI,         //   (empty when JLO > JHI)
  MSUM,        // sum of the grid masses
  S1SUM,       // sum m_j (j - b)
  HMSUM,       // held mass
  HS1SUM,      // sum over held mass of (anchor index - b)
  DETACHED,    // broken for good (R null)
  LASTB,       // broken mass of the last move
  LASTDX,      // X1 - X of the last move
  NHEAD = 16
};

// j mod n in [0, n) without an integer division (|j| < 2^52)
inline long wrap(long j, long n, double inv_n)
{
  long r = j - n * static_cast<long>(std::floor(double(j) * inv_n));
  if (r < 0) r += n;
  else if (r >= n) r -= n;
  return r;
}

inline double clamp(double x, double lo, double hi)
{
  return x < lo ? lo : (x > hi ? hi : x);
}

std::string fmt(double v) { return format_number(v, 6); }

// v rounded up to 4 significant digits (an "allowed value" that is allowed)
double round_up4(double v)
{
  if (!(v > 0.0) || !std::isfinite(v)) return v;
  const double p = std::pow(10.0, std::floor(std::log10(v)) - 3.0);
  return std::ceil(v / p * (1.0 - 1e-12)) * p;
}
double round_down4(double v)
{
  if (!(v > 0.0) || !std::isfinite(v)) return v;
  const double p = std::pow(10.0, std::floor(std::log10(v)) - 3.0);
  return std::floor(v / p * (1.0 + 1e-12)) * p;
}

// one interval of the table of J: the cubic through f0..f3 at y0 + q dy/3,
// q = 0..3 (c[0..3]), and the quartic of its integral G from the node value
// gnode (c[4..8]); gnode moves on to the end of the interval
void fit_interval(double *c, double f0, double f1, double f2, double f3, double dy, double &gnode)
{
  const double d1 = f1 - f0, d2 = f2 - 2.0 * f1 + f0, d3 = f3 - 3.0 * f2 + 3.0 * f1 - f0;
  const double h = dy / 3.0;
  c[0] = f0;
  c[1] = (d1 - 0.5 * d2 + d3 / 3.0) / h;
  c[2] = (0.5 * d2 - 0.5 * d3) / (h * h);
  c[3] = (d3 / 6.0) / (h * h * h);
  c[4] = gnode;
  c[5] = c[0];
  c[6] = c[1] / 2.0;
  c[7] = c[2] / 3.0;
  c[8] = c[3] / 4.0;
  gnode += dy * (c[5] + dy * (c[6] + dy * (c[7] + dy * c[8])));
}

}    // namespace

/* ---------------------------------------------------------------------- */

double meso_default_grid(const Distribution &Pc, double pi0)
{
  if (!(pi0 >= 0.0 && pi0 < 1.0))
    throw std::invalid_argument("meso_default_grid: Pi0 must be in [0, 1), got " + fmt(pi0));
  return MESO_GRID_DEFAULT_SD * std::sqrt(std::max(0.0, Pc.variance())) * (1.0 - pi0);
}

double meso_min_window(const Distribution &Pc)
{
  const double xc = Pc.mean(), sd = std::sqrt(std::max(0.0, Pc.variance()));
  if (!(sd > 0.0)) return std::numeric_limits<double>::infinity();
  return MESO_WINDOW_COEFF * xc * (xc / sd) * (xc / sd);
}

std::unique_ptr<MesoModel> MesoModel::regrid(double du_new) const
{
  return std::unique_ptr<MesoModel>(new MesoModel(Pc, R, du_new, crossing, start));
}

double MesoModel::max_grid(const Distribution &Pc)
{
  const double var = Pc.variance();
  return MESO_GRID_SD_FRACTION * std::sqrt(std::max(0.0, var));
}

MesoModel::MesoModel(DistributionPtr Pc_, DistributionPtr R_, double du_, Crossing crossing_,
                     MEStart start_) :
    Pc(std::move(Pc_)), R(std::move(R_)), du(du_), inv_du(1.0 / du_), crossing(crossing_),
    start(start_)
{
  check_inputs();
  ylow = std::max(0.0, Pc->lower());
  ytop = std::isfinite(Pc->upper()) ? Pc->upper() : Pc->isf(TAIL);
  set_reform_support();
  if (width_bound(du) > double(MESO_MAX_WIDTH))
    throw GridError("grid: spacing " + fmt(du) + " needs about " + fmt(width_bound(du)) +
                    " doubles per block (limit " + std::to_string(MESO_MAX_WIDTH) +
                    "); use a spacing >= " + fmt(min_grid()));
  set_reform_lines();
  set_state_layout();
  set_survival_table();
}

// the thresholds, the grid spacing against them, R and the start
void MesoModel::check_inputs() const
{
  if (!Pc) throw SpecError("threshold: missing threshold distribution");
  if (!(Pc->lower() >= 0.0))
    throw SpecError("threshold " + Pc->describe() + ": breaking thresholds must be >= 0");
  if (!(du > 0.0) || !std::isfinite(du))
    throw GridError("grid: spacing must be a finite number > 0 (got " + fmt(du) + ")");
  const double sd = std::sqrt(std::max(0.0, Pc->variance()));
  if (!(sd > 0.0))
    throw GridError("grid: threshold " + Pc->describe() +
                    " has zero width; the anchor grid needs a spread of thresholds");
  const double dmax = max_grid(*Pc);
  if (du > dmax)
    throw GridError("grid: spacing " + fmt(du) + " is too coarse for threshold " + Pc->describe() +
                    " (sd " + fmt(sd) + "); the largest allowed value is " +
                    fmt(round_down4(dmax)) + " (" + fmt(MESO_GRID_SD_FRACTION) + " sd)");
  if (R) check_reform(*Pc, {R, R->describe()});
  if (start == MEStart::REFORM && !R)
    throw SpecError("start: 'reform' needs a reform distribution (reform none given); allowed: "
                    "relaxed");
}

// support of R (cut at TAIL like the ME solver; 0 when R null), needed by
// the width check before anything of the grid's size is allocated
void MesoModel::set_reform_support()
{
  rsup_lo = rsup_hi = 0.0;
  if (!R) return;
  rsup_lo = R->is_point() ? R->mean() : R->lower();
  rsup_hi = R->is_point() ? R->mean() : R->upper();
  if (!std::isfinite(rsup_lo)) rsup_lo = R->quantile(TAIL);
  if (!std::isfinite(rsup_hi)) rsup_hi = R->isf(TAIL);
}

// R on the grid r_k = k du, hat weights (mass and mean exact), as in the
// master-equation solver: (k, weight) pairs, not yet normalised
std::vector<std::pair<long, double>> MesoModel::reform_weights() const
{
  std::vector<std::pair<long, double>> w;
  if (R->is_point()) {
    const double f = R->mean() * inv_du;
    const long k = static_cast<long>(std::floor(f));
    const double t = f - double(k);
    w.push_back({k, 1.0 - t});
    w.push_back({k + 1, t});
    return w;
  }
  const long klo = static_cast<long>(std::floor(rsup_lo * inv_du));
  const long khi = static_cast<long>(std::ceil(rsup_hi * inv_du));
  std::vector<double> wk(khi - klo + 2, 0.0);
  for (long k = klo; k <= khi; ++k) {
    const double a = double(k) * du, b = double(k + 1) * du;
    const double mass = R->cdf(b) - R->cdf(a);
    if (!(mass > 0.0)) continue;
    const double m1 = R->partial_mean(a, b);
    const double right = std::min(mass, std::max(0.0, (m1 - a * mass) * inv_du));
    wk[k - klo] += mass - right;
    wk[k - klo + 1] += right;
  }
  for (size_t i = 0; i < wk.size(); ++i) w.push_back({klo + long(i), wk[i]});
  return w;
}

// the normalised grid lines of R: r >= 0 re-form onto the grid (lines),
// r < 0 are held (hlines, hold_w, hold_wc)
void MesoModel::set_reform_lines()
{
  if (!R) return;
  const std::vector<std::pair<long, double>> w = reform_weights();
  double sum = 0.0;
  for (auto &p : w) sum += p.second;
  for (auto &p : w) {
    if (!(p.second > 0.0)) continue;
    const Line L{p.first, p.second / sum};
    if (L.k < 0) {
      hlines.push_back(L);
      hold_w += L.w;
      hold_wc += L.w * double(-L.k);
    } else {
      lines.push_back(L);
    }
  }
}

// sizes of the block state: anchors, held records, width and tag
void MesoModel::set_state_layout()
{
  kheld = 0;
  long kmax = 0;
  for (const Line &L : hlines) kheld = std::max(kheld, int(-L.k));
  for (const Line &L : lines) kmax = std::max(kmax, L.k);

  nt = std::max(static_cast<long>(std::ceil(ytop * inv_du)), kmax + 1);
  nt = std::max(nt, 1L);
  ncap = int(nt) + 4;
  nrec = kheld > 0 ? 2 * kheld + 2 : 0;
  inv_ncap = 1.0 / ncap;
  inv_nrec = nrec > 0 ? 1.0 / nrec : 0.0;
  nwidth = NHEAD + ncap + 2 * nrec;
  tag = 7.0e9 + double(nwidth) + 1e-3 * double(kheld);
}

// table of J and G on y_i = i dy (see the header comment), and G(ytop)
void MesoModel::set_survival_table()
{
  dy = du / TABLE_REFINE;
  inv_dy = 1.0 / dy;
  ntab = static_cast<long>(std::ceil(ytop * inv_dy)) + 1;
  tab.assign(9 * ntab, 0.0);
  exact.assign(ntab, 0);
  std::vector<double> kinks = Pc->breakpoints();
  kinks.push_back(ytop);
  double gnode = 0.0;
  auto Jx = [&](double y) { return y >= ytop ? 0.0 : Pc->sf(y); };
  for (long i = 0; i < ntab; ++i) {
    const double y0 = double(i) * dy, tol = 1e-9 * dy;
    bool kink = false;
    for (double b : kinks)
      if (b > y0 + tol && b < y0 + dy - tol) kink = true;
    double *c = &tab[9 * i];
    if (kink) {
      exact[i] = 1;
      c[4] = gnode;
      gnode += Pc->sf_integral(y0, std::min(y0 + dy, ytop));
      continue;
    }
    // cubic through the exact values at y0 + q dy/3, q = 0..3
    const double f0 = Jx(y0), f1 = Jx(y0 + dy / 3.0), f2 = Jx(y0 + 2.0 * dy / 3.0),
                 f3 = Jx(y0 + dy);
    fit_interval(c, f0, f1, f2, f3, dy, gnode);
  }
  double jt;
  gtop = 0.0;
  lookup(std::nextafter(ytop, 0.0), jt, gtop);
}

// upper bound of width() for spacing d (the exact width depends on the
// hat weights of R on the grid; each term here bounds its counterpart)
double MesoModel::width_bound(double d) const
{
  const double nt_ = std::max(std::ceil(ytop / d), std::ceil(std::max(rsup_hi, 0.0) / d) + 2.0);
  const double k_ = rsup_lo < 0.0 ? std::ceil(-rsup_lo / d) + 1.0 : 0.0;
  return double(NHEAD) + nt_ + 5.0 + (k_ > 0.0 ? 2.0 * (2.0 * k_ + 2.0) : 0.0);
}

double MesoModel::min_grid() const
{
  const double span = ytop + 4.0 * std::max(0.0, -rsup_lo);
  double d = span / (double(MESO_MAX_WIDTH) - NHEAD - 20.0);
  while (width_bound(d) > double(MESO_MAX_WIDTH)) d *= 1.0001;
  d = round_up4(d);
  while (width_bound(d) > double(MESO_MAX_WIDTH)) d = round_up4(d * 1.001);
  return d;
}

/* ---------------------------------------------------------------------- */

inline void MesoModel::lookup(double y, double &Jv, double &Gv) const
{
  if (y <= ylow) {
    Jv = 1.0;
    Gv = y;
    return;
  }
  if (y >= ytop) {
    Jv = 0.0;
    Gv = gtop;
    return;
  }
  long i = static_cast<long>(y * inv_dy);
  if (i >= ntab) i = ntab - 1;
  const double *c = &tab[9 * i];
  const double y0 = double(i) * dy;
  if (exact[i]) {
    Jv = Pc->sf(y);
    Gv = c[4] + Pc->sf_integral(y0, y);
    return;
  }
  const double t = y - y0;
  Jv = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
  Gv = c[4] + t * (c[5] + t * (c[6] + t * (c[7] + t * c[8])));
}

inline double MesoModel::J(double y) const
{
  if (y <= ylow) return 1.0;
  if (y >= ytop) return 0.0;
  long i = static_cast<long>(y * inv_dy);
  if (i >= ntab) i = ntab - 1;
  if (exact[i]) return Pc->sf(y);
  const double *c = &tab[9 * i];
  const double t = y - double(i) * dy;
  return c[0] + t * (c[1] + t * (c[2] + t * c[3]));
}

double MesoModel::survival(double y) const
{
  return J(y);
}

/* ---------------------------------------------------------------------- */

// the anchor range [JLO, JHI] grows to include [lo, hi]
void MesoModel::extend(double *s, long lo, long hi) const
{
  long jlo = static_cast<long>(s[JLO]), jhi = static_cast<long>(s[JHI]);
  if (jlo > jhi) {
    jlo = lo;
    jhi = hi;
  } else {
    jlo = std::min(jlo, lo);
    jhi = std::max(jhi, hi);
  }
  if (jhi - jlo >= ncap) throw std::logic_error("eq/meso: anchor ring overflow");
  s[JLO] = double(jlo);
  s[JHI] = double(jhi);
}

void MesoModel::add_main(double *s, long j, long base, double v) const
{
  if (v == 0.0) return;
  extend(s, j, j);
  s[NHEAD + wrap(j, ncap, inv_ncap)] += v;
  s[MSUM] += v;
  s[S1SUM] += v * double(j - base);
}

void MesoModel::add_record(double *s, long g, long base, double lo, double up) const
{
  double *rec = s + NHEAD + ncap + 2 * wrap(g, nrec, inv_nrec);
  rec[0] += lo;
  rec[1] += up;
  s[HMSUM] += hold_w * (lo + up);
  s[HS1SUM] += hold_w * (lo * double(g - base) + up * double(g + 1 - base)) + hold_wc * (lo + up);
}

// H reaches the grid point p_G: held contacts whose stretch reaches |r|
// join the grid; the record slot of cell G is recycled
void MesoModel::cross(double *s, long G, long base) const
{
  if (nrec == 0) return;
  // held lines sorted by k ascending: c = -k descending, anchors G - c
  // ascending, one contiguous range
  extend(s, G + hlines.front().k, G + hlines.back().k);
  const double *recs = s + NHEAD + ncap;
  double *ring = s + NHEAD;
  double out = 0.0, out1 = 0.0;
  for (const Line &L : hlines) {
    const long c = -L.k;
    const double lo = recs[2 * wrap(G - 2 * c, nrec, inv_nrec)];
    const double up = recs[2 * wrap(G - 2 * c - 1, nrec, inv_nrec) + 1];
    const double v = L.w * (lo + up);
    if (v == 0.0) continue;
    ring[wrap(G - c, ncap, inv_ncap)] += v;
    out += v;
    out1 += v * double(G - c - base);
  }
  s[MSUM] += out;
  s[S1SUM] += out1;
  s[HMSUM] -= out;
  s[HS1SUM] -= out1;
  double *rec = s + NHEAD + ncap + 2 * wrap(G, nrec, inv_nrec);
  rec[0] = rec[1] = 0.0;
}

// held mass (and sum of (anchor - base) over it) from the records
double MesoModel::held_mass(const double *s, double *s1, long base) const
{
  double hm = 0.0, h1 = 0.0;
  if (nrec > 0) {
    const long g = static_cast<long>(s[GH]);
    const double *recs = s + NHEAD + ncap;
    for (long gc = g - 2 * kheld - 1; gc <= g; ++gc) {
      const long sl = wrap(gc, nrec, inv_nrec);
      const double lo = recs[2 * sl], up = recs[2 * sl + 1];
      if (lo == 0.0 && up == 0.0) continue;
      for (const Line &L : hlines) {
        const long c = -L.k;
        if (g < gc + 2 * c && lo != 0.0) {
          hm += L.w * lo;
          h1 += L.w * lo * double(gc + c - base);
        }
        if (g < gc + 2 * c + 1 && up != 0.0) {
          hm += L.w * up;
          h1 += L.w * up * double(gc + c + 1 - base);
        }
      }
    }
  }
  if (s1) *s1 = h1;
  return hm;
}

void MesoModel::rebase(double *s) const
{
  const long base = static_cast<long>(s[GH]);
  const long jlo = static_cast<long>(s[JLO]), jhi = static_cast<long>(s[JHI]);
  double M = 0.0, S1 = 0.0;
  for (long j = jlo; j <= jhi; ++j) {
    const double m = s[NHEAD + wrap(j, ncap, inv_ncap)];
    M += m;
    S1 += m * double(j - base);
  }
  s[MSUM] = M;
  s[S1SUM] = S1;
  double h1 = 0.0;
  s[HMSUM] = held_mass(s, &h1, base);
  s[HS1SUM] = h1;
  s[BASE] = double(base);
}

/* ---------------------------------------------------------------------- */

void MesoModel::init(double *s, double X0) const
{
  if (!std::isfinite(X0) || std::fabs(X0) * inv_du > 4e15)
    throw std::invalid_argument("eq/meso: block displacement " + fmt(X0) +
                                " is not finite or too large for the anchor grid");
  std::fill(s, s + nwidth, 0.0);
  s[TAG] = tag;
  s[XABS] = s[HABS] = X0;
  long base = static_cast<long>(std::floor(X0 * inv_du));
  double xr = std::fma(-double(base), du, X0);
  while (xr < 0.0) xr = std::fma(-double(--base), du, X0);
  while (xr >= du) xr = std::fma(-double(++base), du, X0);
  s[BASE] = s[GH] = double(base);
  s[JLO] = double(base + 1);
  s[JHI] = double(base);
  const double lam = clamp(xr * inv_du, 0.0, 1.0);
  if (start == MEStart::RELAXED || !R) {
    const double lo = 1.0 - lam;
    add_main(s, base, base, lo);
    add_main(s, base + 1, base, 1.0 - lo);
  } else {
    for (const Line &L : lines) {
      const double lo = L.w * (1.0 - lam);
      add_main(s, base - L.k, base, lo);
      add_main(s, base - L.k + 1, base, L.w - lo);
    }
    if (nrec > 0) add_record(s, base, base, 1.0 - lam, lam);
  }
}

// a state of this model: its fingerprint, finite values, whole-number
// indices within range, masses in [0, 1] that add up to 1
bool MesoModel::valid(const double *s) const
{
  if (s[TAG] != tag) return false;
  for (int k = 0; k < nwidth; ++k)
    if (!std::isfinite(s[k])) return false;
  const double big = 4503599627370496.0;    // 2^52: the index slots stay exact
  for (const int k : {BASE, GH, JLO, JHI})
    if (!(std::fabs(s[k]) <= big) || s[k] != std::floor(s[k])) return false;
  if (s[JLO] <= s[JHI] && !(s[JHI] - s[JLO] < double(ncap))) return false;
  if (!(s[HABS] >= s[XABS])) return false;
  const double tol = 1e-9;
  for (int i = 0; i < ncap; ++i)
    if (!(s[NHEAD + i] >= 0.0 && s[NHEAD + i] <= 1.0 + tol)) return false;
  if (!(s[DETACHED] >= 0.0 && s[DETACHED] <= 1.0 + tol)) return false;
  return normalization_error(s) <= tol;
}

/* ---------------------------------------------------------------------- */

// breaks over the sub-step [hr, end] inside cell g (positions relative to
// the base): survival exact per anchor; B = broken mass, W = sum of
// broken mass * remaining displacement after the break
void MesoModel::pass(double *s, long g, long base, double hr, double end, double a, double &B,
                     double &W) const
{
  B = W = 0.0;
  long jlo = static_cast<long>(s[JLO]);
  const long jhi = static_cast<long>(s[JHI]);
  if (jlo > jhi) return;
  const double h = end - hr;
  double *ring = s + NHEAD;
  double bsum = 0.0, b1 = 0.0, wsum = 0.0;
  // anchors stretched beyond the top at the cell start: all break (their
  // mass is already 0 for eps >= 0: a guard for the ring, never active)
  const long jforce = g - nt;
  long j = jlo;
  for (; j <= jhi && j <= jforce; ++j) {
    double &m = ring[wrap(j, ncap, inv_ncap)];
    if (m == 0.0) continue;
    bsum += m;
    b1 += m * double(j - base);
    wsum += m * h;
    m = 0.0;
  }
  // locals: the stores into the ring (double) could otherwise alias the
  // model's members and force reloads in the loop
  const double ddu = du, lowy = ylow, topy = ytop, gt = gtop, idy = inv_dy, ddy = dy;
  const long nc = ncap, ntb = ntab;
  const double *tb = tab.data();
  const unsigned char *ex = exact.data();
  auto look = [&](double y, double &Jv, double &Gv) {
    if (y <= lowy) {
      Jv = 1.0;
      Gv = y;
    } else if (y >= topy) {
      Jv = 0.0;
      Gv = gt;
    } else {
      long i = static_cast<long>(y * idy);
      if (i >= ntb) i = ntb - 1;
      const double *c = tb + 9 * i;
      const double y0 = double(i) * ddy;
      if (ex[i]) {
        Jv = Pc->sf(y);
        Gv = c[4] + Pc->sf_integral(y0, y);
      } else {
        const double t = y - y0;
        Jv = c[0] + t * (c[1] + t * (c[2] + t * c[3]));
        Gv = c[4] + t * (c[5] + t * (c[6] + t * (c[7] + t * c[8])));
      }
    }
  };
  long slot = wrap(j, nc, inv_ncap);
  for (; j <= jhi; ++j, slot = (slot + 1 == nc ? 0 : slot + 1)) {
    const double A = double(j - base) * ddu;
    const double y1 = a * (end - A);
    if (y1 <= lowy) break;    // stretch decreases with j: nothing breaks beyond
    const double m = ring[slot];
    if (m == 0.0) continue;
    double J0, G0, J1, G1;
    look(a * (hr - A), J0, G0);
    look(y1, J1, G1);
    double b, wr;
    if (!(J0 > 0.0)) {
      b = m;
      wr = m * h;
    } else {
      const double q = 1.0 / (a * J0);    // one division per anchor
      const double f = std::min(1.0, std::max(0.0, (J0 - J1) * (a * q)));
      b = m * f;
      // int_{s0}^{s1} (1 - J(a s)/J(a s0)) ds = h - (G(y1) - G(y0)) / (a J0)
      const double in = std::min(h * f, std::max(0.0, h - (G1 - G0) * q));
      wr = m * in;
    }
    ring[slot] = m - b;
    bsum += b;
    b1 += b * double(j - base);
    wsum += wr;
  }
  s[MSUM] -= bsum;
  s[S1SUM] -= b1;
  while (jlo <= jhi && ring[wrap(jlo, ncap, inv_ncap)] == 0.0) ++jlo;
  s[JLO] = double(jlo);
  B = bsum;
  W = wsum;
}

// broken mass B of a sub-step ending at `end` in cell g re-forms with mean
// remaining displacement rho; returns the mass broken including re-breaks
double MesoModel::reinject(double *s, long g, long base, double end, double rho, double B,
                           double a) const
{
  const double pg = double(g - base) * du;
  const double lam = clamp((end - rho - pg) * inv_du, 0.0, 1.0);
  double B2 = 0.0;
  if (!lines.empty()) {
    // the lines are sorted by k: anchors g - k (lower) and g - k + 1 (upper)
    // form one contiguous range
    extend(s, g - lines.back().k, g - lines.front().k + 1);
    double *ring = s + NHEAD;
    const double ddu = du, lowy = ylow;
    double dm = 0.0, ds1 = 0.0;
    for (const Line &L : lines) {
      const double v = B * L.w;
      double keep = v;
      if (rho > 0.0) {
        // re-break within the rest of the sub-step: 1 - J(a(r+rho))/J(a r)
        const double r = double(L.k) * ddu;
        const double y1 = a * (r + rho);
        if (y1 > lowy) {
          const double J0 = J(a * r), J1 = J(y1);
          keep = J0 > 0.0 ? v * clamp(J1 / J0, 0.0, 1.0) : 0.0;
        }
      }
      B2 += v - keep;
      const long j = g - L.k;
      const double lo = keep * (1.0 - lam), up = keep - lo;
      const long sl = wrap(j, ncap, inv_ncap);
      ring[sl] += lo;
      ring[sl + 1 == ncap ? 0 : sl + 1] += up;
      dm += keep;
      ds1 += keep * double(j - base) + up;
    }
    if (B2 > 0.0) {
      // second generation: breaks spread evenly over the rest of the
      // sub-step leave 2/3 of the mean remaining displacement; its own
      // re-breaks are O(du^3) per sub-step and are not taken
      const double lam2 = clamp((end - 2.0 * rho / 3.0 - pg) * inv_du, 0.0, 1.0);
      for (const Line &L : lines) {
        const double v = B2 * L.w, lo = v * (1.0 - lam2), up = v - lo;
        const long j = g - L.k;
        const long sl = wrap(j, ncap, inv_ncap);
        ring[sl] += lo;
        ring[sl + 1 == ncap ? 0 : sl + 1] += up;
        dm += v;
        ds1 += v * double(j - base) + up;
      }
    }
    s[MSUM] += dm;
    s[S1SUM] += ds1;
  }
  if (nrec > 0) {
    const double lo = B * (1.0 - lam);
    add_record(s, g, base, lo, B - lo);
    if (B2 > 0.0) {
      const double lo2 = B2 * (1.0 - clamp((end - 2.0 * rho / 3.0 - pg) * inv_du, 0.0, 1.0));
      add_record(s, g, base, lo2, B2 - lo2);
    }
  }
  return B + B2;
}

double MesoModel::forward(double *s, double X1, double eps) const
{
  const double a = 1.0 + eps;
  const long base = static_cast<long>(s[BASE]);
  long g = static_cast<long>(s[GH]);
  double hr = std::fma(-double(base), du, s[HABS]);
  const double x1r = std::fma(-double(base), du, X1);
  double total = 0.0, pending = 0.0;
  for (;;) {
    const double pn = double(g + 1 - base) * du;
    const bool crossing_point = !(x1r < pn);
    const double end = crossing_point ? pn : x1r;
    if (end > hr) {
      double B, W;
      pass(s, g, base, hr, end, a, B, W);
      if (B > 0.0) {
        if (!R) {
          s[DETACHED] += B;
          total += B;
        } else if (crossing == Crossing::STEP) {
          pending += B;
        } else {
          const double rho = clamp(W / B, 0.0, end - hr);
          total += reinject(s, g, base, end, rho, B, a);
        }
      }
      hr = end;
    }
    if (!crossing_point) break;
    ++g;
    cross(s, g, base);
    if (!(x1r > pn)) break;    // X1 exactly on the grid point
  }
  // step crossing: every break of the move re-forms at X1 (no re-breaks)
  if (pending > 0.0) total += reinject(s, g, base, x1r, 0.0, pending, a);
  s[GH] = double(g);
  s[HABS] = X1;
  if (g - base >= REBASE) rebase(s);
  return total;
}

double MesoModel::advance(double *s, double X1, double eps) const
{
  const double X0 = s[XABS];
  if (X1 == X0) return 0.0;
  if (!std::isfinite(X1) || std::fabs(X1) * inv_du > 4e15)
    throw std::invalid_argument("eq/meso: block displacement " + fmt(X1) +
                                " is not finite or too large for the anchor grid");
  if (!(eps >= 0.0) || !std::isfinite(eps))
    throw std::invalid_argument("eq/meso: screening factor eps = " + fmt(eps) +
                                " (need a finite eps >= 0)");
  double brk = 0.0;
  if (X1 > s[HABS]) brk = forward(s, X1, eps);
  s[XABS] = X1;
  s[LASTB] = brk;
  s[LASTDX] = X1 - X0;
  return brk;
}

/* ---------------------------------------------------------------------- */

double MesoModel::position(const double *s) const
{
  return s[XABS];
}

double MesoModel::high_water(const double *s) const
{
  return s[HABS];
}

double MesoModel::mean_stretch(const double *s) const
{
  const double xr = std::fma(-s[BASE], du, s[XABS]);
  return xr * (s[MSUM] + s[HMSUM]) - du * (s[S1SUM] + s[HS1SUM]);
}

double MesoModel::attached(const double *s) const
{
  return s[MSUM] + s[HMSUM];
}

double MesoModel::held(const double *s) const
{
  return s[HMSUM];
}

double MesoModel::detached(const double *s) const
{
  return s[DETACHED];
}

double MesoModel::rate(const double *s) const
{
  return s[LASTDX] != 0.0 ? s[LASTB] / std::fabs(s[LASTDX]) : 0.0;
}

double MesoModel::normalization_error(const double *s) const
{
  double sum = 0.0;
  for (int i = 0; i < ncap; ++i) sum += s[NHEAD + i];
  sum += held_mass(s, nullptr, static_cast<long>(s[BASE]));
  sum += s[DETACHED];
  return std::fabs(sum - 1.0);
}

void MesoModel::density(const double *s, std::vector<double> &u, std::vector<double> &q) const
{
  const long base = static_cast<long>(s[BASE]), g = static_cast<long>(s[GH]);
  long jlo = static_cast<long>(s[JLO]), jhi = static_cast<long>(s[JHI]);
  if (jlo > jhi) {
    jlo = g;
    jhi = g;
  }
  long lo = jlo, hi = jhi;
  if (nrec > 0) {
    lo = std::min(lo, g - 2 * long(kheld));
    hi = std::max(hi, g + long(kheld) + 1);
  }
  std::vector<double> m(hi - lo + 1, 0.0);
  for (long j = jlo; j <= jhi; ++j) m[j - lo] += s[NHEAD + wrap(j, ncap, inv_ncap)];
  if (nrec > 0) {
    const double *recs = s + NHEAD + ncap;
    for (long gc = g - 2 * kheld - 1; gc <= g; ++gc) {
      const long sl = wrap(gc, nrec, inv_nrec);
      const double rl = recs[2 * sl], ru = recs[2 * sl + 1];
      for (const Line &L : hlines) {
        const long c = -L.k;
        if (g < gc + 2 * c) m[gc + c - lo] += L.w * rl;
        if (g < gc + 2 * c + 1) m[gc + c + 1 - lo] += L.w * ru;
      }
    }
  }
  const double xr = std::fma(-double(base), du, s[XABS]);
  u.clear();
  q.clear();
  for (long j = hi; j >= lo; --j) {
    u.push_back(xr - double(j - base) * du);
    q.push_back(m[j - lo] * inv_du);
  }
}

}    // namespace feq
