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
   FRICTION-EQ package: elastic interaction between contacts from the
   surface Green tensor of two isotropic half-spaces (paper Sec. III).

   N contacts on an L x L square lattice (spacing a = 1) couple the top and
   bottom substrates.  With F the contact forces, U0 the imposed stressed
   state, K = diag(k_i) and G = G_top + G_bottom (Eq. int.eq02),

       F = K (U0 - G F)          <=>   F = B K U0,  B = (1 + K G)^-1.

   Units: forces in k_c u0, displacements in u0, lengths in a, stiffnesses
   in k_c (k_i = k_c kappa_i).  With gamma1 = k_c / (E_* a) the system is

       (diag(1/kappa) + gamma1 Gh) f = u,                          (*)

   Gh the dimensionless tensor E_* a G: for a site-to-site vector (dx, dy),
   r = |(dx, dy)|, c = (1 + sigma) / (2 pi r),
       xx = c [2(1-sigma) + 2 sigma dx^2/r^2],   xy = c 2 sigma dx dy/r^2,
       yy = c [2(1-sigma) + 2 sigma dy^2/r^2],   zz = c 2 (1-sigma),
       xz = -zx = -c m (1-2 sigma) dx/r,         yz = -zy = -c m (1-2 sigma) dy/r,
   where m = E_* / E_top - E_* / E_bottom (0 for identical substrates: then the
   normal components decouple and, with U0 along x, carry no force, so only
   the 2N in-plane unknowns are solved).  The self term (r = 0) is cut off at
   r_c = gamma2 a and averaged over directions (<dx^2/r^2> = 1/2):
       xx = yy = (1+sigma)(2-sigma) / (2 pi gamma2),  zz = (1+sigma)(1-sigma) / (pi gamma2).
   Removed contacts (kappa_i = 0) carry no force: (*) is solved on the
   remaining sites.  The matrix of (*) is symmetric (and positive definite
   for the parameters of the paper; the solver checks CG curvature).

   Two independent paths:
     FFT    the lattice operator is a block convolution: zero-padded M x M
            r2c FFTs, M >= 2L-1 the next size with factors 2,3,5,7 (open
            array), or the L x L minimum-image kernel (periodic images: the
            kernel is truncated at the box faces, which distorts the far
            field along the axes beyond about L/10 when gamma1 is large; use
            the open array for the kernel); preconditioned conjugate gradients,
            O(N log N) per iteration.  Preconditioner: the circulant
            (Strang) approximation of (*) with kappa = 1 inverted per wave
            vector (exact for a periodic intact lattice), or Jacobi, or none.
     DENSE  the (nc N)^2 matrix assembled entry by entry, Cholesky (Eigen
            LLT); for checks on small lattices only.
   LAMMPS-free.
------------------------------------------------------------------------- */

#ifndef FEQ_GREEN_H
#define FEQ_GREEN_H

#include <Eigen/Dense>

#include <complex>
#include <memory>
#include <string>
#include <vector>

namespace feq {

struct GreenParams {
  int L = 89;               // L x L square lattice, a = 1
  double gamma1 = 0.06;     // k_c / (E_* a)
  double gamma2 = 0.3;      // self-term cutoff r_c / a
  double sigma = 0.3;       // Poisson ratio of both substrates
  double mismatch = 0.0;    // m = E_* / E_top - E_* / E_bottom, |m| < 1
  bool periodic = false;    // minimum-image periodic lattice instead of an open array
};

enum class GreenMethod { FFT, DENSE };
enum class GreenPrecond { CIRCULANT, JACOBI, NONE };

struct GreenOptions {
  GreenMethod method = GreenMethod::FFT;
  GreenPrecond precond = GreenPrecond::CIRCULANT;
  double tol = 1e-12;       // true relative residual |rhs - A f| / |rhs| of the CG solve
  int maxiter = 20000;      // CG iterations in all (restarts included)
  int max_restarts = 5;     // CG restarts from the true residual (see solve_cg)
  size_t dense_limit = 8000;    // largest nc N accepted by the dense path
};

struct GreenSolveStats {
  int iterations = 0;       // CG iterations, restarts included (0 for the dense path)
  int restarts = 0;         // CG restarts from the true residual
  double residual = 0.0;    // true relative residual |rhs - A f| / |rhs|, recomputed
  double seconds = 0.0;
};

// Throws std::invalid_argument naming the parameter on bad input.
void check_green_params(const GreenParams &p);

// The dimensionless block Gh(dx, dy) (nc x nc, nc = 2 or 3); (0,0) is the
// cut-off self term.  Used by the dense path and by the tests.
Eigen::Matrix3d green_block(double dx, double dy, const GreenParams &p);

class GreenSolver {
 public:
  GreenSolver(const GreenParams &p, const GreenOptions &o = GreenOptions());
  ~GreenSolver();
  GreenSolver(const GreenSolver &) = delete;
  GreenSolver &operator=(const GreenSolver &) = delete;

  int L() const { return par.L; }
  int sites() const { return par.L * par.L; }
  int ncomp() const { return nc; }    // 2 (in-plane) or 3 (m != 0)
  int index(int site, int comp) const { return nc * site + comp; }
  int site(int ix, int iy) const { return iy * par.L + ix; }
  int centre() const { return site(par.L / 2, par.L / 2); }
  const GreenParams &params() const { return par; }
  const GreenOptions &options() const { return opt; }

  // y = Gh v on the whole lattice (FFT convolution or dense product)
  Eigen::VectorXd apply_green(const Eigen::VectorXd &v) const;

  // Solves (*) for per-site relative stiffness kappa (>= 0; 0 = removed
  // contact, its force is 0) and right-hand side u (length nc N).
  Eigen::VectorXd solve(const std::vector<double> &kappa, const Eigen::VectorXd &u,
                        GreenSolveStats *stats = nullptr) const;

  // Bytes held by the operator (FFT kernels, buffers, preconditioner or
  // dense matrix), for the benchmark.
  size_t memory_bytes() const;
  std::string describe() const;
  // true if the solves use the circulant preconditioner (false: Jacobi or
  // none, including the fallback when the circulant is not positive definite)
  bool circulant_active() const;

 private:
  GreenParams par;
  GreenOptions opt;
  int nc;
  struct FFTData;
  std::unique_ptr<FFTData> fft;
  Eigen::MatrixXd dense;    // Gh on the full lattice (dense path)
  Eigen::VectorXd diag_g;   // diagonal of Gh (Jacobi)

  void setup_fft();
  void precondition(const std::vector<double> &kappa, const Eigen::VectorXd &r,
                    Eigen::VectorXd &z) const;
  Eigen::VectorXd solve_cg(const std::vector<double> &kappa, const Eigen::VectorXd &u,
                           GreenSolveStats *stats) const;
  Eigen::VectorXd solve_dense(const std::vector<double> &kappa, const Eigen::VectorXd &u,
                              GreenSolveStats *stats) const;
};

// Removal of contact `removed` from the intact lattice (kappa = 1) in the
// uniform stressed state U0 = u0 x-hat.
struct GreenRemoval {
  int removed = -1;
  Eigen::VectorXd f;           // stressed state F / (k_c u0)
  Eigen::VectorXd stretch;     // (U0 + U) / u0 = u - gamma1 Gh f  (= f / kappa)
  Eigen::VectorXd df_exact;    // f(without the contact) - f(with it)
  Eigen::VectorXd df_linear;   // Eq. int.eq09: B dK (1 - G B K) U0
  GreenSolveStats st_state, st_removed, st_linear;
};
GreenRemoval green_remove_contact(const GreenSolver &s, int removed);

// Response to a unit slip of the rest position of contact j along x (the
// contact breaks and re-forms relaxed): z = (1/kappa + gamma1 Gh)^-1 e_jx.
// The force on contact i changes by -k_c z_i Delta for a slip Delta, so the
// pair coupling of pair_style eq/elastic is k_ij / k_c = -z_{ix} (i != j).
// comp = 1 (y) or 2 (z, mismatch only) gives the response to a slip along y or z.
Eigen::VectorXd green_slip_response(const GreenSolver &s, int j, GreenSolveStats *st = nullptr,
                                    int comp = 0);

// nc x nc block C_JJ of C = (1 + gamma1 Gh)^-1 (the paper's B for kappa = 1)
// at site j, from the nc slip responses of j (symmetrised).  `zx` may pass
// the x slip response if it is already known (saves one solve).
Eigen::MatrixXd green_site_block(const GreenSolver &s, int j, const Eigen::VectorXd *zx = nullptr,
                                 GreenSolveStats *st = nullptr);

// Betti reciprocity for the removal of contact j from the intact lattice in
// the state U0 = u0 x-hat: with C = (1 + gamma1 Gh)^-1 symmetric, f = C u and
// the removal a constraint force t on site j (f'_J = 0: t = C_JJ^-1 f_J),
//   df = -C_(:,J) C_JJ^-1 f_J,   sum_i df_ix = u^T df = -f_J^T C_JJ^-1 f_J,
// f_J the nc force components of j.  Returns that sum (units k_c u0).
double green_reciprocity_sum(const Eigen::VectorXd &fJ, const Eigen::MatrixXd &CJJ);

// Kernel along the axes from a slip response at site j: kx(r) = -z_x at
// (jx + r, jy), ky(r) = -z_x at (jx, jy + r), r = 1..rmax, in units of k_c.
struct GreenKernel {
  std::vector<double> r, kx, ky;
};
GreenKernel green_axis_kernel(const GreenSolver &s, const Eigen::VectorXd &z, int j, int rmax);

// Writes the pair_style eq/elastic table: comment lines, KEYWORD,
// "N n [aniso]", rows "i r k0 [k2]" with k0 = kc (kx + ky)/2,
// k2 = kc (kx - ky)/2.  Throws std::runtime_error if it cannot write.
void write_green_table(const std::string &file, const std::string &keyword,
                       const GreenKernel &k, double kc, bool aniso,
                       const std::vector<std::string> &comments);

// Least-squares fit of log|y| = log A + p log r over rmin <= r <= rmax.
struct PowerFit {
  double exponent = 0.0, amplitude = 0.0, rms = 0.0;    // rms of the log residual
  int points = 0;
};
PowerFit fit_power_law(const std::vector<double> &r, const std::vector<double> &y, double rmin,
                       double rmax);

// Fit of y = A / (r (1 + (r/lambda)^2)) (r^-1 for r << lambda, A lambda^2 / r^3
// beyond) in log space over rmin <= r <= rmax; lambda searched in [lo, hi].
struct CrossoverFit {
  double lambda = 0.0, amplitude = 0.0, rms = 0.0;
  int points = 0;
};
// shape ALGEBRAIC: y = A / (r (1 + (r/lambda)^2));
// shape CONTINUUM: y = A psi(r / lambda) with psi the isotropic continuum
// slip kernel (springs of density k_c / a^2 between half-spaces, G(q) ~ 1/q):
//   psi(rho) = (1/2pi) int_0^inf J0(p rho) p dp / (1 + p)
//            = (1/2pi) [1/rho - (pi/2)(H0(rho) - Y0(rho))]   (Struve, Neumann)
// -> 1/(2 pi rho) for rho << 1 (with logarithmic corrections), 1/(2 pi rho^3)
// for rho >> 1.  Both shapes have the asymptotes A'/r and A' lambda^2/r^3,
// which cross at r = lambda.
enum class CrossoverShape { ALGEBRAIC, CONTINUUM };
CrossoverFit fit_crossover(const std::vector<double> &r, const std::vector<double> &y, double rmin,
                           double rmax, double lo = 0.1, double hi = 1e4,
                           CrossoverShape shape = CrossoverShape::ALGEBRAIC);
double continuum_kernel_psi(double rho);

// Peak resident memory of this process in bytes (getrusage), 0 if unknown.
size_t peak_rss_bytes();

}    // namespace feq

#endif
