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
   FRICTION-EQ package: surface Green tensor solver (see eq_green.h)
------------------------------------------------------------------------- */

#include "eq_green.h"
#include "eq_text.h"

#include <fftw3.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace feq {

namespace {

const double PI = 3.14159265358979323846;

double now()
{
  using clk = std::chrono::steady_clock;
  return std::chrono::duration<double>(clk::now().time_since_epoch()).count();
}

std::string num(double v, int digits = 12) { return format_number(v, digits); }

}    // namespace

void check_green_params(const GreenParams &p)
{
  if (p.L < 3) throw std::invalid_argument("L must be >= 3, got " + std::to_string(p.L));
  if (p.L > 8192) throw std::invalid_argument("L must be <= 8192, got " + std::to_string(p.L));
  if (!(p.gamma1 > 0.0) || !std::isfinite(p.gamma1))
    throw std::invalid_argument("gamma1 must be > 0, got " + num(p.gamma1));
  if (!(p.gamma2 > 0.0) || !std::isfinite(p.gamma2))
    throw std::invalid_argument("gamma2 must be > 0, got " + num(p.gamma2));
  if (!(p.sigma > -1.0 && p.sigma < 0.5))
    throw std::invalid_argument("sigma (Poisson ratio) must be in (-1, 0.5), got " + num(p.sigma));
  if (!(std::fabs(p.mismatch) < 1.0))
    throw std::invalid_argument("mismatch must be in (-1, 1), got " + num(p.mismatch));
}

Eigen::Matrix3d green_block(double dx, double dy, const GreenParams &p)
{
  const double s = p.sigma;
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  const double r2 = dx * dx + dy * dy;
  if (r2 == 0.0) {
    const double c = (1.0 + s) / (2.0 * PI * p.gamma2);
    g(0, 0) = g(1, 1) = c * (2.0 - s);    // 2(1-s) + 2 s <dx^2/r^2>, <.> = 1/2
    g(2, 2) = c * 2.0 * (1.0 - s);
    return g;
  }
  const double r = std::sqrt(r2);
  const double c = (1.0 + s) / (2.0 * PI * r);
  g(0, 0) = c * (2.0 * (1.0 - s) + 2.0 * s * dx * dx / r2);
  g(1, 1) = c * (2.0 * (1.0 - s) + 2.0 * s * dy * dy / r2);
  g(0, 1) = g(1, 0) = c * 2.0 * s * dx * dy / r2;
  g(2, 2) = c * 2.0 * (1.0 - s);
  const double cz = c * p.mismatch * (1.0 - 2.0 * s) / r;
  g(0, 2) = -cz * dx;
  g(2, 0) = cz * dx;
  g(1, 2) = -cz * dy;
  g(2, 1) = cz * dy;
  return g;
}

/* ---------------------------------------------------------------------- */

struct GreenSolver::FFTData {
  int M = 0;                      // FFT box (2L open, L periodic)
  int Mh = 0;                     // M/2 + 1 complex columns
  std::vector<fftw_complex *> khat;    // nc*nc kernels (row-major a*nc+b), M x Mh
  double *rbuf = nullptr;         // M x M real work array
  std::vector<fftw_complex *> cbuf;    // nc complex work arrays
  fftw_plan fwd = nullptr, bwd = nullptr;
  // circulant preconditioner on the L x L periodic box
  int P = 0, Ph = 0;
  double *prbuf = nullptr;
  std::vector<fftw_complex *> pcbuf;
  fftw_plan pfwd = nullptr, pbwd = nullptr;
  std::vector<std::complex<double>> pinv;    // per wave vector nc x nc inverse
  bool precond_ok = false;

  ~FFTData()
  {
    for (auto *k : khat) fftw_free(k);
    for (auto *c : cbuf) fftw_free(c);
    for (auto *c : pcbuf) fftw_free(c);
    if (rbuf) fftw_free(rbuf);
    if (prbuf) fftw_free(prbuf);
    if (fwd) fftw_destroy_plan(fwd);
    if (bwd) fftw_destroy_plan(bwd);
    if (pfwd) fftw_destroy_plan(pfwd);
    if (pbwd) fftw_destroy_plan(pbwd);
  }
};

namespace {

// minimum-image displacement(s) of index i on a ring of n sites: one, or two
// (+n/2 and -n/2) at the half-way point of an even ring
int images(int i, int n, int *d)
{
  int a = i <= n / 2 ? i : i - n;
  if (2 * std::abs(a) == n) {
    d[0] = n / 2;
    d[1] = -n / 2;
    return 2;
  }
  d[0] = a;
  return 1;
}

// kernel block at box index (ix, iy) of an M x M box: open array (zero
// padded, M = 2L) or periodic minimum image (M = L, averaged over tied images)
Eigen::Matrix3d box_block(int ix, int iy, int M, bool periodic, int L, const GreenParams &p)
{
  if (!periodic) {
    const int dx = ix < L ? ix : ix - M;    // M >= 2L-1: every |dx| < L appears once
    const int dy = iy < L ? iy : iy - M;
    if (std::abs(dx) >= L || std::abs(dy) >= L) return Eigen::Matrix3d::Zero();
    return green_block(dx, dy, p);
  }
  int ax[2], ay[2];
  const int nx = images(ix, M, ax), ny = images(iy, M, ay);
  Eigen::Matrix3d g = Eigen::Matrix3d::Zero();
  for (int a = 0; a < nx; ++a)
    for (int b = 0; b < ny; ++b) g += green_block(ax[a], ay[b], p);
  return g / double(nx * ny);
}

// smallest n' >= n with no prime factor above 7 (fast FFTW sizes)
int fast_size(int n)
{
  for (int m = n;; ++m) {
    int k = m;
    for (int p : {2, 3, 5, 7})
      while (k % p == 0) k /= p;
    if (k == 1) return m;
  }
}

}    // namespace

GreenSolver::GreenSolver(const GreenParams &p, const GreenOptions &o) : par(p), opt(o)
{
  check_green_params(par);
  if (!(opt.tol > 0.0)) throw std::invalid_argument("tol must be > 0, got " + num(opt.tol));
  if (opt.maxiter < 1)
    throw std::invalid_argument("maxiter must be >= 1, got " + std::to_string(opt.maxiter));
  if (opt.max_restarts < 0)
    throw std::invalid_argument("max_restarts must be >= 0, got " + std::to_string(opt.max_restarts));
  nc = par.mismatch == 0.0 ? 2 : 3;
  const int N = sites();
  diag_g.resize(nc * N);
  const Eigen::Matrix3d g0 = par.periodic ? box_block(0, 0, par.L, true, par.L, par)
                                          : green_block(0.0, 0.0, par);
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < nc; ++a) diag_g(index(i, a)) = g0(a, a);

  if (opt.method == GreenMethod::DENSE) {
    const size_t n = size_t(nc) * N;
    if (n > opt.dense_limit)
      throw std::invalid_argument("dense path limited to nc N <= " + std::to_string(opt.dense_limit) +
                                  " unknowns, got " + std::to_string(n) + " (L = " +
                                  std::to_string(par.L) + "); use the FFT path");
    dense.resize(n, n);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        const int ix = i % par.L, iy = i / par.L, jx = j % par.L, jy = j / par.L;
        Eigen::Matrix3d g;
        if (par.periodic) {
          const int M = par.L;
          g = box_block(((ix - jx) % M + M) % M, ((iy - jy) % M + M) % M, M, true, par.L, par);
        } else {
          g = green_block(ix - jx, iy - jy, par);
        }
        for (int a = 0; a < nc; ++a)
          for (int b = 0; b < nc; ++b) dense(index(i, a), index(j, b)) = g(a, b);
      }
  } else {
    setup_fft();
  }
}

GreenSolver::~GreenSolver() = default;

void GreenSolver::setup_fft()
{
  fft.reset(new FFTData);
  FFTData &d = *fft;
  const int L = par.L;
  d.M = par.periodic ? L : fast_size(2 * L - 1);    // >= 2L-1: no wrap-around
  d.Mh = d.M / 2 + 1;
  const int M = d.M, Mh = d.Mh;
  const size_t nreal = size_t(M) * M, ncplx = size_t(M) * Mh;
  d.rbuf = fftw_alloc_real(nreal);
  for (int a = 0; a < nc; ++a) d.cbuf.push_back(fftw_alloc_complex(ncplx));
  d.fwd = fftw_plan_dft_r2c_2d(M, M, d.rbuf, d.cbuf[0], FFTW_ESTIMATE);
  d.bwd = fftw_plan_dft_c2r_2d(M, M, d.cbuf[0], d.rbuf, FFTW_ESTIMATE);
  if (!d.fwd || !d.bwd) throw std::runtime_error("FFTW could not create a plan");

  // kernel transforms, one per block entry (array index: row iy, column ix)
  for (int a = 0; a < nc; ++a)
    for (int b = 0; b < nc; ++b) {
      for (int iy = 0; iy < M; ++iy)
        for (int ix = 0; ix < M; ++ix)
          d.rbuf[size_t(iy) * M + ix] = box_block(ix, iy, M, par.periodic, L, par)(a, b);
      fftw_complex *k = fftw_alloc_complex(ncplx);
      fftw_execute_dft_r2c(d.fwd, d.rbuf, k);
      d.khat.push_back(k);
    }

  // circulant (Strang) preconditioner: the periodic minimum-image kernel on
  // a P x P box, P = L (periodic lattice: exact for kappa = 1) or the next
  // fast FFT size >= L (open array: the lattice is embedded in the box, the
  // preconditioner is the restriction of the SPD circulant inverse)
  if (opt.precond == GreenPrecond::CIRCULANT) {
    const int P = par.periodic ? L : fast_size(L);
    d.P = P;
    d.Ph = P / 2 + 1;
    const size_t pr = size_t(P) * P, pc = size_t(P) * d.Ph;
    d.prbuf = fftw_alloc_real(pr);
    for (int a = 0; a < nc; ++a) d.pcbuf.push_back(fftw_alloc_complex(pc));
    d.pfwd = fftw_plan_dft_r2c_2d(P, P, d.prbuf, d.pcbuf[0], FFTW_ESTIMATE);
    d.pbwd = fftw_plan_dft_c2r_2d(P, P, d.pcbuf[0], d.prbuf, FFTW_ESTIMATE);
    std::vector<std::vector<std::complex<double>>> ph(nc * nc,
                                                      std::vector<std::complex<double>>(pc));
    std::vector<fftw_complex> tmp(pc);
    for (int a = 0; a < nc; ++a)
      for (int b = 0; b < nc; ++b) {
        for (int iy = 0; iy < P; ++iy)
          for (int ix = 0; ix < P; ++ix)
            d.prbuf[size_t(iy) * P + ix] = box_block(ix, iy, P, true, L, par)(a, b);
        fftw_execute_dft_r2c(d.pfwd, d.prbuf, tmp.data());
        for (size_t q = 0; q < pc; ++q) ph[a * nc + b][q] = {tmp[q][0], tmp[q][1]};
      }
    d.pinv.resize(pc * nc * nc);
    bool ok = true;
    for (size_t q = 0; q < pc; ++q) {
      // Hermitian part of the block (Hermitian up to round-off), padded to 3 x 3
      Eigen::Matrix3cd m = Eigen::Matrix3cd::Identity();
      for (int a = 0; a < nc; ++a)
        for (int b = 0; b < nc; ++b) {
          const std::complex<double> hab = 0.5 * (ph[a * nc + b][q] + std::conj(ph[b * nc + a][q]));
          m(a, b) = (a == b ? 1.0 : 0.0) + par.gamma1 * hab;
        }
      Eigen::LLT<Eigen::Matrix3cd> llt(m - 1e-8 * Eigen::Matrix3cd::Identity());
      if (llt.info() != Eigen::Success) ok = false;
      const Eigen::Matrix3cd inv = m.inverse();
      for (int a = 0; a < nc; ++a)
        for (int b = 0; b < nc; ++b) d.pinv[q * nc * nc + a * nc + b] = inv(a, b);
    }
    d.precond_ok = ok;    // else: fall back to Jacobi
  }
}

size_t GreenSolver::memory_bytes() const
{
  size_t b = size_t(dense.size()) * sizeof(double) + size_t(diag_g.size()) * sizeof(double);
  if (fft) {
    const FFTData &d = *fft;
    b += size_t(d.M) * d.M * sizeof(double);
    b += (d.khat.size() + d.cbuf.size()) * size_t(d.M) * d.Mh * sizeof(fftw_complex);
    if (d.prbuf) {
      b += size_t(d.P) * d.P * sizeof(double);
      b += d.pcbuf.size() * size_t(d.P) * d.Ph * sizeof(fftw_complex);
      b += d.pinv.size() * sizeof(std::complex<double>);
    }
  }
  return b;
}

std::string GreenSolver::describe() const
{
  std::ostringstream s;
  s << (opt.method == GreenMethod::DENSE ? "dense Cholesky" : "FFT + CG") << ", "
    << (par.periodic ? "periodic images" : "open array (zero padded)");
  if (opt.method == GreenMethod::FFT) {
    s << ", preconditioner ";
    if (opt.precond == GreenPrecond::CIRCULANT)
      s << (fft->precond_ok ? "circulant" : "jacobi (circulant not positive definite)");
    else
      s << (opt.precond == GreenPrecond::JACOBI ? "jacobi" : "none");
  }
  return s.str();
}

bool GreenSolver::circulant_active() const
{
  return opt.method == GreenMethod::FFT && opt.precond == GreenPrecond::CIRCULANT && fft &&
      fft->precond_ok;
}

Eigen::VectorXd GreenSolver::apply_green(const Eigen::VectorXd &v) const
{
  if (v.size() != nc * sites()) throw std::invalid_argument("apply_green: wrong vector length");
  if (opt.method == GreenMethod::DENSE) return dense * v;
  const FFTData &d = *fft;
  const int L = par.L, M = d.M, Mh = d.Mh;
  const size_t ncplx = size_t(M) * Mh;
  for (int b = 0; b < nc; ++b) {
    std::fill(d.rbuf, d.rbuf + size_t(M) * M, 0.0);
    for (int iy = 0; iy < L; ++iy)
      for (int ix = 0; ix < L; ++ix) d.rbuf[size_t(iy) * M + ix] = v(index(site(ix, iy), b));
    fftw_execute_dft_r2c(d.fwd, d.rbuf, d.cbuf[b]);
  }
  // per wave vector: out_a = sum_b K_ab in_b (in place, one q at a time)
  std::complex<double> in[3], out[3];
  for (size_t q = 0; q < ncplx; ++q) {
    for (int b = 0; b < nc; ++b) in[b] = {d.cbuf[b][q][0], d.cbuf[b][q][1]};
    for (int a = 0; a < nc; ++a) {
      out[a] = 0.0;
      for (int b = 0; b < nc; ++b) {
        const fftw_complex &k = d.khat[a * nc + b][q];
        out[a] += std::complex<double>(k[0], k[1]) * in[b];
      }
    }
    for (int a = 0; a < nc; ++a) {
      d.cbuf[a][q][0] = out[a].real();
      d.cbuf[a][q][1] = out[a].imag();
    }
  }
  Eigen::VectorXd y(v.size());
  const double norm = 1.0 / (double(M) * M);
  for (int a = 0; a < nc; ++a) {
    fftw_execute_dft_c2r(d.bwd, d.cbuf[a], d.rbuf);
    for (int iy = 0; iy < L; ++iy)
      for (int ix = 0; ix < L; ++ix) y(index(site(ix, iy), a)) = norm * d.rbuf[size_t(iy) * M + ix];
  }
  return y;
}

void GreenSolver::precondition(const std::vector<double> &kappa, const Eigen::VectorXd &r,
                               Eigen::VectorXd &z) const
{
  const int N = sites();
  const bool circ = opt.precond == GreenPrecond::CIRCULANT && fft && fft->precond_ok;
  if (opt.precond == GreenPrecond::NONE) {
    z = r;
  } else if (!circ) {
    z.resize(r.size());
    for (int i = 0; i < N; ++i)
      for (int a = 0; a < nc; ++a) {
        const int k = index(i, a);
        z(k) = kappa[i] > 0.0 ? r(k) / (1.0 / kappa[i] + par.gamma1 * diag_g(k)) : 0.0;
      }
  } else {
    const FFTData &d = *fft;
    const int L = par.L, P = d.P;
    const size_t pc = size_t(P) * d.Ph;
    for (int b = 0; b < nc; ++b) {
      std::fill(d.prbuf, d.prbuf + size_t(P) * P, 0.0);
      for (int iy = 0; iy < L; ++iy)
        for (int ix = 0; ix < L; ++ix) d.prbuf[size_t(iy) * P + ix] = r(index(site(ix, iy), b));
      fftw_execute_dft_r2c(d.pfwd, d.prbuf, d.pcbuf[b]);
    }
    std::complex<double> in[3], out[3];
    for (size_t q = 0; q < pc; ++q) {
      for (int b = 0; b < nc; ++b) in[b] = {d.pcbuf[b][q][0], d.pcbuf[b][q][1]};
      for (int a = 0; a < nc; ++a) {
        out[a] = 0.0;
        for (int b = 0; b < nc; ++b) out[a] += d.pinv[q * nc * nc + a * nc + b] * in[b];
      }
      for (int a = 0; a < nc; ++a) {
        d.pcbuf[a][q][0] = out[a].real();
        d.pcbuf[a][q][1] = out[a].imag();
      }
    }
    z.resize(r.size());
    const double norm = 1.0 / (double(P) * P);
    for (int a = 0; a < nc; ++a) {
      fftw_execute_dft_c2r(d.pbwd, d.pcbuf[a], d.prbuf);
      for (int iy = 0; iy < L; ++iy)
        for (int ix = 0; ix < L; ++ix) {
          const int i = site(ix, iy);
          z(index(i, a)) = kappa[i] > 0.0 ? norm * d.prbuf[size_t(iy) * P + ix] : 0.0;
        }
    }
  }
}

Eigen::VectorXd GreenSolver::solve(const std::vector<double> &kappa, const Eigen::VectorXd &u,
                                   GreenSolveStats *stats) const
{
  const int N = sites();
  if (int(kappa.size()) != N) throw std::invalid_argument("solve: kappa must have one entry per site");
  if (u.size() != nc * N) throw std::invalid_argument("solve: right-hand side has the wrong length");
  for (double k : kappa)
    if (!(k >= 0.0) || !std::isfinite(k))
      throw std::invalid_argument("solve: contact stiffness kappa must be finite and >= 0");
  GreenSolveStats st;
  const double t0 = now();
  Eigen::VectorXd f = opt.method == GreenMethod::DENSE ? solve_dense(kappa, u, &st)
                                                       : solve_cg(kappa, u, &st);
  st.seconds = now() - t0;
  if (!f.allFinite()) throw std::runtime_error("Green solver produced non-finite forces");
  if (stats) *stats = st;
  return f;
}

Eigen::VectorXd GreenSolver::solve_dense(const std::vector<double> &kappa, const Eigen::VectorXd &u,
                                         GreenSolveStats *stats) const
{
  const int N = sites();
  std::vector<int> act;
  for (int i = 0; i < N; ++i)
    if (kappa[i] > 0.0)
      for (int a = 0; a < nc; ++a) act.push_back(index(i, a));
  const int n = int(act.size());
  Eigen::MatrixXd A(n, n);
  Eigen::VectorXd b(n);
  for (int p = 0; p < n; ++p) {
    for (int q = 0; q < n; ++q) A(p, q) = par.gamma1 * dense(act[p], act[q]);
    A(p, p) += 1.0 / kappa[act[p] / nc];
    b(p) = u(act[p]);
  }
  Eigen::LLT<Eigen::MatrixXd> llt(A);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error("dense Green system is not positive definite (gamma2 too large?)");
  const Eigen::VectorXd x = llt.solve(b);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(nc * N);
  for (int p = 0; p < n; ++p) f(act[p]) = x(p);
  stats->iterations = 0;
  const double bn = b.norm();
  stats->residual = bn > 0.0 ? (A * x - b).norm() / bn : 0.0;
  return f;
}

// preconditioned conjugate gradients on the active sites (inactive entries
// of every vector are kept at zero, so the operator stays symmetric).
//
// A CG cycle stops when the recursive residual r (updated as r -= alpha A p)
// drops below tol.  The recursive residual drifts from the true one,
// b - A x, by round-off (about eps times the condition number), so the true
// residual is then computed once; it is the one reported and the one the
// tolerance applies to, with no margin: a solve returns only if
// |b - A x| / |b| < tol.  Otherwise CG restarts from the true residual (at
// most max_restarts times, within maxiter iterations in all); a restart that
// does not halve the true residual means it has reached its round-off floor,
// and the solve fails with an error naming tol and the attainable residual.
Eigen::VectorXd GreenSolver::solve_cg(const std::vector<double> &kappa, const Eigen::VectorXd &u,
                                      GreenSolveStats *stats) const
{
  const int N = sites();
  Eigen::VectorXd invk(nc * N), mask(nc * N);
  for (int i = 0; i < N; ++i)
    for (int a = 0; a < nc; ++a) {
      mask(index(i, a)) = kappa[i] > 0.0 ? 1.0 : 0.0;
      invk(index(i, a)) = kappa[i] > 0.0 ? 1.0 / kappa[i] : 0.0;
    }
  auto op = [&](const Eigen::VectorXd &v) -> Eigen::VectorXd {
    Eigen::VectorXd y = par.gamma1 * apply_green(v);
    return (invk.array() * v.array() + mask.array() * y.array()).matrix();
  };
  const Eigen::VectorXd b = (mask.array() * u.array()).matrix();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(nc * N);
  const double bn = b.norm();
  stats->iterations = 0;
  stats->restarts = 0;
  stats->residual = 0.0;
  if (bn == 0.0) return x;
  Eigen::VectorXd r = b, z, p, Ap;
  int it = 0, restarts = 0;
  double truerel = 1.0, prev = HUGE_VAL;
  for (;;) {
    // one CG cycle from (x, r)
    precondition(kappa, r, z);
    p = z;
    double rz = r.dot(z);
    double rel = r.norm() / bn;
    while (rel >= opt.tol && it < opt.maxiter) {
      Ap = op(p);
      const double pAp = p.dot(Ap);
      if (!(pAp > 0.0))
        throw std::runtime_error("Green operator is not positive definite (CG curvature " + num(pAp) +
                                 "); gamma2 too large for this lattice?");
      const double alpha = rz / pAp;
      x += alpha * p;
      r -= alpha * Ap;
      ++it;
      rel = r.norm() / bn;
      if (!std::isfinite(rel)) throw std::runtime_error("Green CG diverged (non-finite residual)");
      if (rel < opt.tol) break;
      precondition(kappa, r, z);
      const double rz1 = r.dot(z);
      p = z + (rz1 / rz) * p;
      rz = rz1;
    }
    // the true residual
    r = b - op(x);
    truerel = r.norm() / bn;
    if (truerel < opt.tol) break;
    if (it >= opt.maxiter)
      throw std::runtime_error("Green CG did not converge in " + std::to_string(opt.maxiter) +
                               " iterations (true relative residual " + num(truerel, 3) + ", tol " +
                               num(opt.tol) + "); raise maxiter or tol");
    if (restarts >= opt.max_restarts || !(truerel < 0.5 * prev))
      throw std::runtime_error(
          "Green CG: tol " + num(opt.tol) + " is below the attainable accuracy: the true relative "
          "residual |b - A x|/|b| stays at " + num(truerel, 3) + " (round-off floor; the recursive CG "
          "residual is below tol) after " + std::to_string(restarts) + " restart(s) from the true "
          "residual; use tol >= " + num(10.0 * truerel, 2));
    prev = truerel;
    ++restarts;
  }
  stats->iterations = it;
  stats->restarts = restarts;
  stats->residual = truerel;
  return x;
}

/* ---------------------------------------------------------------------- */

GreenRemoval green_remove_contact(const GreenSolver &s, int removed)
{
  const int N = s.sites(), nc = s.ncomp();
  if (removed < 0 || removed >= N) throw std::invalid_argument("removed contact out of range");
  GreenRemoval R;
  R.removed = removed;
  std::vector<double> kappa(N, 1.0);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(nc * N);
  for (int i = 0; i < N; ++i) u(s.index(i, 0)) = 1.0;    // U0 = u0 x-hat
  R.f = s.solve(kappa, u, &R.st_state);
  R.stretch = u - s.params().gamma1 * s.apply_green(R.f);
  // exact: without the contact
  std::vector<double> k2 = kappa;
  k2[removed] = 0.0;
  R.df_exact = s.solve(k2, u, &R.st_removed) - R.f;
  // Eq. int.eq09: dF = B dK (1 - G B K) U0 with dK = -K at the removed
  // contact; (1 - G B K) U0 = U0 - G F is the stretch; B w solves
  // (1 + K G) z = w, i.e. (1/kappa + gamma1 Gh) z = w / kappa.
  Eigen::VectorXd w = Eigen::VectorXd::Zero(nc * N);
  for (int a = 0; a < nc; ++a) {
    const int k = s.index(removed, a);
    w(k) = -kappa[removed] * R.stretch(k) / kappa[removed];
  }
  R.df_linear = s.solve(kappa, w, &R.st_linear);
  return R;
}

Eigen::VectorXd green_slip_response(const GreenSolver &s, int j, GreenSolveStats *st, int comp)
{
  const int N = s.sites();
  if (j < 0 || j >= N) throw std::invalid_argument("slip site out of range");
  if (comp < 0 || comp >= s.ncomp())
    throw std::invalid_argument("slip component must be in [0, " + std::to_string(s.ncomp() - 1) +
                                "], got " + std::to_string(comp));
  Eigen::VectorXd e = Eigen::VectorXd::Zero(s.ncomp() * N);
  e(s.index(j, comp)) = 1.0;
  return s.solve(std::vector<double>(N, 1.0), e, st);
}

Eigen::MatrixXd green_site_block(const GreenSolver &s, int j, const Eigen::VectorXd *zx,
                                 GreenSolveStats *st)
{
  const int nc = s.ncomp();
  Eigen::MatrixXd C(nc, nc);
  GreenSolveStats worst, one;
  for (int b = 0; b < nc; ++b) {
    Eigen::VectorXd z;
    if (b == 0 && zx) {
      if (zx->size() != nc * s.sites())
        throw std::invalid_argument("green_site_block: x slip response has the wrong length");
      z = *zx;
    } else {
      z = green_slip_response(s, j, &one, b);
      worst.iterations = std::max(worst.iterations, one.iterations);
      worst.restarts = std::max(worst.restarts, one.restarts);
      worst.residual = std::max(worst.residual, one.residual);
      worst.seconds += one.seconds;
    }
    for (int a = 0; a < nc; ++a) C(a, b) = z(s.index(j, a));
  }
  if (st) *st = worst;
  return 0.5 * (C + C.transpose());
}

double green_reciprocity_sum(const Eigen::VectorXd &fJ, const Eigen::MatrixXd &CJJ)
{
  if (CJJ.rows() != fJ.size() || CJJ.cols() != fJ.size())
    throw std::invalid_argument("green_reciprocity_sum: block and force sizes differ");
  return -fJ.dot(CJJ.ldlt().solve(fJ));
}

GreenKernel green_axis_kernel(const GreenSolver &s, const Eigen::VectorXd &z, int j, int rmax)
{
  const int L = s.L(), jx = j % L, jy = j / L;
  if (rmax < 1 || jx + rmax >= L || jy + rmax >= L)
    throw std::invalid_argument("rmax " + std::to_string(rmax) + " does not fit in the lattice (L = " +
                                std::to_string(L) + ")");
  GreenKernel k;
  for (int r = 1; r <= rmax; ++r) {
    k.r.push_back(r);
    k.kx.push_back(-z(s.index(s.site(jx + r, jy), 0)));
    k.ky.push_back(-z(s.index(s.site(jx, jy + r), 0)));
  }
  return k;
}

void write_green_table(const std::string &file, const std::string &keyword, const GreenKernel &k,
                       double kc, bool aniso, const std::vector<std::string> &comments)
{
  if (keyword.empty() || keyword.find_first_of(" \t\n#") != std::string::npos)
    throw std::invalid_argument("table keyword must be one word, got '" + keyword + "'");
  std::ofstream out(file);
  if (!out) throw std::runtime_error("cannot open table file '" + file + "' for writing");
  for (const auto &c : comments) out << "# " << c << "\n";
  out << "\n" << keyword << "\n";
  out << "N " << k.r.size() << (aniso ? " aniso" : "") << "\n\n";
  out << std::setprecision(10);
  for (size_t i = 0; i < k.r.size(); ++i) {
    out << (i + 1) << " " << k.r[i] << " " << kc * 0.5 * (k.kx[i] + k.ky[i]);
    if (aniso) out << " " << kc * 0.5 * (k.kx[i] - k.ky[i]);
    out << "\n";
  }
  if (!out) throw std::runtime_error("error writing table file '" + file + "'");
}

PowerFit fit_power_law(const std::vector<double> &r, const std::vector<double> &y, double rmin,
                       double rmax)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  std::vector<double> lx, ly;
  for (size_t i = 0; i < r.size(); ++i)
    if (r[i] >= rmin && r[i] <= rmax && y[i] != 0.0) {
      const double a = std::log(r[i]), b = std::log(std::fabs(y[i]));
      lx.push_back(a);
      ly.push_back(b);
      sx += a;
      sy += b;
      sxx += a * a;
      sxy += a * b;
      ++n;
    }
  PowerFit f;
  f.points = n;
  if (n < 2) return f;
  const double den = n * sxx - sx * sx;
  f.exponent = (n * sxy - sx * sy) / den;
  const double la = (sy - f.exponent * sx) / n;
  f.amplitude = std::exp(la);
  double e = 0;
  for (int i = 0; i < n; ++i) e += std::pow(ly[i] - la - f.exponent * lx[i], 2);
  f.rms = std::sqrt(e / n);
  return f;
}

double continuum_kernel_psi(double rho)
{
  if (!(rho > 0.0)) throw std::invalid_argument("continuum_kernel_psi: rho must be > 0");
  if (rho >= 25.0) {
    // asymptotic series (pi/2)(H0 - Y0)(x) = 1/x - 1/x^3 + 9/x^5 - 225/x^7 + ...,
    // term ratio -((2k+1)/x)^2: at x >= 25 it is converged to round-off
    double sum = 0.0, term = 1.0 / (rho * rho * rho);
    for (int k = 1; k < 12; ++k) {
      sum += term;
      term *= -double((2 * k + 1) * (2 * k + 1)) / (rho * rho);
    }
    return sum / (2.0 * PI);
  }
  // (pi/2)(H0 - Y0)(rho) = int_0^inf exp(-rho sinh s) ds: composite 8-point
  // Gauss-Legendre on panels of width 0.05 up to rho sinh s = 45
  static const double xg[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
  static const double wg[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};
  const double H = 0.05, smax = std::asinh(45.0 / rho);
  double I = 0.0;
  for (double a = 0.0; a < smax; a += H) {
    const double m = a + 0.5 * H;
    for (int k = 0; k < 4; ++k)
      for (int sg = -1; sg <= 1; sg += 2)
        I += 0.5 * H * wg[k] * std::exp(-rho * std::sinh(m + sg * 0.5 * H * xg[k]));
  }
  return (1.0 / rho - I) / (2.0 * PI);
}

CrossoverFit fit_crossover(const std::vector<double> &r, const std::vector<double> &y, double rmin,
                           double rmax, double lo, double hi, CrossoverShape shape)
{
  std::vector<double> rr, ly;
  for (size_t i = 0; i < r.size(); ++i)
    if (r[i] >= rmin && r[i] <= rmax && y[i] != 0.0) {
      rr.push_back(r[i]);
      ly.push_back(std::log(std::fabs(y[i])));
    }
  CrossoverFit best;
  best.points = int(rr.size());
  if (rr.size() < 3) return best;
  // for a given lambda the optimal log A is the mean residual
  // log of the shape function (up to the amplitude) at distance x
  auto lshape = [&](double x, double lam) {
    if (shape == CrossoverShape::ALGEBRAIC) return -std::log(x * (1.0 + x * x / (lam * lam)));
    return std::log(continuum_kernel_psi(x / lam));
  };
  auto cost = [&](double lam, double *logA) {
    std::vector<double> d(rr.size());
    double m = 0;
    for (size_t i = 0; i < rr.size(); ++i) {
      d[i] = ly[i] - lshape(rr[i], lam);
      m += d[i];
    }
    m /= rr.size();
    double e = 0;
    for (size_t i = 0; i < rr.size(); ++i) e += (d[i] - m) * (d[i] - m);
    if (logA) *logA = m;
    return e / rr.size();
  };
  // coarse logarithmic scan, then golden section around the best point
  const int n = shape == CrossoverShape::ALGEBRAIC ? 400 : 120;
  double bl = std::log(lo), bc = 1e300;
  for (int k = 0; k <= n; ++k) {
    const double l = std::log(lo) + (std::log(hi) - std::log(lo)) * k / n;
    const double c = cost(std::exp(l), nullptr);
    if (c < bc) {
      bc = c;
      bl = l;
    }
  }
  const double step = (std::log(hi) - std::log(lo)) / n;
  double a = bl - step, b = bl + step;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int k = 0; k < 80; ++k) {
    const double c1 = b - g * (b - a), c2 = a + g * (b - a);
    if (cost(std::exp(c1), nullptr) < cost(std::exp(c2), nullptr))
      b = c2;
    else
      a = c1;
  }
  double logA;
  best.lambda = std::exp(0.5 * (a + b));
  best.rms = std::sqrt(cost(best.lambda, &logA));
  best.amplitude = std::exp(logA);
  return best;
}

size_t peak_rss_bytes()
{
  struct rusage ru;
  if (getrusage(RUSAGE_SELF, &ru) != 0) return 0;
  return size_t(ru.ru_maxrss) * 1024;    // kilobytes on Linux
}

}    // namespace feq
