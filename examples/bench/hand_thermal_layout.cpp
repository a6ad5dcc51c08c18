/* FRICTION-EQ benchmark reference (issue 23 item 7): where the time of
   fix eq/contacts' common step at T > 0 goes, as plain loops in one
   process.

   The common step is the step of an attached contact that stays below
   its threshold's lower bound, within its rate bound, and whose budget
   is not used up (ContactModel::quick_attached(), since stop 47
   stored_quick()).  Each loop below does
   that step for N contacts (no breaks): the unwrapped coordinate from x
   and the image flags, the stretch, the tests, the stretch and the force
   stored, the force into f, the four sums.  The layouts:

     T = 0        the athermal row, CS_NCOL = 7 doubles (scan()'s work)
     thermal      the thermal row as fix eq/contacts kept it up to stop 46,
                  CT_NCOL = 15 doubles; the budget and the age written
                  every step
     read-only    the same row as the fix keeps it since stop 47 (the
                  stored form): the budget and age not written, the test
                  is t < the run-out time (the budget as the time at which
                  it runs out, the age as a formation time)
     hot 9        only what the step touches, 9 doubles (S F K A, the lower
                  bound, the bound's stretch and rate, budget, age)
     hot 7 r/o    the same without the writes: 7 doubles (S F K A, the
                  lower bound, the bound's stretch, the run-out time)
     compact 6    fix eq/contacts' compact row with keyword peratom N > 1
                  (since stop 48): hot 7 r/o with the lower bound and the
                  bound's stretch as one limit of |s| (A K LIMIT RUN-OUT S F)

   The loops run in turn, in blocks of passes (one loop's passes back to
   back, so that it finds its own data in the cache as the fix does in a
   run of its own; a block of 1 interleaves them), many times over; each
   prints its fastest pass (the machine's slow spells fall on all loops
   alike) per contact-step, and its ratio to T = 0.  Passes: 2e7/N, at
   least 300 (a pass of one loop takes about N/500 to N/60 microseconds).  The T = 0 loop leaves out
   the tolerance of quasi-static driving (0 in in.bench; scan() tests it
   behind a branch).

   g++ -O2 -std=c++17 -fno-semantic-interposition -ffp-contract=off \
       -I../../src/FRICTION-EQ/lib hand_thermal_layout.cpp -o hand_thermal_layout
   ./hand_thermal_layout N [passes [block]]    (block: passes per block, 10) */

#include "eq_contact.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using namespace feq;
using Clock = std::chrono::steady_clock;

constexpr int IMGMAX = 512, IMGMASK = 1023, IMGBITS = 10;

struct Scene {
  int n;
  std::vector<double> x, f;
  std::vector<int> image;
  double prd = 100.0, reach = HUGE_VAL;
};

// what a loop reads of the scene, in locals that no store can alias (as
// the fix's loops keep them)
struct View {
  const int n;
  const double *const x;
  double *const f;
  const int *const image;
  const double prd, reach;
  explicit View(Scene &c) :
      n(c.n), x(c.x.data()), f(c.f.data()), image(c.image.data()), prd(c.prd), reach(c.reach)
  {
  }
  double unwrap(int i) const
  {
    return x[3 * i] + (int((image[i] >> IMGBITS) & IMGMASK) - IMGMAX) * prd;
  }
};

struct Sums {
  double f = 0.0, e = 0.0, s = 0.0, n = 0.0;
  void add(double *fd, double fc, double s_)
  {
    *fd -= fc;
    f += fc;
    e += fc * s_;
    s += s_;
    n += 1.0;
  }
  double total() const { return f + e + s + n; }
};

// the hot rows' columns
enum Hot9 { H_S, H_F, H_K, H_A, H_XSLOW, H_BOUND_S, H_RATE, H_BUDGET, H_AGE, H9 };
enum Hot7 { R_S, R_F, R_K, R_A, R_XSLOW, R_BOUND_S, R_RUNOUT, H7 };
enum Compact6 { C_A, C_K, C_LIMIT, C_RUNOUT, C_S, C_F, H6 };

[[noreturn]] void off_path()
{
  std::fprintf(stderr, "a contact left the common step\n");
  std::abort();
}

__attribute__((noinline)) double athermal(Scene &scene, double *rows)
{
  const View c(scene);
  Sums sum;
  for (int i = 0; i < c.n; i++) {
    double *st = rows + i * std::size_t(CS_NCOL);
    const double s = c.unwrap(i) - st[CS_ANCHOR];
    if (!(std::fabs(s) < std::min(st[CS_THRESHOLD], c.reach))) off_path();
    st[CS_STRETCH] = s;
    const double fc = st[CS_STIFFNESS] * s;
    st[CS_FORCE] = fc;
    sum.add(&c.f[3 * i], fc, s);
  }
  return sum.total();
}

// the thermal layouts: a row of W doubles and its columns; WRITES: the
// budget (a hazard) and the age are written each step, else the budget
// column holds the run-out time and nothing but S and F is written
struct Today {
  static constexpr std::size_t W = CT_NCOL;
  static constexpr int S = CS_STRETCH, F = CS_FORCE, K = CS_STIFFNESS, A = CS_ANCHOR, XSLOW = CT_XS_LOW,
                       BOUND_S = CT_BOUND_S, RATE = CT_BOUND_RATE, BUDGET = CT_BUDGET, AGE = CT_AGE;
  static constexpr bool WRITES = true;
  static constexpr bool ONE_LIMIT = false;
};
struct TodayReadOnly : Today {
  static constexpr int BUDGET = CT_RUNOUT;
  static constexpr bool WRITES = false;
};
struct Hot9Row {
  static constexpr std::size_t W = H9;
  static constexpr int S = H_S, F = H_F, K = H_K, A = H_A, XSLOW = H_XSLOW, BOUND_S = H_BOUND_S, RATE = H_RATE,
                       BUDGET = H_BUDGET, AGE = H_AGE;
  static constexpr bool WRITES = true;
  static constexpr bool ONE_LIMIT = false;
};
struct Hot7Row {
  static constexpr std::size_t W = H7;
  static constexpr int S = R_S, F = R_F, K = R_K, A = R_A, XSLOW = R_XSLOW, BOUND_S = R_BOUND_S,
                       BUDGET = R_RUNOUT;
  static constexpr bool WRITES = false;
  static constexpr bool ONE_LIMIT = false;
};
struct Compact6Row {
  static constexpr std::size_t W = H6;
  static constexpr int S = C_S, F = C_F, K = C_K, A = C_A, XSLOW = C_LIMIT, BOUND_S = C_LIMIT,
                       BUDGET = C_RUNOUT;
  static constexpr bool WRITES = false;
  static constexpr bool ONE_LIMIT = true;
};

// the common step at T > 0 in layout L; t: the time step (WRITES), else
// the end of the step on the run's clock
template <class L> __attribute__((noinline)) double thermal(Scene &scene, double *rows, double t)
{
  const View c(scene);
  Sums sum;
  for (int i = 0; i < c.n; i++) {
    double *st = rows + i * L::W;
    const double s = c.unwrap(i) - st[L::A], a = std::fabs(s);
    if constexpr (L::ONE_LIMIT) {
      if (!(a < c.reach && a < st[L::XSLOW])) off_path();
    } else if (!(a < c.reach && a < st[L::XSLOW] && a <= st[L::BOUND_S])) {
      off_path();
    }
    if constexpr (L::WRITES) {
      const double dH = st[L::RATE] * t;
      if (!(dH < st[L::BUDGET])) off_path();
      st[L::BUDGET] -= dH;
      st[L::AGE] += t;
    } else {
      if (!(t < st[L::BUDGET])) off_path();
    }
    st[L::S] = s;
    const double fc = st[L::K] * s;
    st[L::F] = fc;
    sum.add(&c.f[3 * i], fc, s);
  }
  return sum.total();
}

}    // namespace

int main(int argc, char **argv)
{
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s N [passes [block]]\n", argv[0]);
    return 2;
  }
  const int n = int(std::atof(argv[1]));
  const int passes = argc > 2 ? std::atoi(argv[2]) : std::max(300, int(2e7 / std::max(n, 1)));
  const int block = argc > 3 ? std::atoi(argv[3]) : 10;
  if (n < 1 || passes < 1 || block < 1) {
    std::fprintf(stderr, "N, passes and block must be >= 1\n");
    return 2;
  }
  const double dt = 0.01;
  Scene c;
  c.n = n;
  c.x.resize(3 * std::size_t(n));
  c.f.assign(3 * std::size_t(n), 0.0);
  c.image.assign(n, IMGMAX << IMGBITS);
  // contacts 0.1 behind their atoms: stretch 0.1, thresholds 1 (lower
  // bound 0.75, the bound's stretch 0.9), budgets that never run out
  std::vector<double> r0(n * std::size_t(CS_NCOL)), rt(n * std::size_t(Today::W)),
      ro(n * std::size_t(CT_NCOL)), h9(n * std::size_t(H9)), h7(n * std::size_t(H7)),
      h6(n * std::size_t(H6));
  for (int i = 0; i < n; i++) {
    c.x[3 * i] = 0.01 * i;
    double *a = &r0[i * std::size_t(CS_NCOL)], *b = &rt[i * Today::W];
    a[CS_THRESHOLD] = 1.0;
    a[CS_STIFFNESS] = 1.0;
    a[CS_ANCHOR] = 0.01 * i - 0.1;
    std::copy(a, a + CS_NCOL, b);
    b[CT_BOUND_RATE] = 1e-3;
    b[CT_BOUND_S] = 0.9;
    b[CT_XS_LOW] = 0.75;
    b[CT_BUDGET] = 1e300;
    std::copy(b, b + Today::W, &ro[i * std::size_t(CT_NCOL)]);    // (CT_RUNOUT: 1e300)
    double *p = &h9[i * std::size_t(H9)], *q = &h7[i * std::size_t(H7)];
    p[H_K] = q[R_K] = 1.0;
    p[H_A] = q[R_A] = a[CS_ANCHOR];
    p[H_XSLOW] = q[R_XSLOW] = 0.75;
    p[H_BOUND_S] = q[R_BOUND_S] = 0.9;
    p[H_RATE] = 1e-3;
    p[H_BUDGET] = q[R_RUNOUT] = 1e300;
    double *u = &h6[i * std::size_t(H6)];
    u[C_K] = 1.0;
    u[C_A] = a[CS_ANCHOR];
    u[C_LIMIT] = 0.75;    // min(lower bound, the double above the bound's stretch)
    u[C_RUNOUT] = 1e300;
  }
  const char *names[] = {"T = 0", "thermal", "read-only", "hot 9", "hot 7 r/o", "compact 6"};
  constexpr int NLOOP = 6;
  std::vector<double> best(NLOOP, HUGE_VAL);
  double sink = 0.0;
  auto now = [] { return Clock::now(); };
  auto secs = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  for (int p0 = 0; p0 < passes; p0 += block) {
    const int p1 = std::min(passes, p0 + block);
    for (int k = 0; k < NLOOP; k++) {
      for (int p = p0; p < p1; p++) {
        const double t_end = (p + 1) * dt;
        const auto t0 = now();
        switch (k) {
          case 0: sink += athermal(c, r0.data()); break;
          case 1: sink += thermal<Today>(c, rt.data(), dt); break;
          case 2: sink += thermal<TodayReadOnly>(c, ro.data(), t_end); break;
          case 3: sink += thermal<Hot9Row>(c, h9.data(), dt); break;
          case 4: sink += thermal<Hot7Row>(c, h7.data(), t_end); break;
          default: sink += thermal<Compact6Row>(c, h6.data(), t_end); break;
        }
        best[k] = std::min(best[k], secs(t0, now()));
      }
    }
  }
  std::printf("N = %d, %d passes in blocks of %d; minimum ns per contact-step (ratio to T = 0):", n, passes, block);
  for (int k = 0; k < NLOOP; k++) std::printf("  %s %.2f (%.2f)", names[k], 1e9 * best[k] / n, best[k] / best[0]);
  std::printf("\n");
  return sink == 0.123456789 ? 1 : 0;    // keeps the sums alive
}
