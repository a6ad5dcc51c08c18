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
   FRICTION-EQ package for LAMMPS: per-atom state of the package's fixes
   (see eq_fix_peratom.h)
------------------------------------------------------------------------- */

#include "eq_fix_peratom.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "memory.h"

#include "eq_lammps_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

FixEQPerAtom::FixEQPerAtom(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), ncol(0), state(nullptr), callbacks(0)
{
}

FixEQPerAtom::~FixEQPerAtom()
{
  if (callbacks) {
    atom->delete_callback(id, Atom::GROW);
    atom->delete_callback(id, Atom::RESTART);
  }
  memory->destroy(state);
}

void FixEQPerAtom::peratom_setup(int ncol_, int noutput)
{
  ncol = ncol_;
  restart_peratom = 1;
  create_attribute = 1;
  peratom_flag = 1;
  size_peratom_cols = noutput;
  peratom_freq = 1;
  maxexchange = ncol;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  callbacks = 1;
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

double FixEQPerAtom::memory_usage()
{
  return static_cast<double>(atom->nmax) * ncol * sizeof(double);
}

void FixEQPerAtom::grow_arrays(int nmax)
{
  memory->grow(state, nmax, ncol, "eq:state");
  array_atom = state;
}

void FixEQPerAtom::copy_arrays(int i, int j, int /*delflag*/)
{
  memcpy(state[j], state[i], ncol * sizeof(double));
}

void FixEQPerAtom::set_arrays(int i)
{
  memset(state[i], 0, ncol * sizeof(double));
}

int FixEQPerAtom::pack_exchange(int i, double *buf)
{
  memcpy(buf, state[i], ncol * sizeof(double));
  return ncol;
}

int FixEQPerAtom::unpack_exchange(int nlocal, double *buf)
{
  memcpy(state[nlocal], buf, ncol * sizeof(double));
  return ncol;
}

// buf[0] is the count of values, as every fix's restart data begins
int FixEQPerAtom::pack_restart(int i, double *buf)
{
  buf[0] = ncol + 1;
  memcpy(buf + 1, state[i], ncol * sizeof(double));
  return ncol + 1;
}

// The records of the restart file are checked before they are used: a
// garbled file, or one written with another per-atom size (another
// version of the package, other settings), is an error, not a read past
// the atom's data.
namespace {
// a record length for a message: an integer when it is one
std::string length_text(double c)
{
  if (c == std::floor(c) && std::fabs(c) < 1e15) return std::to_string(static_cast<long long>(c));
  char buf[32];
  snprintf(buf, sizeof(buf), "%.10g", c);
  return buf;
}
}    // namespace

void FixEQPerAtom::unpack_restart(int nlocal, int nth)
{
  const double *const rec = atom->extra[nlocal];
  const int nstore = atom->nextra_store;
  // a record's first value is its length (that value included): a whole
  // number >= 1 that fits in what is left of the atom's stored values
  auto length_ok = [](double c, int room) {
    return c >= 1.0 && c <= static_cast<double>(room) && c == std::floor(c);
  };
  int m = 0;
  for (int i = 0; i < nth; i++) {
    const double c = m < nstore ? rec[m] : 0.0;
    if (m >= nstore || !length_ok(c, nstore - m))
      error->one(FLERR,
                 "Fix {} {}: the restart file's per-atom data of atom {} is garbled: record {} "
                 "of the {} stored before this fix's has length {}, expected 1 to {} (a corrupt "
                 "file, or one written by another version of LAMMPS or the package)",
                 id, style, atom->tag[nlocal], i + 1, nth,
                 m < nstore ? length_text(c) : std::string("(beyond the data)"),
                 std::max(nstore - m, 0));
    m += static_cast<int>(c);
  }
  const double c = m < nstore ? rec[m] : 0.0;
  if (m >= nstore || c != static_cast<double>(ncol + 1) || ncol + 1 > nstore - m) {
    if (m < nstore && length_ok(c, nstore - m))
      error->one(FLERR,
                 "Fix {} {}: the restart file holds {} values per atom for this fix, it expects "
                 "{} (a corrupt file, or one written by another version of the package or other "
                 "settings{})",
                 id, style, static_cast<long>(c) - 1, ncol,
                 layout_hint(static_cast<long>(c) - 1).empty()
                     ? std::string()
                     : ": " + layout_hint(static_cast<long>(c) - 1));
    error->one(FLERR,
               "Fix {} {}: the restart file's per-atom data of atom {} is garbled: this fix's "
               "record (record {}) has length {}, expected {} with room for {} (a corrupt file, "
               "or one written by another version of the package or other settings)",
               id, style, atom->tag[nlocal], nth + 1,
               m < nstore ? length_text(c) : std::string("(beyond the data)"), ncol + 1,
               std::max(nstore - m, 0));
  }
  memcpy(state[nlocal], &rec[m + 1], ncol * sizeof(double));
  // a garbled value: every value of the state is finite
  for (int k = 0; k < ncol; k++)
    if (!std::isfinite(state[nlocal][k]))
      error->one(FLERR, "Fix {} {}: the restart file's per-atom data of atom {} is garbled: value {} "
                        "of this fix's record is {} (a corrupt file)",
                 id, style, atom->tag[nlocal], k + 1, state[nlocal][k]);
  check_restored(nlocal);
}

void FixEQPerAtom::check_reach(int i, int dir, double ref, const char *what)
{
  const EQUtil::Unwrap unwrap(atom, domain, dir);
  const double xu = unwrap(i);
  const double reach = 1e9 * (1.0 + std::fabs(xu) + domain->prd[dir]);
  if (!(std::fabs(xu - ref) <= reach))
    error->one(FLERR, "Fix {} {}: the restart file's {} of atom {} is {}, more than {:.3g} from "
                      "the atom (at {}): a garbled value (a corrupt file)", id, style, what,
               atom->tag[i], ref, reach, xu);
}

int FixEQPerAtom::size_restart(int /*nlocal*/)
{
  return ncol + 1;
}

int FixEQPerAtom::maxsize_restart()
{
  return ncol + 1;
}
