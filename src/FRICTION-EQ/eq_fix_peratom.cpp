/* ----------------------------------------------------------------------
   FRICTION-EQ package for LAMMPS: per-atom state of the package's fixes
   (see eq_fix_peratom.h)
------------------------------------------------------------------------- */

#include "eq_fix_peratom.h"

#include "atom.h"
#include "memory.h"

#include <cstring>

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
  return (double) atom->nmax * ncol * sizeof(double);
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

void FixEQPerAtom::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  memcpy(state[nlocal], &extra[nlocal][m + 1], ncol * sizeof(double));
}

int FixEQPerAtom::size_restart(int /*nlocal*/)
{
  return ncol + 1;
}

int FixEQPerAtom::maxsize_restart()
{
  return ncol + 1;
}
