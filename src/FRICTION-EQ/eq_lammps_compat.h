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
   FRICTION-EQ package for LAMMPS: the differences between the LAMMPS
   versions the package supports, in one place.

   Tested: 29 Sep 2021 (Debian bookworm), 4 Feb 2025 (Debian trixie),
   4 Jul 2026 (Debian sid).  Two APIs changed between 2021 and 2025:

   - neighbor list requests: neighbor->request() + requests[i]->half/full
     became neighbor->add_request(this, NeighConst::REQ_FULL) (17 Feb 2022);
   - communication of a style's own buffers: comm->forward_comm_pair(this),
     forward_comm_fix(this), ... became overloads of comm->forward_comm(this)
     and comm->reverse_comm(this) (7 Jan 2022).

   FEQ_LAMMPS_VERSION (YYYYMMDD) is set from src/version.h by every build
   route of the package (the wrapper CMake, the plugin CMake, and
   Install.sh of the make build).  Without it (the files copied into a
   LAMMPS tree by hand and built with LAMMPS' own CMake), the version is
   guessed from a header that 29 Sep 2021 lacks and every later stable
   release has.  Include this header from .cpp files only: LAMMPS' own
   files include the package's style headers, which stay version-free.
------------------------------------------------------------------------- */

#ifndef LMP_EQ_LAMMPS_COMPAT_H
#define LMP_EQ_LAMMPS_COMPAT_H

#include "comm.h"
#include "fix.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "pair.h"

#ifndef FEQ_LAMMPS_VERSION
#if defined(__has_include)
#if __has_include("platform.h")
#define FEQ_LAMMPS_VERSION 20220623    // platform.h: Oct 2021 and later
#else
#define FEQ_LAMMPS_VERSION 20210929
#endif
#else
#define FEQ_LAMMPS_VERSION 20210929
#endif
#endif

namespace LAMMPS_NS {
namespace EQCompat {

// pair_style hybrid (and hybrid/scaled) before 4 Jul 2026 copies a
// sub-style's extra single() values with a loop that never ends
// (PairHybrid::copy_svector: 'for (l = 0; single_extra; ++l)'): compute
// pair/local with p1, p2, ... crashes.  A sub-style there offers none.
constexpr bool HYBRID_SVECTOR_BUG = FEQ_LAMMPS_VERSION < 20260704;

// a full neighbor list for a pair style (every pair i-j on both owners)
inline void request_full_list(Neighbor *neighbor, Pair *pair, int instance_me)
{
#if FEQ_LAMMPS_VERSION >= 20220217
  (void) instance_me;
  neighbor->add_request(pair, NeighConst::REQ_FULL);
#else
  const int irequest = neighbor->request(pair, instance_me);
  neighbor->requests[irequest]->half = 0;
  neighbor->requests[irequest]->full = 1;
#endif
}

// a full neighbor list for a fix, with its own cutoff (the fix's
// interaction range, not the pair style's)
inline void request_fix_full_list(Neighbor *neighbor, Fix *fix, int instance_me, double cutoff)
{
#if FEQ_LAMMPS_VERSION >= 20220217
  (void) instance_me;
  neighbor->add_request(fix, NeighConst::REQ_FULL)->set_cutoff(cutoff);
#else
  const int irequest = neighbor->request(fix, instance_me);
  neighbor->requests[irequest]->pair = 0;
  neighbor->requests[irequest]->fix = 1;
  neighbor->requests[irequest]->half = 0;
  neighbor->requests[irequest]->full = 1;
  neighbor->requests[irequest]->cut = 1;
  neighbor->requests[irequest]->cutoff = cutoff;
#endif
}

// owner -> ghost copies of a style's per-atom buffer (pack/unpack_forward_comm)
// and ghost -> owner sums (pack/unpack_reverse_comm)
#if FEQ_LAMMPS_VERSION >= 20220107
inline void forward_comm(Comm *comm, Pair *style) { comm->forward_comm(style); }
inline void reverse_comm(Comm *comm, Pair *style) { comm->reverse_comm(style); }
inline void forward_comm(Comm *comm, Fix *style) { comm->forward_comm(style); }
inline void reverse_comm(Comm *comm, Fix *style) { comm->reverse_comm(style); }
#else
inline void forward_comm(Comm *comm, Pair *style) { comm->forward_comm_pair(style); }
inline void reverse_comm(Comm *comm, Pair *style) { comm->reverse_comm_pair(style); }
inline void forward_comm(Comm *comm, Fix *style) { comm->forward_comm_fix(style); }
inline void reverse_comm(Comm *comm, Fix *style) { comm->reverse_comm_fix(style); }
#endif

}    // namespace EQCompat
}    // namespace LAMMPS_NS

#endif
