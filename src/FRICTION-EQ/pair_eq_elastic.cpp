/* ----------------------------------------------------------------------
   FRICTION-EQ package for LAMMPS: pair_style eq/elastic

   Elastic interaction between contacts (Braun, Peyrard, Stryzheus,
   Tosatti, Secs. III-IV).  The contacts and their stretches belong to fix
   eq/contacts; this style evaluates the interaction field
   h_i = sum_j k_ij (x_i - x_j), its forces -h_i along the sliding
   direction, energy and virial.  With fix eq/substrate instead, x_i are
   the displacements of FK-ME blocks (Sec. V B) and the style is their
   scalar elastic coupling (e.g. a 2d interface of blocks).  The kernel k(r) is a LAMMPS-free unit
   (lib/eq_kernel.h).  A full neighbor list gives every contact all its
   partners, so the field of a contact is complete on its owner rank and
   changes after breaks are scattered with one reverse communication.
------------------------------------------------------------------------- */

#include "pair_eq_elastic.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_eq_contacts.h"
#include "fix_eq_substrate.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include "eq_distribution.h"
#include "eq_lammps_compat.h"
#include "eq_lammps_util.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;

namespace {
constexpr double NOT_A_CONTACT = std::numeric_limits<double>::quiet_NaN();
// distances within this relative margin of the cutoff count as inside, so
// a lattice shell at exactly rcut = lambda_c is included
constexpr double CUT_MARGIN = 1.0e-12;
enum { COMM_STRETCH = 1 };
const char *USAGE = "expected 'pair_coeff I J ftilde lambda_c [rcut]' or "
                    "'pair_coeff I J table FILE KEYWORD [rcut]'";
}    // namespace

/* ---------------------------------------------------------------------- */

PairEQElastic::PairEQElastic(LAMMPS *lmp) :
    Pair(lmp), cut(nullptr), cutsq_in(nullptr), ftilde(nullptr), lambda(nullptr), kidx(nullptr), mixed(nullptr),
    anisotropic(0), fix(nullptr), sub(nullptr), hcol(0), idir(0), fresh(0), comm_mode(0), nmax(0), sx(nullptr),
    dh(nullptr), ksum(nullptr), ghosts_current(0), bcache(-1)
{
  single_enable = 1;
  single_extra = 2;
  svector = new double[single_extra];
  restartinfo = 1;
  reinitflag = 0;    // see reinit()
  writedata = 0;
  one_coeff = 0;
  manybody_flag = 0;
  no_virial_fdotr_compute = 1;    // forces on local atoms only (full list)
  comm_forward = 1;
  comm_reverse = 1;
  cut_global = 0.0;
}

PairEQElastic::~PairEQElastic()
{
  delete[] svector;
  memory->destroy(sx);
  memory->destroy(dh);
  memory->destroy(ksum);
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(cut);
    memory->destroy(cutsq_in);
    memory->destroy(ftilde);
    memory->destroy(lambda);
    memory->destroy(kidx);
    memory->destroy(mixed);
  }
}

/* ---------------------------------------------------------------------- */

void PairEQElastic::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(cut, n + 1, n + 1, "pair:cut");
  memory->create(cutsq_in, n + 1, n + 1, "pair:cutsq_in");
  memory->create(ftilde, n + 1, n + 1, "pair:ftilde");
  memory->create(lambda, n + 1, n + 1, "pair:lambda");
  memory->create(kidx, n + 1, n + 1, "pair:kidx");
  memory->create(mixed, n + 1, n + 1, "pair:mixed");
  for (int i = 0; i <= n; i++)
    for (int j = 0; j <= n; j++) {
      setflag[i][j] = 0;
      cut[i][j] = cutsq_in[i][j] = ftilde[i][j] = lambda[i][j] = 0.0;
      kidx[i][j] = -1;
      mixed[i][j] = 0;
    }
}

void PairEQElastic::grow()
{
  if (atom->nmax <= nmax) return;
  nmax = atom->nmax;
  memory->destroy(sx);
  memory->destroy(dh);
  memory->destroy(ksum);
  memory->create(sx, nmax, "pair:sx");
  memory->create(dh, nmax, "pair:dh");
  memory->create(ksum, nmax, "pair:ksum");
  ghosts_current = 0;
}

/* ----------------------------------------------------------------------
   pair_style eq/elastic rcut
------------------------------------------------------------------------- */

void PairEQElastic::settings(int narg, char **arg)
{
  if (narg != 1)
    error->all(FLERR, "Illegal pair_style eq/elastic command: expected 'pair_style eq/elastic rcut'");
  cut_global = EQUtil::numeric(lmp, "Pair style eq/elastic: rcut", arg[0]);
  if (!(cut_global > 0.0) || !std::isfinite(cut_global))
    error->all(FLERR, "Pair style eq/elastic: rcut must be a finite number > 0 (got {})", arg[0]);

  // reset explicit cutoffs that were set from the previous global cutoff
  if (allocated) {
    for (int i = 1; i <= atom->ntypes; i++)
      for (int j = i; j <= atom->ntypes; j++)
        if (setflag[i][j]) cut[i][j] = cut_global;
  }
}

/* ----------------------------------------------------------------------
   pair_coeff I J ftilde lambda_c [rcut]
   pair_coeff I J table FILE KEYWORD [rcut]
------------------------------------------------------------------------- */

void PairEQElastic::coeff(int narg, char **arg)
{
  if (narg < 3) error->all(FLERR, "Incorrect args for pair eq/elastic coefficients: {}", USAGE);
  if (!allocated) allocate();

  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);

  feq::Kernel kern;
  double cut_one = cut_global;
  int next;
  try {
    if (strcmp(arg[2], "table") == 0) {
      if (narg < 5 || narg > 6)
        throw feq::SpecError("table: wrong number of values; " + std::string(USAGE));
      const std::string text = EQUtil::file_loader(lmp)(arg[3]);
      kern = feq::read_kernel_table(text, arg[3], arg[4]);
      next = 5;
    } else {
      if (narg < 4 || narg > 5) throw feq::SpecError(std::string("wrong number of values; ") + USAGE);
      const auto number = EQUtil::number_parser(lmp);
      double f, l;
      try {
        f = number(arg[2]);
      } catch (const feq::SpecError &) {
        throw feq::SpecError(std::string("ftilde '") + arg[2] +
                             "' is not a number; allowed: a number >= 0 or the word 'table'");
      }
      try {
        l = number(arg[3]);
      } catch (const feq::SpecError &) {
        throw feq::SpecError(std::string("lambda_c '") + arg[3] + "' is not a number > 0");
      }
      kern = feq::make_crossover(f, l);
      next = 4;
    }
    if (narg > next) {
      try {
        cut_one = EQUtil::number_parser(lmp)(arg[next]);
      } catch (const feq::SpecError &) {
        throw feq::SpecError(std::string("rcut '") + arg[next] + "' is not a number");
      }
      if (!(cut_one > 0.0) || !std::isfinite(cut_one))
        throw feq::SpecError(std::string("rcut must be a finite number > 0 (got ") + arg[next] + ")");
    }
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Pair eq/elastic coefficients for {} {}: {}", arg[0], arg[1], e.what());
  }

  kernels.push_back(kern);
  const int k = (int) kernels.size() - 1;
  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    for (int j = MAX(jlo, i); j <= jhi; j++) {
      kidx[i][j] = k;
      mixed[i][j] = 0;
      ftilde[i][j] = kern.ftilde;
      lambda[i][j] = kern.lambda;
      cut[i][j] = cut_one;
      setflag[i][j] = 1;
      count++;
    }
  }
  if (count == 0) error->all(FLERR, "Incorrect args for pair eq/elastic coefficients: no type pair in {} {}", arg[0], arg[1]);
}

/* ---------------------------------------------------------------------- */

void PairEQElastic::init_style()
{
  if (!atom->tag_enable) error->all(FLERR, "Pair style eq/elastic requires atom IDs");

  // the cached block pairs are keyed by neighbor->ncalls, which restarts at
  // 0 with every run or minimize, whose setup may also sort or migrate the
  // atoms: drop the cache here
  bcache = -1;

  // exactly one fix eq/contacts (contacts and their stretches) or one fix
  // eq/substrate (FK-ME blocks and their displacements)
  fix = nullptr;
  sub = nullptr;
  int ncontacts = 0, nsubstrate = 0;
  for (int i = 0; i < modify->nfix; i++) {
    if (utils::strmatch(modify->fix[i]->style, "^eq/contacts$")) {
      fix = dynamic_cast<FixEQContacts *>(modify->fix[i]);
      ++ncontacts;
    }
    if (utils::strmatch(modify->fix[i]->style, "^eq/substrate$")) {
      sub = dynamic_cast<FixEQSubstrate *>(modify->fix[i]);
      ++nsubstrate;
    }
  }
  if (ncontacts + nsubstrate == 0)
    error->all(FLERR, "Pair style eq/elastic needs a fix eq/contacts (the contacts and their "
                      "stretches) or a fix eq/substrate (blocks and their displacements); define "
                      "it before the run");
  if (ncontacts > 1 || nsubstrate > 1 || (ncontacts && nsubstrate))
    error->all(FLERR, "Pair style eq/elastic found {} fixes eq/contacts and {} fixes eq/substrate; "
               "allowed: exactly one of either", ncontacts, nsubstrate);
  int dim;
  if (fix) {
    idir = *(int *) fix->extract("dir", dim);
    hcol = FixEQContacts::INTERACT;
  } else {
    idir = *(int *) sub->extract("dir", dim);
    hcol = FixEQSubstrate::INTERACT;
  }

  anisotropic = 0;
  for (const auto &k : kernels)
    if (k.anisotropic()) anisotropic = 1;

  EQCompat::request_full_list(neighbor, this, instance_me);
  fresh = 0;
}

/* ----------------------------------------------------------------------
   mixing for crossover kernels: ftilde geometric (or as pair_modify mix),
   lambda_c and rcut as distances; tables are not mixed
------------------------------------------------------------------------- */

double PairEQElastic::init_one(int i, int j)
{
  if (setflag[i][j] == 0) {
    if (kidx[i][i] < 0 || kidx[j][j] < 0)
      error->all(FLERR, "Pair eq/elastic: coefficients for type pair {} {} are not set and cannot "
                        "be mixed (set pair_coeff {} {} or both {} {} and {} {})",
                 i, j, i, j, i, i, j, j);
    const feq::Kernel &ki = kernels[kidx[i][i]], &kj = kernels[kidx[j][j]];
    if (ki.kind != feq::Kernel::CROSSOVER || kj.kind != feq::Kernel::CROSSOVER)
      error->all(FLERR, "Pair eq/elastic: type pair {} {} would mix a table kernel; set "
                        "pair_coeff {} {} explicitly (tables are not mixed)", i, j, i, j);
    const double f = mix_energy(ki.ftilde, kj.ftilde, ki.lambda, kj.lambda);
    const double l = mix_distance(ki.lambda, kj.lambda);
    // a kernel mixed by an earlier init is replaced, not appended again
    if (kidx[i][j] >= 0 && mixed[i][j]) kernels[kidx[i][j]] = feq::make_crossover(f, l);
    else {
      kernels.push_back(feq::make_crossover(f, l));
      kidx[i][j] = (int) kernels.size() - 1;
      mixed[i][j] = 1;
    }
    ftilde[i][j] = f;
    lambda[i][j] = l;
    cut[i][j] = mix_distance(cut[i][i], cut[j][j]);
  }
  const feq::Kernel &k = kernels[kidx[i][j]];
  if (k.kind == feq::Kernel::TABLE && cut[i][j] > k.range() * (1.0 + CUT_MARGIN) && comm->me == 0 &&
      i == j)
    error->warning(FLERR, "Pair eq/elastic: rcut {} of type pair {} {} beyond the table's last r "
                          "{}: k = 0 there", cut[i][j], i, j, k.range());
  kidx[j][i] = kidx[i][j];
  ftilde[j][i] = ftilde[i][j];
  lambda[j][i] = lambda[i][j];
  cut[j][i] = cut[i][j];
  const double c = cut[i][j] * (1.0 + CUT_MARGIN);
  cutsq_in[i][j] = cutsq_in[j][i] = c * c;
  return c;
}

/* ----------------------------------------------------------------------
   k_ij of a pair at squared distance rsq, del = x_i - x_j
------------------------------------------------------------------------- */

inline double PairEQElastic::kval(int itype, int jtype, double rsq, const double *del) const
{
  const feq::Kernel &k = kernels[kidx[itype][jtype]];
  const double r = sqrt(rsq);
  if (!anisotropic || !k.anisotropic()) return k.eval(r);
  const double c2 = 2.0 * del[idir] * del[idir] / rsq - 1.0;
  return k.eval(r, c2);
}

/* ----------------------------------------------------------------------
   per-atom state of the fix that holds the coupled coordinates
------------------------------------------------------------------------- */

double **PairEQElastic::state()
{
  int dim;
  return fix ? (double **) fix->extract("state", dim) : (double **) sub->extract("state", dim);
}

/* ----------------------------------------------------------------------
   stretches of local contacts from the fix, then to the ghosts
------------------------------------------------------------------------- */

void PairEQElastic::load_stretches()
{
  double **st = state();
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  if (fix) {
    const int groupbit = fix->groupbit;
    for (int i = 0; i < nlocal; i++)
      sx[i] = ((mask[i] & groupbit) && st[i][FixEQContacts::THRESHOLD] > 0.0)
          ? st[i][FixEQContacts::STRETCH]
          : NOT_A_CONTACT;
  } else {
    // displacements from the current positions (the fix's state holds
    // those of its last force evaluation, the step before)
    const int groupbit = sub->groupbit;
    for (int i = 0; i < nlocal; i++)
      sx[i] = (mask[i] & groupbit) ? sub->displacement(i) : NOT_A_CONTACT;
  }
  comm_mode = COMM_STRETCH;
  EQCompat::forward_comm(comm, this);
  ghosts_current = 1;
}

/* ----------------------------------------------------------------------
   field h_i and coupling K_i = sum_j k_ij of all local contacts
------------------------------------------------------------------------- */

void PairEQElastic::field()
{
  grow();
  load_stretches();
  if (sub) {
    field_blocks();
    return;
  }
  double **st = state();
  double **x = atom->x;
  const int *type = atom->type;
  const double *special_lj = force->special_lj;
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const double si = sx[i];
    if (std::isnan(si)) {
      ksum[i] = 0.0;
      st[i][hcol] = 0.0;
      continue;
    }
    const int itype = type[i];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    double hi = 0.0, ki = 0.0;
    for (int jj = 0; jj < jnum; jj++) {
      int j = jlist[jj];
      const double factor = special_lj[sbmask(j)];
      j &= NEIGHMASK;
      const double sj = sx[j];
      if (std::isnan(sj)) continue;
      const int jtype = type[j];
      const double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
      if (rsq > cutsq_in[itype][jtype]) continue;
      const double k = factor * kval(itype, jtype, rsq, del);
      ki += k;
      hi += k * (si - sj);
    }
    ksum[i] = ki;
    st[i][hcol] = hi;
  }
}

/* ----------------------------------------------------------------------
   blocks of fix eq/substrate: the pairs of the neighbor list whose sites
   are within the cutoff, with k_ij at the sites' distance
   (x_i - x_j - (u_i - u_j) along dir); valid until the next list build
------------------------------------------------------------------------- */

void PairEQElastic::block_pairs()
{
  double **x = atom->x;
  const int *type = atom->type;
  const double *special_lj = force->special_lj;
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  const int d = idir;
  bfirst.assign(inum + 1, 0);
  bj.clear();
  bk.clear();
  for (int ii = 0; ii < inum; ii++) {
    bfirst[ii] = (int) bj.size();
    const int i = ilist[ii];
    const double si = sx[i];
    if (std::isnan(si)) continue;
    const int itype = type[i];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      int j = jlist[jj];
      const double factor = special_lj[sbmask(j)];
      j &= NEIGHMASK;
      const double sj = sx[j];
      if (std::isnan(sj)) continue;
      const int jtype = type[j];
      double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      del[d] -= si - sj;
      const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
      if (rsq > cutsq_in[itype][jtype]) continue;
      bj.push_back(j);
      bk.push_back(factor * kval(itype, jtype, rsq, del));
    }
  }
  bfirst[inum] = (int) bj.size();
  bcache = neighbor->ncalls;
}

/* ----------------------------------------------------------------------
   field h_i = sum_j k_ij (u_i - u_j) of the blocks.  A coupled pair is in
   the neighbor list of the current positions as long as the blocks'
   displacements differ by less than the skin: checked every step with a
   margin of a factor 2 for the motion until the next list build
------------------------------------------------------------------------- */

void PairEQElastic::field_blocks()
{
  if (bcache != neighbor->ncalls || (int) bfirst.size() != list->inum + 1) block_pairs();
  double **st = state();
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *first = bfirst.data();
  const int *jv = bj.data();
  const double *kv = bk.data();
  const double dumax = 0.5 * neighbor->skin;
  double dubig = 0.0;
  int ibig = -1, jbig = -1;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const double si = sx[i];
    if (std::isnan(si)) {
      ksum[i] = 0.0;
      st[i][hcol] = 0.0;
      continue;
    }
    double hi = 0.0, ki = 0.0;
    for (int m = first[ii]; m < first[ii + 1]; m++) {
      const double ds = si - sx[jv[m]];
      ki += kv[m];
      hi += kv[m] * ds;
      if (std::fabs(ds) > dubig) {
        dubig = std::fabs(ds);
        ibig = i;
        jbig = jv[m];
      }
    }
    ksum[i] = ki;
    st[i][hcol] = hi;
  }
  if (dubig > dumax)
    error->one(FLERR,
               "Pair eq/elastic: the displacements of coupled blocks {} and {} differ by {:.6g}, more "
               "than half the neighbor skin {}: coupled pairs may be missing from the neighbor "
               "list; raise the skin (neighbor SKIN bin) above twice the largest difference",
               atom->tag[ibig], atom->tag[jbig], dubig, neighbor->skin);
}

/* ----------------------------------------------------------------------
   contacts list[0..n) changed their stretches by ds: h_i += K_i ds_i and
   h_j -= k_ij ds_i for all partners j (ghost shares returned to owners)
------------------------------------------------------------------------- */

void PairEQElastic::scatter(const int *clist, int n, const double *ds)
{
  double **st = state();
  double **x = atom->x;
  const int *type = atom->type;
  const double *special_lj = force->special_lj;
  const int nall = atom->nlocal + atom->nghost;
  const int nlocal = atom->nlocal;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  for (int i = 0; i < nall; i++) dh[i] = 0.0;
  for (int m = 0; m < n; m++) {
    const int i = clist[m];
    const double d = ds[i];
    dh[i] += ksum[i] * d;
    const int itype = type[i];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      int j = jlist[jj];
      const double factor = special_lj[sbmask(j)];
      j &= NEIGHMASK;
      if (std::isnan(sx[j])) continue;
      const int jtype = type[j];
      const double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
      if (rsq > cutsq_in[itype][jtype]) continue;
      dh[j] -= factor * kval(itype, jtype, rsq, del) * d;
    }
  }
  EQCompat::reverse_comm(comm, this);
  for (int i = 0; i < nlocal; i++)
    if (!std::isnan(sx[i])) st[i][hcol] += dh[i];
  ghosts_current = 0;
}

/* ---------------------------------------------------------------------- */

void PairEQElastic::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  grow();
  if (!fresh) {
    // not prepared by fix eq/contacts this step (run 0, minimization,
    // rerun; always with fix eq/substrate): stretches or displacements
    // from the current positions, no breaking
    if (fix) fix->update_stretches();
    field();
  }
  fresh = 0;

  double **st = state();
  double **f = atom->f;
  const int nlocal = atom->nlocal;
  const int d = idir;
  for (int i = 0; i < nlocal; i++)
    if (!std::isnan(sx[i])) f[i][d] -= st[i][hcol];

  // after an avalanche the stretches held here (local and ghost) are those
  // before its breaks: reload them, for the energy below and for single()
  // (compute pair/local), one forward communication on steps with breaks
  if (!ghosts_current) load_stretches();
  if (!evflag) return;

  // energy and virial: one more pass, only on steps that need them
  double **x = atom->x;
  const int *type = atom->type;
  const double *special_lj = force->special_lj;
  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  double fv[3] = {0.0, 0.0, 0.0};

  if (sub) {
    // blocks: the cached pairs, the virial at the sites' separation
    if (bcache != neighbor->ncalls || (int) bfirst.size() != inum + 1) block_pairs();
    for (int ii = 0; ii < inum; ii++) {
      const int i = ilist[ii];
      const double si = sx[i];
      if (std::isnan(si)) continue;
      for (int m = bfirst[ii]; m < bfirst[ii + 1]; m++) {
        const int j = bj[m];
        const double k = bk[m], ds = si - sx[j];
        double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
        del[d] -= ds;
        fv[d] = -k * ds;
        ev_tally_xyz_full(i, 0.5 * k * ds * ds, 0.0, fv[0], fv[1], fv[2], del[0], del[1], del[2]);
      }
    }
    return;
  }

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const double si = sx[i];
    if (std::isnan(si)) continue;
    const int itype = type[i];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      int j = jlist[jj];
      const double factor = special_lj[sbmask(j)];
      j &= NEIGHMASK;
      const double sj = sx[j];
      if (std::isnan(sj)) continue;
      const int jtype = type[j];
      const double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
      if (rsq > cutsq_in[itype][jtype]) continue;
      const double k = factor * kval(itype, jtype, rsq, del);
      const double ds = si - sj;
      fv[d] = -k * ds;
      ev_tally_xyz_full(i, 0.5 * k * ds * ds, 0.0, fv[0], fv[1], fv[2], del[0], del[1], del[2]);
    }
  }
}

/* ----------------------------------------------------------------------
   energy of one pair; the force is not central (it acts along the sliding
   direction), so fforce = 0 and svector = {k_ij, force on i along dir}
------------------------------------------------------------------------- */

double PairEQElastic::single(int i, int j, int itype, int jtype, double rsq,
                             double /*factor_coul*/, double factor_lj, double &fforce)
{
  fforce = 0.0;
  svector[0] = svector[1] = 0.0;
  if ((!fix && !sub) || !sx || i >= nmax || j >= nmax) return 0.0;
  if (std::isnan(sx[i]) || std::isnan(sx[j])) return 0.0;
  if (rsq > cutsq_in[itype][jtype]) return 0.0;
  double **x = atom->x;
  double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
  if (sub) del[idir] -= sx[i] - sx[j];
  rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
  if (rsq > cutsq_in[itype][jtype]) return 0.0;
  const double k = factor_lj * kval(itype, jtype, rsq, del);
  const double ds = sx[i] - sx[j];
  svector[0] = k;
  svector[1] = -k * ds;
  return 0.5 * k * ds * ds;
}

/* ---------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   fix adapt: the kernels are built by pair_coeff, and the cached block
   pairs and the field of the contacts would not follow a change of the
   extract()ed arrays: refused with an error that says what to do instead
------------------------------------------------------------------------- */

void PairEQElastic::reinit()
{
  error->all(FLERR, "Pair style eq/elastic does not support fix adapt (its kernels are set by "
                    "pair_coeff): change the coefficients with pair_coeff between runs");
}

void *PairEQElastic::extract(const char *str, int &dim)
{
  dim = 2;
  if (strcmp(str, "ftilde") == 0) return (void *) ftilde;
  if (strcmp(str, "lambda_c") == 0) return (void *) lambda;
  if (strcmp(str, "cut") == 0) return (void *) cut;
  return nullptr;
}

/* ---------------------------------------------------------------------- */

int PairEQElastic::pack_forward_comm(int n, int *list_, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  for (int i = 0; i < n; i++) buf[i] = sx[list_[i]];
  return n;
}

void PairEQElastic::unpack_forward_comm(int n, int first, double *buf)
{
  for (int i = 0; i < n; i++) sx[first + i] = buf[i];
}

int PairEQElastic::pack_reverse_comm(int n, int first, double *buf)
{
  for (int i = 0; i < n; i++) buf[i] = dh[first + i];
  return n;
}

void PairEQElastic::unpack_reverse_comm(int n, int *list_, double *buf)
{
  for (int i = 0; i < n; i++) dh[list_[i]] += buf[i];
}

/* ----------------------------------------------------------------------
   restart: settings and every explicitly set kernel (tables included)
------------------------------------------------------------------------- */

void PairEQElastic::write_restart_settings(FILE *fp)
{
  fwrite(&cut_global, sizeof(double), 1, fp);
  fwrite(&mix_flag, sizeof(int), 1, fp);
}

void PairEQElastic::read_restart_settings(FILE *fp)
{
  if (comm->me == 0) {
    utils::sfread(FLERR, &cut_global, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &mix_flag, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&cut_global, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&mix_flag, 1, MPI_INT, 0, world);
}

void PairEQElastic::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (!setflag[i][j]) continue;
      const feq::Kernel &k = kernels[kidx[i][j]];
      const int kind = (int) k.kind;
      const int n = (int) k.r.size();
      const int aniso = k.anisotropic() ? 1 : 0;
      fwrite(&kind, sizeof(int), 1, fp);
      fwrite(&k.ftilde, sizeof(double), 1, fp);
      fwrite(&k.lambda, sizeof(double), 1, fp);
      fwrite(&cut[i][j], sizeof(double), 1, fp);
      fwrite(&n, sizeof(int), 1, fp);
      fwrite(&aniso, sizeof(int), 1, fp);
      if (n > 0) {
        fwrite(k.r.data(), sizeof(double), n, fp);
        fwrite(k.k0.data(), sizeof(double), n, fp);
        if (aniso) fwrite(k.k2.data(), sizeof(double), n, fp);
      }
    }
}

void PairEQElastic::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  kernels.clear();
  const int me = comm->me;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (!setflag[i][j]) continue;
      int kind = 0, n = 0, aniso = 0;
      feq::Kernel k;
      if (me == 0) {
        utils::sfread(FLERR, &kind, sizeof(int), 1, fp, nullptr, error);
        utils::sfread(FLERR, &k.ftilde, sizeof(double), 1, fp, nullptr, error);
        utils::sfread(FLERR, &k.lambda, sizeof(double), 1, fp, nullptr, error);
        utils::sfread(FLERR, &cut[i][j], sizeof(double), 1, fp, nullptr, error);
        utils::sfread(FLERR, &n, sizeof(int), 1, fp, nullptr, error);
        utils::sfread(FLERR, &aniso, sizeof(int), 1, fp, nullptr, error);
      }
      MPI_Bcast(&kind, 1, MPI_INT, 0, world);
      MPI_Bcast(&k.ftilde, 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&k.lambda, 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&cut[i][j], 1, MPI_DOUBLE, 0, world);
      MPI_Bcast(&n, 1, MPI_INT, 0, world);
      MPI_Bcast(&aniso, 1, MPI_INT, 0, world);
      k.kind = (feq::Kernel::Kind) kind;
      k.r.resize(n);
      k.k0.resize(n);
      if (aniso) k.k2.resize(n);
      if (n > 0) {
        if (me == 0) {
          utils::sfread(FLERR, k.r.data(), sizeof(double), n, fp, nullptr, error);
          utils::sfread(FLERR, k.k0.data(), sizeof(double), n, fp, nullptr, error);
          if (aniso) utils::sfread(FLERR, k.k2.data(), sizeof(double), n, fp, nullptr, error);
        }
        MPI_Bcast(k.r.data(), n, MPI_DOUBLE, 0, world);
        MPI_Bcast(k.k0.data(), n, MPI_DOUBLE, 0, world);
        if (aniso) MPI_Bcast(k.k2.data(), n, MPI_DOUBLE, 0, world);
      }
      k.source = k.kind == feq::Kernel::TABLE ? "table (restart)" : "crossover";
      kernels.push_back(k);
      kidx[i][j] = (int) kernels.size() - 1;
      ftilde[i][j] = k.ftilde;
      lambda[i][j] = k.lambda;
    }
}

/* ---------------------------------------------------------------------- */

double PairEQElastic::memory_usage()
{
  double bytes = Pair::memory_usage();
  bytes += 3.0 * nmax * sizeof(double);
  return bytes;
}
