/* FRICTION-EQ benchmark reference (issue 24): what a break must cost at
   least in pair eq/elastic, the update of its partners' fields, as a
   plain loop without LAMMPS, so that bench_interact.py can print the cost
   per break of the package beside it.

   The scene of in.bench-pair: N contacts on a triangular lattice of
   spacing 1 (rows of nx atoms, atoms numbered row by row as create_atoms
   does, periodic), coupled within rcut = 3 (36 partners each), the pairs
   in the layout of the pair style (per atom the range first[2i] ..
   first[2i+1] of partner indices pj and couplings pk, built once).  A
   break of contact i by dq changes h_i by K_i dq and h_j by -k_ij dq for
   each partner j: that loop is timed, for breaks at random contacts
   (steady sliding: most breaks are single, at uncorrelated places), many
   rounds of B breaks each.  Nothing else (no breaking test, no new
   threshold, no bookkeeping, no communication) is done: the loop is the
   lower bound of a break's work.

   g++ -O2 -std=c++17 hand_scatter.cpp
   ./a.out N B           prints: ns per break, partners per break
   ./a.out N B BREAKS    the same with BREAKS breaks per repeat (3 repeats)  */

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

struct Lattice {
  int n = 0;
  std::vector<int> first, pj;
  std::vector<double> pk, ksum;
};

// rows of nx atoms, row r shifted by r/2 (mod 2) of a spacing; ny rows
Lattice triangular(int nx, int ny, double rcut)
{
  Lattice L;
  L.n = nx * ny;
  L.first.assign(2 * static_cast<size_t>(L.n), 0);
  L.ksum.assign(L.n, 0.0);
  const double dy = std::sqrt(3.0) / 2.0;
  const int reach = static_cast<int>(std::ceil(rcut)) + 1;
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) {
      const int i = r * nx + c;
      L.first[2 * i] = static_cast<int>(L.pj.size());
      for (int dr = -reach; dr <= reach; ++dr)
        for (int dc = -reach - 1; dc <= reach + 1; ++dc) {
          if (dr == 0 && dc == 0) continue;
          const int r2 = ((r + dr) % ny + ny) % ny, c2 = ((c + dc) % nx + nx) % nx;
          const double ddx = dc + 0.5 * ((r + dr) & 1) - 0.5 * (r & 1), ddy = dr * dy;
          const double d = std::sqrt(ddx * ddx + ddy * ddy);
          if (d > rcut + 1e-9) continue;
          L.pj.push_back(r2 * nx + c2);
          L.pk.push_back(0.02 * rcut / d);
          L.ksum[i] += L.pk.back();
        }
      L.first[2 * i + 1] = static_cast<int>(L.pj.size());
    }
  return L;
}

// one round of b breaks (the timed loop; not inlined, so that valgrind's
// callgrind can count its instructions alone: --toggle-collect=*scatter_round*)
__attribute__((noinline)) void scatter_round(const Lattice &L, double *h, const int *who,
                                             const double *dq, int b)
{
  for (int m = 0; m < b; ++m) {
    const int i = who[m];
    const double d = dq[m];
    h[i] += L.ksum[i] * d;
    for (int p = L.first[2 * i]; p < L.first[2 * i + 1]; ++p) h[L.pj[p]] -= L.pk[p] * d;
  }
}

uint64_t next(uint64_t &s)
{
  s ^= s << 13;
  s ^= s >> 7;
  s ^= s << 17;
  return s;
}

}    // namespace

int main(int argc, char **argv)
{
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s N breaks_per_round [breaks]\n", argv[0]);
    return 1;
  }
  const long n_req = std::atol(argv[1]);
  const int b = std::max(1, std::atoi(argv[2]));
  const int ny = std::max(2, 2 * static_cast<int>(std::lround(std::sqrt(n_req / 4.0))));
  const int nx = std::max(2, static_cast<int>(n_req / ny));
  const Lattice L = triangular(nx, ny, 3.0);
  std::vector<double> h(L.n, 0.0);
  std::vector<int> who(b);
  std::vector<double> dq(b);
  uint64_t s = 88172645463325252ull;
  // breaks timed (a third argument: fewer, for callgrind)
  const long target = argc > 3 ? std::max(1L, std::atol(argv[3])) : 4000000;
  const long rounds = std::max(1L, target / b);
  double best = 1e300;
  for (int rep = 0; rep < 3; ++rep) {
    double t = 0.0;
    for (long round = 0; round < rounds; ++round) {
      for (int m = 0; m < b; ++m) {
        who[m] = static_cast<int>(next(s) % static_cast<uint64_t>(L.n));
        dq[m] = -0.5 - 1e-3 * static_cast<double>(next(s) % 1000);
      }
      const auto t0 = Clock::now();
      scatter_round(L, h.data(), who.data(), dq.data(), b);
      t += std::chrono::duration<double>(Clock::now() - t0).count();
    }
    best = std::min(best, t);
  }
  double hs = 0.0;
  for (const double v : h) hs += v;
  std::printf("atoms %d partners_per_break %.1f ns_per_break %.2f (checksum %.3g)\n", L.n,
              static_cast<double>(L.pj.size()) / L.n, 1e9 * best / (rounds * b), hs);
  return 0;
}
