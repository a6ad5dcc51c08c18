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
   eq-green: elastic interaction between contacts from the surface Green
   tensor (paper Sec. III), solver in src/FRICTION-EQ/lib/eq_green.h

   eq-green [keyword value ...]

   keywords:
     L n                 L x L square lattice, a = 1                  (89)
     gamma1 g            k_c / (E_* a)                                (0.06)
     gamma2 g            self-term cutoff r_c / a                     (0.3)
     sigma s             Poisson ratio                                (0.3)
     mismatch m          E_* / E_top - E_* / E_bottom (z coupling)        (0)
     boundary open|periodic   finite array or periodic images         (open)
     method fft|dense    FFT + CG, or dense Cholesky (small L)        (fft)
     dense_limit n       largest number of unknowns of the dense path (8000:
                         L <= 63, or L <= 51 with mismatch (3 components);
                         L = 89 needs 15842: 1.9 GiB, minutes)
     precond circulant|jacobi|none                                    (circulant)
     tol t               CG true relative residual |b - A x|/|b|      (1e-12)
     maxiter n           CG iteration limit                           (20000)
     remove ix iy        removed contact, 0 <= ix, iy <= L-1          (centre)
     remove centre       the centre contact (L/2, L/2), as by default
     profile FILE        along +x, +y and the diagonal from the removed
                         contact: dir r df_x df_y (exact) df_x df_y (Eq. 09)
                         kernel_x (slip response -z_x, units of k_c)
     map FILE            ix iy dx dy f_x f_y df_x df_y (exact) df_x df_y (Eq. 09)
     table FILE KEYWORD  pair_style eq/elastic table of the slip kernel
     rmax R              last tabulated distance                      (L/4)
     kc k                contact stiffness k_c the table is written for (1)
     aniso yes|no        write k2 (cos 2 phi) as a 4th column         (yes)
     summary FILE        "name value" lines of the printed summary
   See doc/src/eq_green.rst.
------------------------------------------------------------------------- */

#include "eq_green.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace feq;

namespace {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double number(const std::string &kw, const std::string &s)
{
  char *end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v))
    throw UsageError("keyword " + kw + ": expected a number, got '" + s + "'");
  return v;
}

int integer(const std::string &kw, const std::string &s)
{
  const double v = number(kw, s);
  if (v != std::floor(v) || std::fabs(v) > 1e9)
    throw UsageError("keyword " + kw + ": expected an integer, got '" + s + "'");
  return int(v);
}

const char *USAGE =
    "usage: eq-green [keyword value ...]\n"
    "keywords: L n | gamma1 g | gamma2 g | sigma s | mismatch m | boundary open|periodic |\n"
    "          method fft|dense | dense_limit n | precond circulant|jacobi|none | tol t | maxiter n |\n"
    "          remove ix iy|centre | profile FILE | map FILE | table FILE KEYWORD | rmax R |\n"
    "          kc k | aniso yes|no | summary FILE\n"
    "see doc/src/eq_green.rst\n";

// what the command line asks for
struct Request {
  GreenParams p;
  GreenOptions o;
  int rx = 0, ry = 0, rmax = -1;    // removed contact; last kernel distance (-1: default)
  bool remove_centre = true;
  std::string remove_arg;           // "ix iy" as given (for the message)
  double kc = 1.0;
  bool aniso = true;
  std::string profile, map, table, keyword, summary;
};

// the command-line words, read one keyword at a time
struct ArgCursor {
  explicit ArgCursor(const std::vector<std::string> &args_) : args(args_) {}

  const std::vector<std::string> &args;
  size_t i = 0;

  // the n-th word after the keyword
  const std::string &val(int n = 1) const
  {
    if (i + n >= args.size()) throw UsageError("keyword " + args[i] + ": missing value");
    return args[i + n];
  }
};

// reads the value of a solver keyword (lattice, elasticity, method) into
// q; false when k is none of them
bool read_solver_keyword(const std::string &k, const ArgCursor &a, Request &q)
{
  GreenParams &p = q.p;
  GreenOptions &o = q.o;
  if (k == "L") p.L = integer(k, a.val());
  else if (k == "gamma1") p.gamma1 = number(k, a.val());
  else if (k == "gamma2") p.gamma2 = number(k, a.val());
  else if (k == "sigma") p.sigma = number(k, a.val());
  else if (k == "mismatch") p.mismatch = number(k, a.val());
  else if (k == "tol") o.tol = number(k, a.val());
  else if (k == "maxiter") o.maxiter = integer(k, a.val());
  else if (k == "dense_limit") {
    const long n = integer(k, a.val());
    if (n < 1) throw UsageError("keyword dense_limit: must be >= 1");
    o.dense_limit = static_cast<size_t>(n);
  } else if (k == "boundary") {
    const std::string &v = a.val();
    if (v == "open") p.periodic = false;
    else if (v == "periodic") p.periodic = true;
    else throw UsageError("keyword boundary: expected open or periodic, got '" + v + "'");
  } else if (k == "method") {
    const std::string &v = a.val();
    if (v == "fft") o.method = GreenMethod::FFT;
    else if (v == "dense") o.method = GreenMethod::DENSE;
    else throw UsageError("keyword method: expected fft or dense, got '" + v + "'");
  } else if (k == "precond") {
    const std::string &v = a.val();
    if (v == "circulant") o.precond = GreenPrecond::CIRCULANT;
    else if (v == "jacobi") o.precond = GreenPrecond::JACOBI;
    else if (v == "none") o.precond = GreenPrecond::NONE;
    else throw UsageError("keyword precond: expected circulant, jacobi or none, got '" + v + "'");
  } else
    return false;
  return true;
}

// reads the values of a removal, kernel or output keyword into q; false
// when k is none of them.  Advances a.i past the values beyond the first.
bool read_output_keyword(const std::string &k, ArgCursor &a, Request &q)
{
  if (k == "rmax") q.rmax = integer(k, a.val());
  else if (k == "kc") {
    q.kc = number(k, a.val());
    if (!(q.kc > 0.0)) throw UsageError("keyword kc: must be > 0");
  } else if (k == "aniso") {
    const std::string &v = a.val();
    if (v == "yes") q.aniso = true;
    else if (v == "no") q.aniso = false;
    else throw UsageError("keyword aniso: expected yes or no, got '" + v + "'");
  } else if (k == "remove") {
    if (a.val(1) == "centre" || a.val(1) == "center") {
      q.remove_centre = true;
    } else {
      q.rx = integer(k, a.val(1));
      q.ry = integer(k, a.val(2));
      q.remove_centre = false;
      q.remove_arg = a.val(1) + " " + a.val(2);
      ++a.i;
    }
  } else if (k == "profile") q.profile = a.val();
  else if (k == "map") q.map = a.val();
  else if (k == "summary") q.summary = a.val();
  else if (k == "table") {
    q.table = a.val(1);
    q.keyword = a.val(2);
    ++a.i;
  } else
    return false;
  return true;
}

// the removed contact and rmax: defaults, and checks against the lattice
void resolve_removal(Request &q)
{
  const GreenParams &p = q.p;
  if (q.remove_centre) {
    q.rx = q.ry = p.L / 2;
  } else if (q.rx < 0 || q.ry < 0 || q.rx >= p.L || q.ry >= p.L) {
    throw UsageError("keyword remove: ix iy must both be in [0, L-1] = [0, " +
                     std::to_string(p.L - 1) + "], got " + q.remove_arg +
                     " (omit the keyword, or use 'remove centre', for the centre contact)");
  }
  const int maxr = std::min(p.L - 1 - q.rx, p.L - 1 - q.ry);
  if (q.rmax < 0) q.rmax = std::max(1, std::min(p.L / 4, maxr));
  if (q.rmax < 1 || q.rmax > maxr)
    throw UsageError("keyword rmax: must be in [1, " + std::to_string(maxr) +
                     "] (distance from the removed contact to the lattice edge)");
}

// the request of the command line, checked
Request parse_request(const std::vector<std::string> &args)
{
  Request q;
  ArgCursor a(args);
  for (; a.i < args.size(); ++a.i) {
    const std::string &k = args[a.i];
    if (!read_solver_keyword(k, a, q) && !read_output_keyword(k, a, q))
      throw UsageError("unknown keyword '" + k + "'");
    ++a.i;
  }
  try {
    check_green_params(q.p);
  } catch (const std::invalid_argument &e) {
    throw UsageError(e.what());
  }
  resolve_removal(q);
  return q;
}

// what is solved for the removed contact j
struct Solution {
  int j = 0, nc = 0;
  GreenRemoval R;
  GreenSolveStats sst, sblk;
  Eigen::VectorXd z;     // slip response of j along x
  GreenKernel K;         // slip kernel along the axes
  Eigen::MatrixXd Bjj;   // nc x nc block of B = (1 + K G)^-1 at j
};

// removal of the contact, its slip response, kernel and block of B
Solution solve_removal(const GreenSolver &s, const Request &q)
{
  Solution r;
  r.j = s.site(q.rx, q.ry);
  r.nc = s.ncomp();
  r.R = green_remove_contact(s, r.j);
  r.z = green_slip_response(s, r.j, &r.sst);
  r.K = green_axis_kernel(s, r.z, r.j, q.rmax);
  // nc x nc block of B = (1 + K G)^-1 at the removed contact (the other
  // columns from the slip responses along y (and z))
  r.Bjj = green_site_block(s, r.j, &r.z, &r.sblk);
  return r;
}

// near-zone interaction strength: <r k_x(r)> over 2 <= r <= rn, rn =
// min(floor(lambda_c / 4), rmax) with lambda_c = a / gamma1 (Eq. int.eq30).
// Reported only if that window holds at least r = 2 and 3 (gamma1 <= 1/12
// and rmax >= 3); else NaN: for stiffer contacts there is no r^-1 zone
// on the lattice to average over (r = 2 already lies beyond lambda_c / 4
// for gamma1 > 1/8).
struct NearZone {
  int rn = 0;
  double kt = NAN, kty = NAN;
};

// the near-zone strength of kernel K (see above)
NearZone near_zone(const GreenParams &p, const GreenKernel &K, int rmax)
{
  NearZone n;
  const double lamc = 1.0 / p.gamma1;
  n.rn = int(std::min(std::floor(0.25 * lamc), double(rmax)));
  if (n.rn >= 3) {
    n.kt = n.kty = 0.0;
    int nk = 0;
    for (size_t i = 0; i < K.r.size(); ++i)
      if (K.r[i] >= 2 && K.r[i] <= n.rn) {
        n.kt += K.r[i] * K.kx[i];
        n.kty += K.r[i] * K.ky[i];
        ++nk;
      }
    n.kt /= nk;
    n.kty /= nk;
  }
  return n;
}

// the summary: "name value" pairs in the order printed
struct Summary {
  std::map<std::string, double> v;
  std::vector<std::string> order;
  void put(const std::string &n, double x)
  {
    v[n] = x;
    order.push_back(n);
  }
};

// summary of the lattice, its parameters and the solver statistics
void put_solver_values(const GreenSolver &s, const Request &q, const Solution &r, Summary &out)
{
  const GreenParams &p = q.p;
  const GreenRemoval &R = r.R;
  out.put("L", p.L);
  out.put("contacts", s.sites());
  out.put("unknowns", r.nc * s.sites());
  out.put("gamma1", p.gamma1);
  out.put("gamma2", p.gamma2);
  out.put("sigma", p.sigma);
  out.put("mismatch", p.mismatch);
  out.put("iterations_state", R.st_state.iterations);
  out.put("iterations_removed", R.st_removed.iterations);
  out.put("iterations_linear", R.st_linear.iterations);
  out.put("residual_max", std::max({R.st_state.residual, R.st_removed.residual,
                                    R.st_linear.residual, r.sst.residual, r.sblk.residual}));
  out.put("cg_restarts", std::max({R.st_state.restarts, R.st_removed.restarts,
                                   R.st_linear.restarts, r.sst.restarts, r.sblk.restarts}));
  out.put("seconds_state", R.st_state.seconds);
  out.put("seconds_total", R.st_state.seconds + R.st_removed.seconds + R.st_linear.seconds +
                               r.sst.seconds + r.sblk.seconds);
  out.put("operator_MB", s.memory_bytes() / 1048576.0);
  out.put("peak_rss_MB", peak_rss_bytes() / 1048576.0);
}

// summary of the removed contact: forces, block of B, force balance
void put_removal_values(const GreenSolver &s, const Request &q, const Solution &r, Summary &out)
{
  const GreenRemoval &R = r.R;
  const int j = r.j, nc = r.nc;
  // force balance (Betti reciprocity): sum_i dF_ix = -f_J^T B_JJ^-1 f_J
  // with f_J = (f_x, f_y[, f_z]) of the removed contact, B_JJ its block
  double sum_exact = 0.0, sum_linear = 0.0;
  for (int i = 0; i < s.sites(); ++i) {
    sum_exact += R.df_exact(s.index(i, 0));
    sum_linear += R.df_linear(s.index(i, 0));
  }
  Eigen::VectorXd fJ(nc);
  for (int a = 0; a < nc; ++a) fJ(a) = R.f(s.index(j, a));
  double ftot = 0.0;
  for (int i = 0; i < s.sites(); ++i) ftot += R.f(s.index(i, 0));
  out.put("total_force", ftot);
  out.put("removed_ix", q.rx);
  out.put("removed_iy", q.ry);
  out.put("f_removed", fJ(0));
  out.put("f_removed_y", fJ(1));
  if (nc == 3) out.put("f_removed_z", fJ(2));
  out.put("stretch_removed", R.stretch(s.index(j, 0)));
  out.put("B_removed", r.z(s.index(j, 0)));
  out.put("B_removed_xy", r.Bjj(0, 1));
  out.put("B_removed_yy", r.Bjj(1, 1));
  if (nc == 3) {
    out.put("B_removed_xz", r.Bjj(0, 2));
    out.put("B_removed_yz", r.Bjj(1, 2));
    out.put("B_removed_zz", r.Bjj(2, 2));
  }
  out.put("sum_df_exact", sum_exact);
  out.put("sum_df_exact_reciprocity", green_reciprocity_sum(fJ, r.Bjj));
  out.put("sum_df_linear", sum_linear);
}

// summary of the kernel: near the contact, near-zone strength, crossover
void put_kernel_values(const GreenSolver &s, const Request &q, const Solution &r, Summary &out)
{
  const GreenParams &p = q.p;
  const GreenKernel &K = r.K;
  const NearZone nz = near_zone(p, K, q.rmax);
  // crossover length of the slip kernel along x (proportional to df_x)
  const CrossoverFit cf = fit_crossover(K.r, K.kx, 1.0, q.rmax, 0.05, 1e5);
  const CrossoverFit cc =
      fit_crossover(K.r, K.kx, 1.0, q.rmax, 0.05, 1e5, CrossoverShape::CONTINUUM);
  out.put("df_x_r1_exact", r.R.df_exact(s.index(s.site(q.rx + int(K.r[0]), q.ry), 0)));
  out.put("df_x_r1_linear", r.R.df_linear(s.index(s.site(q.rx + 1, q.ry), 0)));
  out.put("kernel_x_r1", K.kx[0]);
  out.put("kernel_y_r1", K.ky[0]);
  out.put("kappa_tilde_x", nz.kt);
  out.put("kappa_tilde_y", nz.kty);
  out.put("kappa_tilde_rmax", nz.rn >= 3 ? nz.rn : 0);
  out.put("kappa_tilde_x_first_order", p.gamma1 * (1.0 + p.sigma) / M_PI);
  out.put("kappa_tilde_y_first_order", p.gamma1 * (1.0 + p.sigma) * (1.0 - p.sigma) / M_PI);
  out.put("crossover_lambda", cf.lambda);
  out.put("crossover_lambda_gamma1", cf.lambda * p.gamma1);
  out.put("crossover_rms", cf.rms);
  out.put("crossover_lambda_continuum", cc.lambda);
  out.put("crossover_lambda_continuum_gamma1", cc.lambda * p.gamma1);
  out.put("crossover_continuum_rms", cc.rms);
  // near-zone amplitude of the continuum fit: k_x -> kappa_tilde k_c a / r
  out.put("kappa_tilde_x_continuum", cc.amplitude * cc.lambda / (2.0 * M_PI));
}

// prints the summary on stdout
void print_summary(const GreenSolver &s, const GreenParams &p, Summary &sum)
{
  std::ostringstream txt;
  txt << "eq-green: " << p.L << " x " << p.L << " contacts, " << s.describe() << "\n";
  txt << std::setprecision(8);
  for (const auto &n : sum.order) {
    txt << "  " << std::left << std::setw(28) << n << " ";
    if (std::isnan(sum.v[n]))
      txt << "n/a\n";    // (the summary file writes nan)
    else
      txt << sum.v[n] << "\n";
  }
  std::fputs(txt.str().c_str(), stdout);
}

// an output file, with 12 digits
std::ofstream open_output(const std::string &f)
{
  std::ofstream out(f);
  if (!out) throw UsageError("cannot open output file '" + f + "'");
  out << std::setprecision(12);
  return out;
}

// summary file: "name value" lines
void write_summary(const std::string &file, Summary &sum)
{
  std::ofstream out = open_output(file);
  out << std::setprecision(12);
  for (const auto &n : sum.order) out << n << " " << sum.v[n] << "\n";
}

// profile file: along +x, +y and the diagonal from the removed contact
void write_profile(const GreenSolver &s, const Request &q, const Solution &r)
{
  std::ofstream out = open_output(q.profile);
  out << "# dir r df_x df_y (exact removal)  df_x df_y (Eq. int.eq09)  kernel_x (-z_x, k_c)\n";
  const int dirs[3][2] = {{1, 0}, {0, 1}, {1, 1}};
  const char *names[3] = {"x", "y", "d"};
  for (int d = 0; d < 3; ++d)
    for (int k = 1;; ++k) {
      const int ix = q.rx + k * dirs[d][0], iy = q.ry + k * dirs[d][1];
      if (ix >= q.p.L || iy >= q.p.L) break;
      const int i = s.site(ix, iy);
      out << names[d] << " " << k * std::hypot(dirs[d][0], dirs[d][1]) << " "
          << r.R.df_exact(s.index(i, 0)) << " " << r.R.df_exact(s.index(i, 1)) << " "
          << r.R.df_linear(s.index(i, 0)) << " " << r.R.df_linear(s.index(i, 1)) << " "
          << -r.z(s.index(i, 0)) << "\n";
    }
}

// map file: forces and force changes at every contact
void write_map(const GreenSolver &s, const Request &q, const GreenRemoval &R)
{
  std::ofstream out = open_output(q.map);
  out << "# ix iy dx dy f_x f_y df_x df_y (exact) df_x df_y (Eq. int.eq09)\n";
  for (int iy = 0; iy < q.p.L; ++iy)
    for (int ix = 0; ix < q.p.L; ++ix) {
      const int i = s.site(ix, iy);
      out << ix << " " << iy << " " << ix - q.rx << " " << iy - q.ry << " " << R.f(s.index(i, 0))
          << " " << R.f(s.index(i, 1)) << " " << R.df_exact(s.index(i, 0)) << " "
          << R.df_exact(s.index(i, 1)) << " " << R.df_linear(s.index(i, 0)) << " "
          << R.df_linear(s.index(i, 1)) << "\n";
    }
}

// pair_style eq/elastic table of the slip kernel, with its generator command
void write_table(const std::vector<std::string> &args, const Request &q, const GreenKernel &K)
{
  const GreenParams &p = q.p;
  std::ostringstream cmd;    // the generator command (without output files)
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "summary" || args[i] == "profile" || args[i] == "map") {
      ++i;
      continue;
    }
    cmd << " " << args[i];
  }
  std::ostringstream par;
  par << "gamma_1 = " << p.gamma1 << ", gamma_2 = " << p.gamma2 << ", sigma = " << p.sigma
      << ", mismatch = " << p.mismatch << ", L = " << p.L << " ("
      << (p.periodic ? "periodic" : "open") << "), k_c = " << q.kc << ", a = 1";
  std::vector<std::string> com = {
      "FRICTION-EQ elastic interaction kernel for pair_style eq/elastic",
      par.str(),
      "k(r, phi) = k0(r) + k2(r) cos(2 phi): force rise on a contact at distance r, angle phi",
      "to x, per unit stretch drop (slip) of a contact: k_ij = -k_c [(1 + K G)^-1]_(ix,jx),",
      "from the slip response of the centre contact of the lattice (paper Eq. int.eq09),",
      "k0 = (k(r, 0) + k(r, pi/2)) / 2, k2 = (k(r, 0) - k(r, pi/2)) / 2 along the lattice axes",
      "produced by: eq-green" + cmd.str()};
  write_green_table(q.table, q.keyword, K, q.kc, q.aniso, com);
}

// solves the request, prints the summary and writes the files asked for
void run(const std::vector<std::string> &args)
{
  const Request q = parse_request(args);
  GreenSolver s(q.p, q.o);
  const Solution r = solve_removal(s, q);
  Summary sum;
  put_solver_values(s, q, r, sum);
  put_removal_values(s, q, r, sum);
  put_kernel_values(s, q, r, sum);
  print_summary(s, q.p, sum);
  if (!q.summary.empty()) write_summary(q.summary, sum);
  if (!q.profile.empty()) write_profile(s, q, r);
  if (!q.map.empty()) write_map(s, q, r.R);
  if (!q.table.empty()) write_table(args, q, r.K);
}

}    // namespace

int main(int argc, char **argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && (args[0] == "-h" || args[0] == "--help")) {
    std::cout << USAGE;
    return 0;
  }
  try {
    run(args);
  } catch (const UsageError &e) {
    std::cerr << "eq-green: ERROR: " << e.what() << "\n" << USAGE;
    return 1;
  } catch (const std::exception &e) {
    std::cerr << "eq-green: ERROR: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
