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

}    // namespace

int main(int argc, char **argv)
{
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (!args.empty() && (args[0] == "-h" || args[0] == "--help")) {
    std::cout << USAGE;
    return 0;
  }
  try {
    GreenParams p;
    GreenOptions o;
    int rx = 0, ry = 0, rmax = -1;
    bool remove_centre = true;
    std::string remove_arg;
    double kc = 1.0;
    bool aniso = true;
    std::string profile, map, table, keyword, summary;
    for (size_t i = 0; i < args.size(); ++i) {
      const std::string &k = args[i];
      auto val = [&](int n = 1) -> const std::string & {
        if (i + n >= args.size()) throw UsageError("keyword " + k + ": missing value");
        return args[i + n];
      };
      if (k == "L") p.L = integer(k, val());
      else if (k == "gamma1") p.gamma1 = number(k, val());
      else if (k == "gamma2") p.gamma2 = number(k, val());
      else if (k == "sigma") p.sigma = number(k, val());
      else if (k == "mismatch") p.mismatch = number(k, val());
      else if (k == "tol") o.tol = number(k, val());
      else if (k == "maxiter") o.maxiter = integer(k, val());
      else if (k == "dense_limit") {
        const long n = integer(k, val());
        if (n < 1) throw UsageError("keyword dense_limit: must be >= 1");
        o.dense_limit = static_cast<size_t>(n);
      }
      else if (k == "rmax") rmax = integer(k, val());
      else if (k == "kc") {
        kc = number(k, val());
        if (!(kc > 0.0)) throw UsageError("keyword kc: must be > 0");
      } else if (k == "boundary") {
        const std::string &v = val();
        if (v == "open") p.periodic = false;
        else if (v == "periodic") p.periodic = true;
        else throw UsageError("keyword boundary: expected open or periodic, got '" + v + "'");
      } else if (k == "method") {
        const std::string &v = val();
        if (v == "fft") o.method = GreenMethod::FFT;
        else if (v == "dense") o.method = GreenMethod::DENSE;
        else throw UsageError("keyword method: expected fft or dense, got '" + v + "'");
      } else if (k == "precond") {
        const std::string &v = val();
        if (v == "circulant") o.precond = GreenPrecond::CIRCULANT;
        else if (v == "jacobi") o.precond = GreenPrecond::JACOBI;
        else if (v == "none") o.precond = GreenPrecond::NONE;
        else throw UsageError("keyword precond: expected circulant, jacobi or none, got '" + v + "'");
      } else if (k == "aniso") {
        const std::string &v = val();
        if (v == "yes") aniso = true;
        else if (v == "no") aniso = false;
        else throw UsageError("keyword aniso: expected yes or no, got '" + v + "'");
      } else if (k == "remove") {
        if (val(1) == "centre" || val(1) == "center") {
          remove_centre = true;
        } else {
          rx = integer(k, val(1));
          ry = integer(k, val(2));
          remove_centre = false;
          remove_arg = val(1) + " " + val(2);
          ++i;
        }
      } else if (k == "profile") profile = val();
      else if (k == "map") map = val();
      else if (k == "summary") summary = val();
      else if (k == "table") {
        table = val(1);
        keyword = val(2);
        ++i;
      } else
        throw UsageError("unknown keyword '" + k + "'");
      ++i;
    }
    try {
      check_green_params(p);
    } catch (const std::invalid_argument &e) {
      throw UsageError(e.what());
    }
    if (remove_centre) {
      rx = ry = p.L / 2;
    } else if (rx < 0 || ry < 0 || rx >= p.L || ry >= p.L) {
      throw UsageError("keyword remove: ix iy must both be in [0, L-1] = [0, " +
                       std::to_string(p.L - 1) + "], got " + remove_arg +
                       " (omit the keyword, or use 'remove centre', for the centre contact)");
    }
    const int maxr = std::min(p.L - 1 - rx, p.L - 1 - ry);
    if (rmax < 0) rmax = std::max(1, std::min(p.L / 4, maxr));
    if (rmax < 1 || rmax > maxr)
      throw UsageError("keyword rmax: must be in [1, " + std::to_string(maxr) +
                       "] (distance from the removed contact to the lattice edge)");

    GreenSolver s(p, o);
    const int j = s.site(rx, ry), nc = s.ncomp();
    const GreenRemoval R = green_remove_contact(s, j);
    GreenSolveStats sst, sblk;
    const Eigen::VectorXd z = green_slip_response(s, j, &sst);
    const GreenKernel K = green_axis_kernel(s, z, j, rmax);
    // nc x nc block of B = (1 + K G)^-1 at the removed contact (the other
    // columns from the slip responses along y (and z))
    const Eigen::MatrixXd Bjj = green_site_block(s, j, &z, &sblk);

    // near-zone interaction strength: <r k_x(r)> over 2 <= r <= rn, rn =
    // min(floor(lambda_c / 4), rmax) with lambda_c = a / gamma1 (Eq. int.eq30).
    // Reported only if that window holds at least r = 2 and 3 (gamma1 <= 1/12
    // and rmax >= 3); else NaN: for stiffer contacts there is no r^-1 zone
    // on the lattice to average over (r = 2 already lies beyond lambda_c / 4
    // for gamma1 > 1/8).
    const double lamc = 1.0 / p.gamma1;
    const int rn = int(std::min(std::floor(0.25 * lamc), double(rmax)));
    double kt = NAN, kty = NAN;
    if (rn >= 3) {
      kt = kty = 0.0;
      int nk = 0;
      for (size_t i = 0; i < K.r.size(); ++i)
        if (K.r[i] >= 2 && K.r[i] <= rn) {
          kt += K.r[i] * K.kx[i];
          kty += K.r[i] * K.ky[i];
          ++nk;
        }
      kt /= nk;
      kty /= nk;
    }

    // force balance (Betti reciprocity): sum_i dF_ix = -f_J^T B_JJ^-1 f_J
    // with f_J = (f_x, f_y[, f_z]) of the removed contact, B_JJ its block
    double sum_exact = 0.0, sum_linear = 0.0;
    for (int i = 0; i < s.sites(); ++i) {
      sum_exact += R.df_exact(s.index(i, 0));
      sum_linear += R.df_linear(s.index(i, 0));
    }
    Eigen::VectorXd fJ(nc);
    for (int a = 0; a < nc; ++a) fJ(a) = R.f(s.index(j, a));
    const double fj = fJ(0), zj = z(s.index(j, 0));
    double ftot = 0.0;
    for (int i = 0; i < s.sites(); ++i) ftot += R.f(s.index(i, 0));

    std::vector<double> dfx;
    for (double r : K.r) dfx.push_back(R.df_exact(s.index(s.site(rx + int(r), ry), 0)));
    // crossover length of the slip kernel along x (proportional to df_x)
    const CrossoverFit cf = fit_crossover(K.r, K.kx, 1.0, rmax, 0.05, 1e5);
    const CrossoverFit cc =
        fit_crossover(K.r, K.kx, 1.0, rmax, 0.05, 1e5, CrossoverShape::CONTINUUM);

    std::map<std::string, double> v;
    std::vector<std::string> order;
    auto put = [&](const std::string &n, double x) {
      v[n] = x;
      order.push_back(n);
    };
    put("L", p.L);
    put("contacts", s.sites());
    put("unknowns", nc * s.sites());
    put("gamma1", p.gamma1);
    put("gamma2", p.gamma2);
    put("sigma", p.sigma);
    put("mismatch", p.mismatch);
    put("iterations_state", R.st_state.iterations);
    put("iterations_removed", R.st_removed.iterations);
    put("iterations_linear", R.st_linear.iterations);
    put("residual_max", std::max({R.st_state.residual, R.st_removed.residual, R.st_linear.residual,
                                  sst.residual, sblk.residual}));
    put("cg_restarts", std::max({R.st_state.restarts, R.st_removed.restarts, R.st_linear.restarts,
                                 sst.restarts, sblk.restarts}));
    put("seconds_state", R.st_state.seconds);
    put("seconds_total", R.st_state.seconds + R.st_removed.seconds + R.st_linear.seconds +
                             sst.seconds + sblk.seconds);
    put("operator_MB", s.memory_bytes() / 1048576.0);
    put("peak_rss_MB", peak_rss_bytes() / 1048576.0);
    put("total_force", ftot);
    put("removed_ix", rx);
    put("removed_iy", ry);
    put("f_removed", fj);
    put("f_removed_y", fJ(1));
    if (nc == 3) put("f_removed_z", fJ(2));
    put("stretch_removed", R.stretch(s.index(j, 0)));
    put("B_removed", zj);
    put("B_removed_xy", Bjj(0, 1));
    put("B_removed_yy", Bjj(1, 1));
    if (nc == 3) {
      put("B_removed_xz", Bjj(0, 2));
      put("B_removed_yz", Bjj(1, 2));
      put("B_removed_zz", Bjj(2, 2));
    }
    put("sum_df_exact", sum_exact);
    put("sum_df_exact_reciprocity", green_reciprocity_sum(fJ, Bjj));
    put("sum_df_linear", sum_linear);
    put("df_x_r1_exact", dfx[0]);
    put("df_x_r1_linear", R.df_linear(s.index(s.site(rx + 1, ry), 0)));
    put("kernel_x_r1", K.kx[0]);
    put("kernel_y_r1", K.ky[0]);
    put("kappa_tilde_x", kt);
    put("kappa_tilde_y", kty);
    put("kappa_tilde_rmax", rn >= 3 ? rn : 0);
    put("kappa_tilde_x_first_order", p.gamma1 * (1.0 + p.sigma) / M_PI);
    put("kappa_tilde_y_first_order", p.gamma1 * (1.0 + p.sigma) * (1.0 - p.sigma) / M_PI);
    put("crossover_lambda", cf.lambda);
    put("crossover_lambda_gamma1", cf.lambda * p.gamma1);
    put("crossover_rms", cf.rms);
    put("crossover_lambda_continuum", cc.lambda);
    put("crossover_lambda_continuum_gamma1", cc.lambda * p.gamma1);
    put("crossover_continuum_rms", cc.rms);
    // near-zone amplitude of the continuum fit: k_x -> kappa_tilde k_c a / r
    put("kappa_tilde_x_continuum", cc.amplitude * cc.lambda / (2.0 * M_PI));

    std::ostringstream txt;
    txt << "eq-green: " << p.L << " x " << p.L << " contacts, " << s.describe() << "\n";
    txt << std::setprecision(8);
    for (const auto &n : order) {
      txt << "  " << std::left << std::setw(28) << n << " ";
      if (std::isnan(v[n]))
        txt << "n/a\n";    // (the summary file writes nan)
      else
        txt << v[n] << "\n";
    }
    std::fputs(txt.str().c_str(), stdout);

    auto open = [](const std::string &f) {
      std::ofstream out(f);
      if (!out) throw UsageError("cannot open output file '" + f + "'");
      out << std::setprecision(12);
      return out;
    };
    if (!summary.empty()) {
      std::ofstream out = open(summary);
      out << std::setprecision(12);
      for (const auto &n : order) out << n << " " << v[n] << "\n";
    }
    if (!profile.empty()) {
      std::ofstream out = open(profile);
      out << "# dir r df_x df_y (exact removal)  df_x df_y (Eq. int.eq09)  kernel_x (-z_x, k_c)\n";
      const int dirs[3][2] = {{1, 0}, {0, 1}, {1, 1}};
      const char *names[3] = {"x", "y", "d"};
      for (int d = 0; d < 3; ++d)
        for (int r = 1;; ++r) {
          const int ix = rx + r * dirs[d][0], iy = ry + r * dirs[d][1];
          if (ix >= p.L || iy >= p.L) break;
          const int i = s.site(ix, iy);
          out << names[d] << " " << r * std::hypot(dirs[d][0], dirs[d][1]) << " "
              << R.df_exact(s.index(i, 0)) << " " << R.df_exact(s.index(i, 1)) << " "
              << R.df_linear(s.index(i, 0)) << " " << R.df_linear(s.index(i, 1)) << " "
              << -z(s.index(i, 0)) << "\n";
        }
    }
    if (!map.empty()) {
      std::ofstream out = open(map);
      out << "# ix iy dx dy f_x f_y df_x df_y (exact) df_x df_y (Eq. int.eq09)\n";
      for (int iy = 0; iy < p.L; ++iy)
        for (int ix = 0; ix < p.L; ++ix) {
          const int i = s.site(ix, iy);
          out << ix << " " << iy << " " << ix - rx << " " << iy - ry << " " << R.f(s.index(i, 0))
              << " " << R.f(s.index(i, 1)) << " " << R.df_exact(s.index(i, 0)) << " "
              << R.df_exact(s.index(i, 1)) << " " << R.df_linear(s.index(i, 0)) << " "
              << R.df_linear(s.index(i, 1)) << "\n";
        }
    }
    if (!table.empty()) {
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
          << (p.periodic ? "periodic" : "open") << "), k_c = " << kc << ", a = 1";
      std::vector<std::string> com = {
          "FRICTION-EQ elastic interaction kernel for pair_style eq/elastic",
          par.str(),
          "k(r, phi) = k0(r) + k2(r) cos(2 phi): force rise on a contact at distance r, angle phi",
          "to x, per unit stretch drop (slip) of a contact: k_ij = -k_c [(1 + K G)^-1]_(ix,jx),",
          "from the slip response of the centre contact of the lattice (paper Eq. int.eq09),",
          "k0 = (k(r, 0) + k(r, pi/2)) / 2, k2 = (k(r, 0) - k(r, pi/2)) / 2 along the lattice axes",
          "produced by: eq-green" + cmd.str()};
      write_green_table(table, keyword, K, kc, aniso, com);
    }
  } catch (const UsageError &e) {
    std::cerr << "eq-green: ERROR: " << e.what() << "\n" << USAGE;
    return 1;
  } catch (const std::exception &e) {
    std::cerr << "eq-green: ERROR: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
