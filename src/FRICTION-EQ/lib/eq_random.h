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
   FRICTION-EQ package: stateless, counter-based random numbers.

   Every random number of a contact is a pure function of
   (seed, atom tag, event counter, stream): Philox4x32-10 (Salmon et al.,
   SC'11, "Parallel random numbers: as easy as 1, 2, 3") with key = seed
   and counter = (tag, event, stream).  No generator state exists, so the
   draws do not depend on the MPI decomposition, on the order in which
   contacts are visited, or on restarts: only the per-contact event
   counter has to be kept (it travels with the atom and is in restarts).
------------------------------------------------------------------------- */

#ifndef FEQ_RANDOM_H
#define FEQ_RANDOM_H

#include <array>
#include <cmath>
#include <cstdint>

namespace feq {

using Philox4x32 = std::array<uint32_t, 4>;

// one round of Philox4x32 with round key `key`
inline void philox4x32_round(Philox4x32 &ctr, const std::array<uint32_t, 2> &key)
{
  const uint64_t M0 = 0xD2511F53u, M1 = 0xCD9E8D57u;
  const uint64_t p0 = M0 * ctr[0];
  const uint64_t p1 = M1 * ctr[2];
  const uint32_t hi0 = uint32_t(p0 >> 32), lo0 = uint32_t(p0);
  const uint32_t hi1 = uint32_t(p1 >> 32), lo1 = uint32_t(p1);
  ctr = {hi1 ^ ctr[1] ^ key[0], lo1, hi0 ^ ctr[3] ^ key[1], lo0};
}

// Philox4x32-10: ten rounds, the key bumped by the Weyl constants between
// them (unrolled: a contact's break draws one block)
inline Philox4x32 philox4x32(Philox4x32 ctr, std::array<uint32_t, 2> key)
{
  const uint32_t W0 = 0x9E3779B9u, W1 = 0xBB67AE85u;
  philox4x32_round(ctr, key);
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC unroll 9
#elif defined(__clang__)
#pragma unroll 9
#endif
  for (int r = 1; r < 10; ++r) {
    key[0] += W0;
    key[1] += W1;
    philox4x32_round(ctr, key);
  }
  return ctr;
}

// Streams: independent sequences of one contact.  A contact formed again
// when its atom re-enters the group draws from the streams offset by
// STREAM_REENTRY (keyed by its break count), so it does not repeat the
// draws of its first formation.
enum Stream : uint32_t {
  STREAM_THRESHOLD = 0,
  STREAM_REFORM = 1,
  STREAM_STIFFNESS = 2,
  STREAM_BUDGET = 3,    // the hazard a life can take (fix eq/substrate's blocks; a
                        // contact's comes with its threshold: draw_pair())
  STREAM_DELAY = 4,     // the delay before a broken contact re-forms
  STREAM_REENTRY = 8
};

// A uniform variate u in the open interval (0,1) together with 1-u, both
// exact (52-bit grid shifted by half a unit): samplers use whichever tail
// keeps full relative precision.
struct Uniform {
  double u;
  double one_minus_u;
};

inline Uniform uniform_from_bits(uint64_t bits)
{
  const uint64_t k = bits >> 12;    // 52 random bits: u and 1-u exact near 0 and 1
  const double scale = 1.0 / 4503599627370496.0;    // 2^-52
  return {(double(k) + 0.5) * scale, (double((uint64_t(1) << 52) - k) - 0.5) * scale};
}

// an Exp(1) variate from u, with full relative precision in both tails
inline double exponential(const Uniform &u)
{
  return -std::log1p(-u.one_minus_u);
}

// the Philox block of (seed, tag, event, stream)
inline Philox4x32 draw_block(uint64_t seed, uint64_t tag, uint64_t event, uint32_t stream)
{
  return philox4x32({uint32_t(tag), uint32_t(tag >> 32), uint32_t(event),
                     (uint32_t(event >> 32) << 8) | (stream & 0xffu)},
                    {uint32_t(seed), uint32_t(seed >> 32)});
}

// The draw of one contact: seed (> 0), global atom tag, event counter
// (number of earlier breaks of that contact) and stream.
inline Uniform draw(uint64_t seed, uint64_t tag, uint64_t event, uint32_t stream)
{
  const Philox4x32 out = draw_block(seed, tag, event, stream);
  return uniform_from_bits((uint64_t(out[0]) << 32) | out[1]);
}

// two uniforms from one Philox call: the first is draw()'s (the same
// bits), the second from the call's other 64 bits, independent of it
struct UniformPair {
  Uniform first;
  Uniform second;
};
inline UniformPair draw_pair(uint64_t seed, uint64_t tag, uint64_t event, uint32_t stream)
{
  const Philox4x32 out = draw_block(seed, tag, event, stream);
  return {uniform_from_bits((uint64_t(out[0]) << 32) | out[1]),
          uniform_from_bits((uint64_t(out[2]) << 32) | out[3])};
}

// The draws of candidate k of a contact's life (thermal breaking by
// thinning, eq_contact.cpp): the acceptance u and the Exp(1) budget to the
// next candidate, from one Philox block keyed apart from draw()'s by
// CANDIDATE_KEY ("CAND") in the key's upper word.
constexpr uint32_t CANDIDATE_KEY = 0x43414e44u;
struct CandidateDraws {
  double accept;    // uniform in (0, 1)
  double next;      // Exp(1)
};
inline CandidateDraws draw_candidate(uint64_t seed, uint64_t tag, uint64_t life, uint64_t k)
{
  const Philox4x32 out =
      philox4x32({uint32_t(tag), uint32_t(tag >> 32), uint32_t(life), uint32_t(k)},
                 {uint32_t(seed), uint32_t(seed >> 32) ^ CANDIDATE_KEY ^ uint32_t(k >> 32) ^
                      (uint32_t(life >> 32) << 16)});
  return {uniform_from_bits((uint64_t(out[0]) << 32) | out[1]).u,
          exponential(uniform_from_bits((uint64_t(out[2]) << 32) | out[3]))};
}

}    // namespace feq

#endif
