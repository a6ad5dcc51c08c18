/* FRICTION-EQ benchmark reference (issue 24): the work of fix eq/contacts
   without LAMMPS, as a plain loop, and the memory bandwidth of this
   machine, so that bench_contacts.py can print the fix beside both.

   The scene of in.bench: N contacts sliding at dX per step along x in a
   periodic box, thresholds uniform [0.75, 1.25], re-forming unstretched
   (reform delta 0), stiffness 1.  Per contact and step the loop does what
   the fix's does: the unwrapped coordinate from x and the image flags,
   the stretch, the breaking test, on a break a new threshold from the
   counter-keyed generator of the package (lib/eq_random.h, the same
   Philox draw) and the anchor moved, the force into f and the sums of the
   output (force, energy, stretch, attached).  Its state is what the test
   needs, structure of arrays (anchor, threshold, stiffness, break count);
   x, f and the image flags are LAMMPS-like (x and f: 3 doubles per atom).
   Moving the atoms (fix nve/noforce's work, the baseline of the fix) is
   not timed.

   The bandwidth: the STREAM triad a = b + q c over arrays of 2^25
   doubles (3 x 256 MiB), best of 5, counting 24 bytes per element (no
   write-allocate traffic counted, as STREAM reports).

   g++ -O2 -std=c++17 -I../../src/FRICTION-EQ/lib hand_contacts.cpp
   ./a.out N steps        prints: ns per contact-step, breaks, GB/s        */

#include "eq_random.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

constexpr uint64_t SEED = 1;
constexpr int IMGMAX = 512, IMGMASK = 1023;

struct Scene {
  int n;
  double prd, dx;
  std::vector<double> x, f;          // 3 per atom, as LAMMPS' x and f
  std::vector<int> image;            // LAMMPS' packed image flags (x in the low bits)
  std::vector<double> anchor, threshold, stiffness;
  std::vector<uint64_t> nbreak;
};

double threshold_draw(uint64_t tag, uint64_t event)
{
  return 0.75 + 0.5 * feq::draw(SEED, tag, event, feq::STREAM_THRESHOLD).u;
}

Scene make(int n)
{
  Scene s{n, 1.0 * n, 0.01, {}, {}, {}, {}, {}, {}, {}};
  s.x.assign(3 * n, 0.0);
  s.f.assign(3 * n, 0.0);
  s.image.assign(n, IMGMAX | (IMGMAX << 10) | (IMGMAX << 20));
  s.anchor.resize(n);
  s.threshold.resize(n);
  s.stiffness.assign(n, 1.0);
  s.nbreak.assign(n, 0);
  for (int i = 0; i < n; i++) {
    s.x[3 * i] = i + 0.5;
    s.anchor[i] = s.x[3 * i];
    s.threshold[i] = threshold_draw(i + 1, 0);
  }
  return s;
}

// fix nve/noforce's work, not timed: x advances, wraps into the box
void move(Scene &s)
{
  for (int i = 0; i < s.n; i++) {
    double &x = s.x[3 * i];
    x += s.dx;
    if (x >= s.prd) {
      x -= s.prd;
      s.image[i] = (s.image[i] & ~IMGMASK) | (((s.image[i] & IMGMASK) + 1) & IMGMASK);
    }
  }
  std::fill(s.f.begin(), s.f.end(), 0.0);
}

// the contact loop; returns the number of breaks
long contacts(Scene &s, double sums[4])
{
  const double prd = s.prd;
  const double *const x = s.x.data();
  const int *const image = s.image.data();
  double *const f = s.f.data();
  double *const anchor = s.anchor.data();
  double *const thr = s.threshold.data();
  const double *const k = s.stiffness.data();
  uint64_t *const nb = s.nbreak.data();
  double fsum = 0.0, esum = 0.0, ssum = 0.0, natt = 0.0;
  long breaks = 0;
  for (int i = 0; i < s.n; i++) {
    const double xu = x[3 * i] + ((image[i] & IMGMASK) - IMGMAX) * prd;
    double st = xu - anchor[i];
    if (!(std::fabs(st) < thr[i])) {
      thr[i] = threshold_draw(i + 1, ++nb[i]);
      anchor[i] = xu;
      st = 0.0;
      breaks++;
    }
    const double fc = k[i] * st;
    f[3 * i] -= fc;
    fsum += fc;
    esum += fc * st;
    ssum += st;
    natt += 1.0;
  }
  sums[0] += fsum;
  sums[1] += 0.5 * esum;
  sums[2] += ssum;
  sums[3] += natt;
  return breaks;
}

double triad_bandwidth()
{
  const std::size_t m = std::size_t(1) << 25;
  std::vector<double> a(m, 0.0), b(m, 1.0), c(m, 2.0);
  double best = 1e30;
  for (int r = 0; r < 5; r++) {
    const auto t0 = Clock::now();
    const double q = 3.0 + r;
    for (std::size_t i = 0; i < m; i++) a[i] = b[i] + q * c[i];
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  if (a[m / 2] < 0.0) std::puts("");    // keep the loop
  return 24.0 * m / best / 1e9;
}

}    // namespace

int main(int argc, char **argv)
{
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s N steps\n", argv[0]);
    return 1;
  }
  const int n = std::atoi(argv[1]);
  const int steps = std::atoi(argv[2]);
  Scene s = make(n);
  double sums[4] = {0, 0, 0, 0};
  long breaks = 0;
  double t = 0.0;
  for (int step = 0; step < steps; step++) {
    move(s);
    const auto t0 = Clock::now();
    breaks += contacts(s, sums);
    t += std::chrono::duration<double>(Clock::now() - t0).count();
  }
  std::printf("hand_loop N %d steps %d ns_per_contact_step %.4f breaks_per_contact_step %.5f "
              "mean_force %.6f triad_GB_per_s %.2f\n",
              n, steps, 1e9 * t / (double(n) * steps), breaks / (double(n) * steps),
              sums[0] / (double(n) * steps), triad_bandwidth());
  return 0;
}
