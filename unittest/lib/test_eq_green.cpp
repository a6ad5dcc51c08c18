// Unit tests: surface Green tensor solver (paper Sec. III) against the dense
// Cholesky path, the paper's finite-dK formula, Sherman-Morrison and Betti
// reciprocity identities, lattice symmetry, first-order perturbation theory
// and the power laws of the interaction (r^-1 near, r^-3 far).
#include "eq_green.h"

#include "gtest/gtest.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

using namespace feq;

namespace {

const double PI = 3.14159265358979323846;

GreenParams params(int L, double g1, bool periodic = false, double m = 0.0)
{
  GreenParams p;
  p.L = L;
  p.gamma1 = g1;
  p.periodic = periodic;
  p.mismatch = m;
  return p;
}

GreenOptions dense_opt()
{
  GreenOptions o;
  o.method = GreenMethod::DENSE;
  return o;
}

double rel_diff(const Eigen::VectorXd &a, const Eigen::VectorXd &b)
{
  return (a - b).lpNorm<Eigen::Infinity>() / b.lpNorm<Eigen::Infinity>();
}

// profile of df_x along +x from the centre of an L x L lattice
void profile(const GreenSolver &s, const Eigen::VectorXd &df, std::vector<double> &r,
             std::vector<double> &y)
{
  const int c = s.L() / 2;
  r.clear();
  y.clear();
  for (int k = 1; c + k < s.L(); ++k) {
    r.push_back(k);
    y.push_back(df(s.index(s.site(c + k, c), 0)));
  }
}

}    // namespace

TEST(GreenBlock, LandauLifshitzElementsAndSymmetry)
{
  GreenParams p = params(5, 0.1, false, 0.4);
  const double s = p.sigma;
  // along x at r = 2: xx = (1+s)/(2 pi 2) * 2, yy = (1+s)/(2 pi 2) * 2(1-s)
  const Eigen::Matrix3d g = green_block(2.0, 0.0, p);
  EXPECT_NEAR(g(0, 0), (1 + s) / (4 * PI) * 2.0, 1e-15);
  EXPECT_NEAR(g(1, 1), (1 + s) / (4 * PI) * 2.0 * (1 - s), 1e-15);
  EXPECT_NEAR(g(0, 1), 0.0, 1e-15);
  EXPECT_NEAR(g(0, 2), -(1 + s) / (4 * PI) * 0.4 * (1 - 2 * s), 1e-15);
  // G_(ia,jb) = G_(jb,ia): block(d) = block(-d)^T, for any direction
  for (double dx : {-3.0, 0.5, 2.0})
    for (double dy : {-1.0, 0.0, 4.0}) {
      const Eigen::Matrix3d a = green_block(dx, dy, p), b = green_block(-dx, -dy, p);
      EXPECT_LT((a - b.transpose()).cwiseAbs().maxCoeff(), 1e-15);
      // rotation covariance of the in-plane part: rotate by 90 degrees
      const Eigen::Matrix3d c = green_block(-dy, dx, p);
      Eigen::Matrix2d R;
      R << 0, -1, 1, 0;
      const Eigen::Matrix2d rot = R * a.topLeftCorner<2, 2>() * R.transpose();
      EXPECT_LT((rot - c.topLeftCorner<2, 2>()).cwiseAbs().maxCoeff(), 1e-14);
    }
  // self term: direction average of the r = r_c element
  const Eigen::Matrix3d g0 = green_block(0.0, 0.0, p);
  const Eigen::Matrix3d gx = green_block(p.gamma2, 0.0, p), gy = green_block(0.0, p.gamma2, p);
  EXPECT_NEAR(g0(0, 0), 0.5 * (gx(0, 0) + gy(0, 0)), 1e-14);
  EXPECT_NEAR(g0(2, 2), gx(2, 2), 1e-14);
}

// The full 3 x 3 block at off-axis points (where xy, yz and the x-y
// asymmetry of xx, yy are all nonzero) against the paper's Eq. int.eq02,
// written out here independently of green_block: the Landau-Lifshitz tensor
// of each substrate with its own Young modulus, the bottom one with the
// opposite sign of the xz / zx (and yz / zy) elements, summed and scaled by
// E_* a (E_*^-1 = E_top^-1 + E_bottom^-1).
TEST(GreenBlock, OffAxisFullBlockAgainstPaperEq02)
{
  const double Etop = 1.0, Ebot = 3.0;
  const double Estar = 1.0 / (1.0 / Etop + 1.0 / Ebot);    // 0.75
  for (double sg : {0.3, 0.25, -0.2})
    for (const auto &d : {std::make_pair(3.0, 2.0), std::make_pair(-1.5, 2.5),
                          std::make_pair(2.0, -3.0), std::make_pair(-4.0, -1.0)}) {
      const double x = d.first, y = d.second, r = std::sqrt(x * x + y * y);
      // one substrate, Eq. int.eq02 (u_i = G_ij f_j, x = x_i - x_j)
      auto LL = [&](double E, double zsign) {
        const double g = (1 + sg) / (2 * PI * E * r);
        Eigen::Matrix3d G;
        G(0, 0) = g * (2 * (1 - sg) + 2 * sg * x * x / (r * r));
        G(0, 1) = 2 * g * sg * x * y / (r * r);
        G(1, 0) = G(0, 1);
        G(1, 1) = g * (2 * (1 - sg) + 2 * sg * y * y / (r * r));
        G(0, 2) = -zsign * g * (1 - 2 * sg) * x / r;
        G(1, 2) = -zsign * g * (1 - 2 * sg) * y / r;
        G(2, 0) = -G(0, 2);
        G(2, 1) = -G(1, 2);
        G(2, 2) = 2 * g * (1 - sg);
        return G;
      };
      const Eigen::Matrix3d expect = Estar * (LL(Etop, +1.0) + LL(Ebot, -1.0));
      GreenParams p = params(9, 0.1, false, Estar / Etop - Estar / Ebot);    // m = 0.5
      p.sigma = sg;
      const Eigen::Matrix3d g = green_block(x, y, p);
      EXPECT_LT((g - expect).cwiseAbs().maxCoeff(), 1e-15) << "sigma " << sg << " at " << x << ","
                                                           << y << "\n" << g << "\n" << expect;
      // identical substrates: the z coupling vanishes
      p.mismatch = 0.0;
      const Eigen::Matrix3d e0 = 0.5 * (LL(1.0, +1.0) + LL(1.0, -1.0));    // E_* = E / 2
      EXPECT_LT((green_block(x, y, p) - e0).cwiseAbs().maxCoeff(), 1e-15);
      EXPECT_EQ(green_block(x, y, p)(0, 2), 0.0);
    }
  // one value by hand: (3, 2), sigma = 0.3, m = 0: xy = 2 (1.3 / (2 pi sqrt 13))
  // * 0.3 * 6 / 13 (both substrates, times E_* = E / 2)
  GreenParams p = params(9, 0.1);
  EXPECT_NEAR(green_block(3.0, 2.0, p)(0, 1), 2 * 1.3 / (2 * PI * std::sqrt(13.0)) * 0.3 * 6 / 13,
              1e-16);
}

TEST(GreenSolver, FFTConvolutionEqualsDenseProduct)
{
  for (bool periodic : {false, true})
    for (int L : {5, 7, 12, 41})    // FFT boxes 9, 14, 24, 81 (odd and even)
      for (double m : {0.0, 0.5}) {
        const GreenParams p = params(L, 0.3, periodic, m);
        GreenSolver f(p), d(p, dense_opt());
        ASSERT_EQ(f.ncomp(), m == 0.0 ? 2 : 3);
        Eigen::VectorXd v = Eigen::VectorXd::Random(f.ncomp() * f.sites());
        EXPECT_LT(rel_diff(f.apply_green(v), d.apply_green(v)), 1e-12)
            << "L " << L << " periodic " << periodic << " m " << m;
      }
}

TEST(GreenSolver, FFTSolveEqualsDenseSolve)
{
  // acceptance: agreement to 1e-10 on small lattices, every preconditioner,
  // open and periodic, removed contacts and non-uniform stiffness
  for (bool periodic : {false, true})
    for (double g1 : {0.06, 0.8})
      for (GreenPrecond pc : {GreenPrecond::CIRCULANT, GreenPrecond::JACOBI, GreenPrecond::NONE}) {
        const GreenParams p = params(15, g1, periodic, periodic ? 0.0 : 0.3);
        GreenOptions o;
        o.precond = pc;
        o.tol = 1e-13;
        GreenSolver f(p, o), d(p, dense_opt());
        const int N = f.sites();
        std::vector<double> kappa(N);
        for (int i = 0; i < N; ++i) kappa[i] = 0.5 + 0.9 * std::fabs(std::sin(1.7 * i));
        kappa[f.centre()] = 0.0;
        kappa[3] = 0.0;
        Eigen::VectorXd u = Eigen::VectorXd::Random(f.ncomp() * N);
        GreenSolveStats sf, sd;
        const Eigen::VectorXd xf = f.solve(kappa, u, &sf), xd = d.solve(kappa, u, &sd);
        EXPECT_LT(rel_diff(xf, xd), 1e-10) << "gamma1 " << g1 << " periodic " << periodic;
        EXPECT_LT(sd.residual, 1e-12);
        EXPECT_GT(sf.iterations, 0);
        // removed contacts carry no force
        for (int a = 0; a < f.ncomp(); ++a) EXPECT_EQ(xf(f.index(f.centre(), a)), 0.0);
      }
}

TEST(GreenSolver, CirculantPreconditionerIsExactOnIntactPeriodicLattice)
{
  const GreenParams p = params(32, 0.8, true);
  GreenSolver s(p);
  GreenSolveStats st;
  Eigen::VectorXd u = Eigen::VectorXd::Random(s.ncomp() * s.sites());
  s.solve(std::vector<double>(s.sites(), 1.0), u, &st);
  EXPECT_EQ(st.iterations, 1);
  // open array: the circulant preconditioner beats Jacobi (measured: 12
  // against 38 iterations at gamma1 = 0.8, 10 against 16 at gamma1 = 0.06)
  GreenOptions oj;
  oj.precond = GreenPrecond::JACOBI;
  GreenSolver sc(params(61, 0.8)), sj(params(61, 0.8), oj);
  GreenRemoval rc = green_remove_contact(sc, sc.centre());
  GreenRemoval rj = green_remove_contact(sj, sj.centre());
  EXPECT_LT(2 * rc.st_state.iterations, rj.st_state.iterations);
  EXPECT_LT(rel_diff(rc.df_exact, rj.df_exact), 1e-9);
}

TEST(GreenRemoval, PaperFiniteDeltaKFormulaAndShermanMorrison)
{
  // dense L = 9: dF = B dK (1 - G B Kt) U0, Kt = (1 + dK G B)^-1 (K + dK)
  // (the paper's finite-dK expression) equals the difference of the two
  // solves; Eq. int.eq09 differs from it by the factor 1 / B_jj exactly
  // (removal is a rank-2 update: Sherman-Morrison-Woodbury).
  for (double g1 : {0.06, 0.8}) {
    const GreenParams p = params(9, g1);
    GreenSolver d(p, dense_opt());
    const GreenRemoval R = green_remove_contact(d, d.centre());
    const int n = d.ncomp() * d.sites(), j = d.centre();
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd G(n, n);
    for (int k = 0; k < n; ++k) {
      v.setZero();
      v(k) = 1.0;
      G.col(k) = g1 * d.apply_green(v);    // G in units 1 / k_c
    }
    const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n), K = I;
    Eigen::MatrixXd dK = Eigen::MatrixXd::Zero(n, n);
    for (int a = 0; a < d.ncomp(); ++a) dK(d.index(j, a), d.index(j, a)) = -1.0;
    const Eigen::MatrixXd B = (I + K * G).inverse();
    const Eigen::MatrixXd Kt = (I + dK * G * B).inverse() * (K + dK);
    Eigen::VectorXd U0 = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < d.sites(); ++i) U0(d.index(i, 0)) = 1.0;
    const Eigen::VectorXd paper_exact = B * dK * (I - G * B * Kt) * U0;
    const Eigen::VectorXd paper_linear = B * dK * (I - G * B * K) * U0;
    EXPECT_LT(rel_diff(R.df_exact, paper_exact), 1e-10) << g1;
    EXPECT_LT(rel_diff(R.df_linear, paper_linear), 1e-10) << g1;
    EXPECT_LT(rel_diff(R.f, B * K * U0), 1e-12);
    // centre contact: f_y = 0 by symmetry, so the update is scalar
    const double Bjj = B(d.index(j, 0), d.index(j, 0));
    EXPECT_LT(rel_diff(R.df_exact, R.df_linear / Bjj), 1e-10);
  }
  // the same identity on the FFT path (89 x 89, the paper's lattice)
  GreenSolver s(params(89, 0.06));
  const GreenRemoval R = green_remove_contact(s, s.centre());
  const Eigen::VectorXd z = green_slip_response(s, s.centre());
  EXPECT_LT(rel_diff(R.df_exact, R.df_linear / z(s.index(s.centre(), 0))), 1e-9);
  // Eq. int.eq09 is the slip response scaled by the removed contact's stretch
  EXPECT_LT(rel_diff(R.df_linear, -R.stretch(s.index(s.centre(), 0)) * z), 1e-9);
  // and the stretch is F / K
  EXPECT_LT(rel_diff(R.stretch, R.f), 1e-10);
}

TEST(GreenRemoval, SymmetryOfForceChanges)
{
  for (bool periodic : {false, true}) {
    GreenSolver s(params(41, 0.06, periodic));
    const GreenRemoval R = green_remove_contact(s, s.centre());
    const int c = s.L() / 2;
    double maxabs = R.df_exact.lpNorm<Eigen::Infinity>(), err = 0.0;
    int positive_x = 0, n_x = 0;
    for (int dy = -c; dy <= c; ++dy)
      for (int dx = -c; dx <= c; ++dx) {
        auto at = [&](int x, int y, int a) { return R.df_exact(s.index(s.site(c + x, c + y), a)); };
        // df_x even in dx and dy, df_y odd in both
        err = std::max(err, std::fabs(at(dx, dy, 0) - at(-dx, dy, 0)));
        err = std::max(err, std::fabs(at(dx, dy, 0) - at(dx, -dy, 0)));
        err = std::max(err, std::fabs(at(dx, dy, 1) + at(-dx, dy, 1)));
        err = std::max(err, std::fabs(at(dx, dy, 1) + at(dx, -dy, 1)));
        if (dy == 0 && dx != 0) {
          ++n_x;
          if (at(dx, 0, 0) > 0) ++positive_x;
        }
      }
    EXPECT_LT(err, 1e-11 * maxabs);
    // the neighbours along the sliding direction pick up load
    EXPECT_EQ(positive_x, n_x);
    EXPECT_NEAR(R.df_exact(s.index(s.centre(), 0)), -R.f(s.index(s.centre(), 0)), 1e-14);
  }
}

TEST(GreenRemoval, ForceBalance)
{
  // Betti reciprocity at the centre (f_y = 0 there): sum_i dF_ix = -f_j^2 / z_jj
  // (the slip response z is a column of (1 + K G)^-1, and f = (1 + K G)^-1 K
  // U0 by the same operator); rigid substrates (gamma1 -> 0): the removed
  // force is simply lost.  Off-centre: GreenRemoval.ReciprocityOffCentre.
  for (double g1 : {0.003, 0.06, 0.8}) {
    GreenSolver s(params(89, g1));
    const int j = s.centre();
    const GreenRemoval R = green_remove_contact(s, j);
    const Eigen::VectorXd z = green_slip_response(s, j);
    double sum = 0.0;
    for (int i = 0; i < s.sites(); ++i) sum += R.df_exact(s.index(i, 0));
    const double fj = R.f(s.index(j, 0));
    EXPECT_NEAR(sum, -fj * fj / z(s.index(j, 0)), 1e-9 * std::fabs(sum)) << g1;
    // the others take up part of the removed force: -f_j < sum < 0
    EXPECT_LT(sum, 0.0);
    EXPECT_GT(sum, -fj);
  }
  GreenSolver rigid(params(21, 1e-7));
  const GreenRemoval R = green_remove_contact(rigid, rigid.centre());
  double sum = 0.0;
  for (int i = 0; i < rigid.sites(); ++i) sum += R.df_exact(rigid.index(i, 0));
  EXPECT_NEAR(sum, -1.0, 1e-5);
}

TEST(GreenRemoval, ReciprocityOffCentre)
{
  // General removal (Woodbury): with C = (1 + gamma1 Gh)^-1 and J the nc
  // components of the removed contact, df = -C_(:,J) C_JJ^-1 f_J and, as
  // u^T C = f^T, sum_i dF_ix = -f_J^T C_JJ^-1 f_J.  At an off-centre contact
  // f_y != 0 (and f_z != 0 with mismatch), so the scalar -f_x^2 / C_xx of the
  // centre is wrong there (measured: 31 x 31, gamma1 0.3, contact (5, 9):
  // -0.0082506 against the true -0.0082548).
  struct Case {
    int L, ix, iy;
    double g1, m;
  };
  for (const Case &c : {Case{31, 5, 9, 0.3, 0.0}, Case{21, 4, 13, 0.3, 0.5}, Case{31, 2, 27, 0.8, 0.0}}) {
    GreenOptions o;
    o.tol = 1e-13;
    GreenSolver s(params(c.L, c.g1, false, c.m), o);
    const int nc = s.ncomp(), j = s.site(c.ix, c.iy);
    const GreenRemoval R = green_remove_contact(s, j);
    std::vector<Eigen::VectorXd> col;
    for (int b = 0; b < nc; ++b) col.push_back(green_slip_response(s, j, nullptr, b));
    const Eigen::MatrixXd C = green_site_block(s, j);
    EXPECT_LT((C - C.transpose()).cwiseAbs().maxCoeff(), 1e-14);
    Eigen::VectorXd fJ(nc);
    for (int a = 0; a < nc; ++a) fJ(a) = R.f(s.index(j, a));
    EXPECT_GT(std::fabs(fJ(1)), 1e-3 * fJ(0)) << "not an off-centre case";
    if (nc == 3) {
      EXPECT_GT(std::fabs(fJ(2)), 1e-3 * fJ(0));
    }
    // the whole force change from the block
    const Eigen::VectorXd t = C.ldlt().solve(fJ);
    Eigen::VectorXd df = Eigen::VectorXd::Zero(nc * s.sites());
    for (int b = 0; b < nc; ++b) df -= t(b) * col[b];
    EXPECT_LT(rel_diff(df, R.df_exact), 1e-10) << c.L << " " << c.m;
    // the sum rule
    double sum = 0.0;
    for (int i = 0; i < s.sites(); ++i) sum += R.df_exact(s.index(i, 0));
    const double rec = green_reciprocity_sum(fJ, C);
    EXPECT_NEAR(sum, rec, 1e-9 * std::fabs(sum)) << c.L << " " << c.m;
    // ... which the x-only scalar formula misses by far more than that
    const double xonly = -fJ(0) * fJ(0) / C(0, 0);
    EXPECT_GT(std::fabs(xonly - sum), 1e-5 * std::fabs(sum)) << c.L << " " << c.m;
  }
  // the block is that of the inverse matrix (dense 9 x 9, mismatch)
  GreenSolver d(params(9, 0.3, false, 0.5), dense_opt());
  const int n = d.ncomp() * d.sites(), j = d.site(1, 6);
  Eigen::MatrixXd A(n, n);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < n; ++k) {
    v.setZero();
    v(k) = 1.0;
    A.col(k) = v + 0.3 * d.apply_green(v);
  }
  const Eigen::MatrixXd Ci = A.inverse();
  const Eigen::MatrixXd C = green_site_block(d, j);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      EXPECT_NEAR(C(a, b), 0.5 * (Ci(d.index(j, a), d.index(j, b)) + Ci(d.index(j, b), d.index(j, a))),
                  1e-12);
  EXPECT_THROW(green_slip_response(GreenSolver(params(9, 0.3)), 0, nullptr, 2), std::invalid_argument);
}

TEST(GreenKernel, FirstOrderNearField)
{
  // gamma1 -> 0: the slip kernel is gamma1 Gh (first order in 1 + gamma1 Gh),
  // k_x(r) = gamma1 (1+s)/(pi r) along x, gamma1 (1+s)(1-s)/(pi r) along y;
  // the relative deviation is second order, i.e. proportional to gamma1
  const double s = 0.3;
  double e[2];
  int n = 0;
  for (double g1 : {1e-4, 1e-3}) {
    GreenSolver S(params(41, g1));
    const Eigen::VectorXd z = green_slip_response(S, S.centre());
    const GreenKernel k = green_axis_kernel(S, z, S.centre(), 10);
    double err = 0.0;
    for (size_t i = 0; i < k.r.size(); ++i) {
      err = std::max(err, std::fabs(k.kx[i] * PI * k.r[i] / (g1 * (1 + s)) - 1.0));
      err = std::max(err, std::fabs(k.ky[i] * PI * k.r[i] / (g1 * (1 + s) * (1 - s)) - 1.0));
    }
    EXPECT_LT(err, 100 * g1) << g1;    // measured: 54 gamma1 (41 x 41)
    e[n++] = err;
  }
  EXPECT_NEAR(e[1] / e[0], 10.0, 1.0);
}

TEST(GreenKernel, PowerLawsNearAndFar)
{
  // near zone, r << lambda_c = 1/gamma1: r^-1 (89 x 89, gamma1 = 0.003,
  // lambda_c = 333); fit over 2 <= r <= 16, well inside the array
  {
    GreenSolver s(params(89, 0.003));
    const GreenRemoval R = green_remove_contact(s, s.centre());
    std::vector<double> r, y;
    profile(s, R.df_exact, r, y);
    const PowerFit f = fit_power_law(r, y, 2, 16);
    EXPECT_NEAR(f.exponent, -1.0, 0.1);    // measured -1.06
  }
  // far zone, r >> lambda_c: r^-3 (gamma1 = 0.8, lambda_c = 1.25); the array
  // edge adds load (finite array), so the fit stays within L/5 of the centre
  {
    GreenSolver s(params(181, 0.8));
    const GreenRemoval R = green_remove_contact(s, s.centre());
    std::vector<double> r, y;
    profile(s, R.df_exact, r, y);
    const PowerFit f = fit_power_law(r, y, 8, 36);
    EXPECT_NEAR(f.exponent, -3.0, 0.1);    // measured -2.97
  }
}

TEST(GreenKernel, CrossoverScalesAsOneOverGamma1)
{
  // Eq. int.eq30: lambda_c ~ a / gamma1.  The slip kernel fitted with the
  // continuum crossover shape A psi(r / lambda) gives lambda gamma1 the same
  // for gamma1 = 0.1 and 0.2 (open 257 x 257 array, r <= 40, well inside
  // it), between the continuum lengths of the two in-plane modes,
  // 1 / (2 (1+s) gamma1) and 1 / (2 (1+s)(1-s) gamma1) (s = 0.3: 0.385 and
  // 0.549 a / gamma1); measured 0.517 and 0.508.
  double lg[2];
  int k = 0;
  for (double g1 : {0.1, 0.2}) {
    GreenSolver s(params(257, g1));
    const Eigen::VectorXd z = green_slip_response(s, s.centre());
    const GreenKernel K = green_axis_kernel(s, z, s.centre(), 40);
    const CrossoverFit c = fit_crossover(K.r, K.kx, 1, 40, 0.1, 1e4, CrossoverShape::CONTINUUM);
    EXPECT_LT(c.rms, 0.01);    // the continuum shape fits to 1 % (log rms)
    lg[k++] = c.lambda * g1;
  }
  EXPECT_NEAR(lg[0] / lg[1], 1.0, 0.05);
  for (double l : lg) {
    EXPECT_GT(l, 1.0 / (2 * 1.3));
    EXPECT_LT(l, 1.0 / (2 * 1.3 * 0.7));
  }
}

TEST(GreenKernel, ContinuumShape)
{
  // (pi/2)(H0(1) - Y0(1)) = (pi/2)(0.5686566270 - 0.0882569642)
  EXPECT_NEAR(continuum_kernel_psi(1.0), (1.0 - 0.5 * PI * 0.4803996628) / (2 * PI), 1e-9);
  // asymptotes 1/(2 pi rho) and 1/(2 pi rho^3)
  EXPECT_NEAR(continuum_kernel_psi(1e-4) * 2 * PI * 1e-4, 1.0, 2e-3);
  EXPECT_NEAR(continuum_kernel_psi(200.0) * 2 * PI * 8e6, 1.0, 1e-3);
  // the fit recovers lambda from exact data of either shape
  std::vector<double> r, ya, yc;
  for (int i = 1; i <= 60; ++i) {
    r.push_back(i);
    ya.push_back(2.0 / (i * (1.0 + i * i / 49.0)));
    yc.push_back(3.0 * continuum_kernel_psi(i / 7.0));
  }
  EXPECT_NEAR(fit_crossover(r, ya, 1, 60).lambda, 7.0, 1e-6);
  const CrossoverFit c = fit_crossover(r, yc, 1, 60, 0.1, 1e4, CrossoverShape::CONTINUUM);
  EXPECT_NEAR(c.lambda, 7.0, 1e-6);
  EXPECT_NEAR(c.amplitude, 3.0, 1e-6);
}

TEST(GreenTable, FormatReadBack)
{
  GreenSolver s(params(21, 0.06));
  const Eigen::VectorXd z = green_slip_response(s, s.centre());
  const GreenKernel k = green_axis_kernel(s, z, s.centre(), 5);
  const std::string file = "test_eq_green_table.txt";
  write_green_table(file, "TEST", k, 2.0, true, {"a comment", "another"});
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "# a comment");
  std::getline(in, line);
  std::getline(in, line);
  EXPECT_EQ(line, "");
  std::getline(in, line);
  EXPECT_EQ(line, "TEST");
  std::getline(in, line);
  EXPECT_EQ(line, "N 5 aniso");
  std::getline(in, line);
  for (int i = 0; i < 5; ++i) {
    int idx;
    double r, k0, k2;
    in >> idx >> r >> k0 >> k2;
    EXPECT_EQ(idx, i + 1);
    EXPECT_EQ(r, i + 1.0);
    EXPECT_NEAR(k0, 2.0 * 0.5 * (k.kx[i] + k.ky[i]), 1e-9 * std::fabs(k0));
    EXPECT_NEAR(k2, 2.0 * 0.5 * (k.kx[i] - k.ky[i]), 1e-9 * std::fabs(k0));
    EXPECT_GT(k0, 0.0);
  }
  std::remove(file.c_str());
  EXPECT_THROW(write_green_table("x.txt", "TWO WORDS", k, 1.0, false, {}), std::invalid_argument);
}

TEST(GreenSolver, BadInputIsRejected)
{
  EXPECT_THROW(GreenSolver(params(2, 0.06)), std::invalid_argument);
  EXPECT_THROW(GreenSolver(params(9, -1.0)), std::invalid_argument);
  GreenParams p = params(9, 0.06);
  p.sigma = 0.5;
  EXPECT_THROW(GreenSolver{p}, std::invalid_argument);
  p = params(9, 0.06);
  p.gamma2 = 0.0;
  EXPECT_THROW(GreenSolver{p}, std::invalid_argument);
  p = params(9, 0.06, false, 1.0);
  EXPECT_THROW(GreenSolver{p}, std::invalid_argument);
  GreenOptions o = dense_opt();
  o.dense_limit = 100;
  EXPECT_THROW(GreenSolver(params(9, 0.06), o), std::invalid_argument);
  GreenSolver s(params(9, 0.06));
  Eigen::VectorXd u = Eigen::VectorXd::Ones(s.ncomp() * s.sites());
  std::vector<double> kappa(s.sites(), 1.0);
  kappa[2] = -1.0;
  EXPECT_THROW(s.solve(kappa, u), std::invalid_argument);
  EXPECT_THROW(s.solve(std::vector<double>(3, 1.0), u), std::invalid_argument);
  // a self term too small for the lattice makes the operator indefinite: the
  // solver reports it instead of returning garbage
  p = params(9, 5.0);
  p.gamma2 = 50.0;
  GreenOptions on;
  on.precond = GreenPrecond::NONE;
  GreenSolver bad(p, on);
  EXPECT_THROW(bad.solve(std::vector<double>(bad.sites(), 1.0),
                         Eigen::VectorXd::Ones(bad.ncomp() * bad.sites())),
               std::runtime_error);
  GreenOptions nr;
  nr.max_restarts = -1;
  EXPECT_THROW(GreenSolver(params(9, 0.06), nr), std::invalid_argument);
}

namespace {
// the message of the std::runtime_error thrown by f, "" if none
template <class F> std::string runtime_error_of(F f)
{
  try {
    f();
  } catch (const std::runtime_error &e) {
    return e.what();
  }
  return "";
}
}    // namespace

TEST(GreenSolver, TrueResidualAndUnattainableTolerance)
{
  // CG stops a cycle on the recursive residual; the solve returns only if the
  // true residual |b - A x| / |b| is below tol (restarting from it), and a
  // tolerance below the round-off floor (~1e-16) is an error naming tol and
  // the attainable residual, not a silent success
  const GreenParams p = params(31, 0.06);
  const std::vector<double> kappa(31 * 31, 1.0);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(2 * 31 * 31);
  for (int i = 0; i < 31 * 31; ++i) u(2 * i) = 1.0;
  for (double tol : {1e-6, 1e-10, 1e-14}) {
    GreenOptions o;
    o.tol = tol;
    GreenSolver s(p, o);
    GreenSolveStats st;
    const Eigen::VectorXd f = s.solve(kappa, u, &st);
    Eigen::VectorXd Af = f + p.gamma1 * s.apply_green(f);
    EXPECT_LT(st.residual, tol);
    EXPECT_NEAR(st.residual, (Af - u).norm() / u.norm(), 1e-3 * tol);
  }
  GreenOptions o;
  o.tol = 1e-17;
  GreenSolver s(p, o);
  const std::string msg = runtime_error_of([&] { s.solve(kappa, u); });
  EXPECT_NE(msg.find("tol 1e-17 is below the attainable accuracy"), std::string::npos) << msg;
  EXPECT_NE(msg.find("use tol >="), std::string::npos) << msg;
}

TEST(GreenSolver, MaxiterNonConvergenceIsAnError)
{
  GreenOptions o;
  o.maxiter = 3;
  o.precond = GreenPrecond::NONE;
  GreenSolver s(params(31, 0.8), o);
  const std::string msg = runtime_error_of([&] { green_remove_contact(s, s.centre()); });
  EXPECT_NE(msg.find("did not converge in 3 iterations"), std::string::npos) << msg;
  // enough iterations: converges
  o.maxiter = 200;
  GreenSolver ok(params(31, 0.8), o);
  GreenRemoval R = green_remove_contact(ok, ok.centre());
  EXPECT_LT(R.st_state.residual, 1e-12);
  EXPECT_LE(R.st_state.iterations, 200);
}

TEST(GreenSolver, CirculantFallsBackToJacobi)
{
  // the periodic (circulant) approximation can be indefinite where the open
  // array is not (stiff contacts, large self-term cutoff): the solver then
  // preconditions with Jacobi and still solves the system
  GreenParams p = params(9, 2.0);
  p.gamma2 = 5.0;
  GreenSolver s(p), d(p, dense_opt());
  GreenOptions oj;
  oj.precond = GreenPrecond::JACOBI;
  GreenSolver sj(p, oj);
  EXPECT_FALSE(s.circulant_active());
  EXPECT_NE(s.describe().find("jacobi (circulant not positive definite)"), std::string::npos);
  const std::vector<double> kappa(s.sites(), 1.0);
  const Eigen::VectorXd u = Eigen::VectorXd::Ones(s.ncomp() * s.sites());
  GreenSolveStats st, stj;
  const Eigen::VectorXd f = s.solve(kappa, u, &st);
  EXPECT_LT(rel_diff(f, d.solve(kappa, u)), 1e-10);
  const Eigen::VectorXd fj = sj.solve(kappa, u, &stj);
  EXPECT_EQ(st.iterations, stj.iterations);    // the same (Jacobi) iteration
  EXPECT_LT(rel_diff(f, fj), 1e-14);
  // the paper's parameters keep the circulant
  EXPECT_TRUE(GreenSolver(params(9, 0.06)).circulant_active());
  EXPECT_FALSE(sj.circulant_active());
  EXPECT_FALSE(d.circulant_active());
}

TEST(GreenSolver, DenseNotPositiveDefiniteIsAnError)
{
  GreenParams p = params(9, 5.0);
  p.gamma2 = 1.0;
  GreenSolver d(p, dense_opt());
  const std::string msg = runtime_error_of([&] {
    d.solve(std::vector<double>(d.sites(), 1.0), Eigen::VectorXd::Ones(d.ncomp() * d.sites()));
  });
  EXPECT_NE(msg.find("dense Green system is not positive definite"), std::string::npos) << msg;
}
