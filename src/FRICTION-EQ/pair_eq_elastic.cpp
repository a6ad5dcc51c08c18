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
   FRICTION-EQ package for LAMMPS: pair_style eq/elastic

   Elastic interaction between the atoms of one coordinate source (Braun,
   Peyrard, Stryzheus, Tosatti, Secs. III-V): contacts of fix eq/contacts
   (q = stretch) or FK-ME blocks of fix eq/substrate (q = displacement).
   This style is the source's elastic field (eq_field.h): it owns
   h_i = sum_j k_ij (q_i - q_j) and K_i = sum_j k_ij and applies -h_i
   along the source's direction.  The kernel k(r) is a LAMMPS-free unit
   (lib/eq_kernel.h).

   Who owns what (eq_field.h): the source owns the coordinates, their
   force evaluations and versions, and its change sets; this style owns
   the field and everything cached for it, and reads from the source what
   it needs when it needs it (refresh(): from field_view(), which the
   contacts call before and after every avalanche round, and from
   compute()).  It never writes into the source.

   Incremental field, within one validity key (see refresh()):
   - contacts: when every coupled atom this rank holds (local and ghost)
     moved by the same distance along dir since the last evaluation (to
     the rounding of the positions), h is unchanged: a rigid slider costs
     O(N) and no pair work, whatever the cutoff; otherwise h is recomputed
     over the pairs of the list, cached with their k_ij at the list build;
   - a change set of the source (the breaks of an avalanche round) changes
     h of the partners only: O(breaks x neighbours), one reverse
     communication per round carrying the touched ghosts' shares only;
     the view names the owned atoms whose h changed (the fix tests only
     those in the next round), and after breaks only the changed
     coordinates go to the ghosts (once per step); a set the source flags
     as too large to follow (on any rank) is recomputed on all ranks;
   - blocks (sites fixed): q = x - w along dir, h and the forces in one
     pass over the cached pairs in compute().
   Only the coupled ghosts of the lists (glist) are followed.  Every
   `check` updates the field is recomputed from scratch as a drift check
   whose result is reported at the end of each run.  A full neighbor list
   gives every atom all its partners, so h is complete on the owner and a
   break's changes reach the partners' owners by one reverse
   communication.
------------------------------------------------------------------------- */

#include "pair_eq_elastic.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include "eq_cite.h"
#include "eq_distribution.h"
#include "eq_lammps_compat.h"
#include "eq_lammps_util.h"
#include "eq_link.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;

namespace {
constexpr double NOT_COUPLED = std::numeric_limits<double>::quiet_NaN();
// distances within this relative margin of the cutoff count as inside, so
// that a lattice shell at exactly rcut = lambda_c is included for the whole
// run: integrating the positions adds a rounding of up to ulp(|x|)/2 per
// step to each atom, different for each, so the distances of a rigidly
// moving lattice wander (1e-12 of rcut = 3 after a few 1e3 steps at
// |x| ~ 60 was crossed: pairs of the shell dropped at the next list build,
// a change of h by k(rcut) |dq|, 1 % of h); 1e-8 covers 1e6 steps at
// |x| = 100 rcut in the worst case, and no physics lives at that scale
constexpr double CUT_MARGIN = 1.0e-8;
// two coupled atoms closer than this fraction of their cutoff are at one
// place (k ~ 1/r: 1e10 times its value at the cutoff)
constexpr double OVERLAP = 1.0e-10;
// default number of field updates between two drift checks
constexpr int CHECK_DEFAULT = 1000;
const char *USAGE = "expected 'pair_coeff I J ftilde lambda_c [rcut]' or "
                    "'pair_coeff I J table FILE KEYWORD [rcut]'";
}    // namespace

/* ---------------------------------------------------------------------- */

PairEQElastic::PairEQElastic(LAMMPS *lmp) :
    Pair(lmp), check_every(CHECK_DEFAULT), cut(nullptr), cutsq_in(nullptr), ftilde(nullptr),
    lambda(nullptr), kidx(nullptr), mixed(nullptr), anisotropic(0), ncoeff(0), ncoeff_init(0),
    idir(0), site_distance(false), nmax(0), q(nullptr), w(nullptr), h(nullptr), ksum(nullptr),
    dh(nullptr), dk(nullptr), xq(nullptr), mom(nullptr), member_bit(0), key(), key_set(false),
    eval_seen(-1), version_seen(-1), ghost_version(-1), eval_computed(-1), eval_built(-1),
    pending(0), nfield(0), vir_at(-1), mom_valid(false), comm_mode(COMM_ALL), gsorted(true),
    changed_at(-1), smark_ghosts(false)
{
  EQCite::add(lmp);
  single_enable = 1;
  single_extra = 7;
  svector = new double[single_extra];
  // a sub-style of pair hybrid (the pair style being defined) of a LAMMPS
  // whose hybrid would crash on the extra values offers none
  if (EQCompat::HYBRID_SVECTOR_BUG && force->pair_style &&
      utils::strmatch(force->pair_style, "^hybrid") &&
      !utils::strmatch(force->pair_style, "^hybrid/overlay"))
    single_extra = 0;
  restartinfo = 1;
  reinitflag = 0;    // see reinit()
  writedata = 0;
  one_coeff = 0;
  manybody_flag = 0;
  no_virial_fdotr_compute = 1;    // forces on local atoms only (full list)
  // sparse exchanges (changed ghosts, scattered shares): a count, then
  // (index, value) pairs, at most 1 + 2 n values for n atoms; the shares
  // of a change of members: (index, share of K, share of h) triples
  comm_forward = 3;
  comm_reverse = 4;
  cut_global = 0.0;
  wvir[0] = wvir[1] = wvir[2] = 0.0;
  n_update = n_uniform = n_rebuild = n_nonuniform = n_advance = n_change = n_check = n_joined = 0;
  n_members = 0;
  drift_max = hscale_max = kdrift_max = kscale_max = 0.0;
}

PairEQElastic::~PairEQElastic()
{
  delete[] svector;
  memory->destroy(q);
  memory->sfree(xq);
  memory->destroy(w);
  memory->destroy(h);
  memory->destroy(ksum);
  memory->destroy(dh);
  memory->destroy(dk);
  memory->sfree(mom);
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

// per-atom arrays; they grow only when atoms arrive (at a list build)
void PairEQElastic::grow()
{
  if (atom->nmax <= nmax) return;
  nmax = atom->nmax;
  memory->destroy(q);
  memory->sfree(xq);
  memory->destroy(w);
  memory->destroy(h);
  memory->destroy(ksum);
  memory->destroy(dh);
  memory->sfree(mom);
  memory->create(q, nmax, "pair:q");
  xq = static_cast<double(*)[3]>(memory->smalloc(sizeof(double[3]) * nmax, "pair:xq"));
  memory->create(w, nmax, "pair:w");
  memory->create(h, nmax, "pair:h");
  memory->create(ksum, nmax, "pair:ksum");
  memory->destroy(dk);
  memory->create(dh, nmax, "pair:dh");
  memory->create(dk, nmax, "pair:dk");
  memset(dh, 0, nmax * sizeof(double));
  memset(dk, 0, nmax * sizeof(double));
  tmark.assign(nmax, 0);
  cmark.assign(nmax, 0);
  csync.clear();
  smark.assign(nmax, 0);
  smarked.clear();
  mom = static_cast<double(*)[3]>(memory->smalloc(sizeof(double[3]) * nmax, "pair:mom"));
  key_set = false;    // the arrays hold nothing now
}

/* ----------------------------------------------------------------------
   pair_style eq/elastic rcut [check N]
------------------------------------------------------------------------- */

void PairEQElastic::settings(int narg, char **arg)
{
  if (narg != 1 && narg != 3)
    error->all(FLERR, "Illegal pair_style eq/elastic command: expected 'pair_style eq/elastic rcut "
                      "[check N]'");
  ++ncoeff;    // the cutoffs change
  cut_global = EQUtil::numeric(lmp, "Pair style eq/elastic: rcut", arg[0]);
  if (!(cut_global > 0.0) || !std::isfinite(cut_global))
    error->all(FLERR, "Pair style eq/elastic: rcut must be a finite number > 0 (got {})", arg[0]);
  check_every = CHECK_DEFAULT;
  if (narg == 3) {
    if (strcmp(arg[1], "check") != 0)
      error->all(FLERR, "Pair style eq/elastic: unknown keyword '{}'; allowed: check", arg[1]);
    const bigint n = EQUtil::bnumeric(lmp, "Pair style eq/elastic: check", arg[2]);
    if (n < 0 || n > MAXSMALLINT)
      error->all(FLERR, "Pair style eq/elastic: check must be an integer >= 0 (0: never; got {})",
                 arg[2]);
    check_every = static_cast<int>(n);
  }

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

  // the two type ranges are checked here, so that a bad one is named
  // (LAMMPS' utils::bounds() answers 'Invalid range string: 0' or
  // 'Numeric index 3 is out of bounds (1-2)'): N, *, *N, M*, M*N with
  // 1 <= M <= N <= ntypes
  const int ntypes = atom->ntypes;
  for (int k = 0; k < 2; ++k) {
    const std::string t = arg[k];
    const size_t star = t.find('*');
    const std::string lo = t.substr(0, star);
    const std::string hi = star == std::string::npos ? lo : t.substr(star + 1);
    auto number = [](const std::string &v) -> long long {    // -1: not a number
      if (v.empty() || v.size() > 18 || v.find_first_not_of("0123456789") != std::string::npos)
        return -1;
      return std::stoll(v);
    };
    const long long nlo = lo.empty() && star != std::string::npos ? 1 : number(lo);
    const long long nhi = hi.empty() && star != std::string::npos ? ntypes : number(hi);
    std::string why;
    if (nlo < 0 || nhi < 0 || (star != std::string::npos && t.find('*', star + 1) != std::string::npos))
      why = "is neither an atom type nor a range of types";
    else if (nlo < 1 || nhi > ntypes)
      why = fmt::format("is out of range (the box has {} atom type{})", ntypes, ntypes > 1 ? "s" : "");
    else if (nlo > nhi)
      why = "is an empty range";
    if (!why.empty())
      error->all(FLERR, "Pair eq/elastic coefficients for {} {}: atom type '{}' {}; allowed: 1-{}, *, "
                        "*N, M*, M*N", arg[0], arg[1], t, why, ntypes);
  }
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
      if (!std::isfinite(f * l * l) || !std::isfinite(f / l))
        throw feq::SpecError(fmt::format("ftilde {} and lambda_c {} overflow the kernel (ftilde "
                                         "lambda_c^2 and ftilde/lambda_c must be finite)",
                                         arg[2], arg[3]));
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
  ++ncoeff;
  const int k = static_cast<int>(kernels.size()) - 1;
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

/* ----------------------------------------------------------------------
   the coordinate source of this run: exactly one fix of the package that
   provides coordinates (fix eq/contacts, eq/substrate, eq/meso)
------------------------------------------------------------------------- */

void PairEQElastic::init_style()
{
  if (!atom->tag_enable) error->all(FLERR, "Pair style eq/elastic requires atom IDs");
  int nfield = 0;
  EQLink::elastic_pair(force, nfield);
  if (nfield > 1)
    error->all(FLERR, "Pair style {} has {} sub-styles eq/elastic; allowed: one (the elastic "
                      "field of the contacts or blocks is one interaction: give all its type pairs "
                      "to one sub-style)", force->pair_style, nfield);

  source.clear();
  EQCoordinateSource *found = nullptr;
  Fix *found_fix = nullptr;
  int nsources = 0;
  std::string names;
  for (int i = 0; i < modify->nfix; i++) {
    auto *s = dynamic_cast<EQCoordinateSource *>(modify->fix[i]);
    if (!s) continue;
    if (!found) {
      found = s;
      found_fix = modify->fix[i];
    }
    names += (nsources++ ? ", " : "") + std::string(s->eq_name());
  }
  if (nsources == 0)
    error->all(FLERR, "Pair style eq/elastic needs a fix eq/contacts (the contacts and their "
                      "stretches), eq/substrate or eq/meso (blocks and their displacements); define "
                      "it before the run");
  if (nsources > 1)
    error->all(FLERR, "Pair style eq/elastic found {} fixes with coordinates ({}); allowed: "
                      "exactly one fix eq/contacts, eq/substrate or eq/meso", nsources, names);
  source.set(found, found_fix);
  source_label = found->eq_name();
  idir = found->source_dir();
  site_distance = found->source_site_distance();

  anisotropic = 0;
  for (const auto &k : kernels)
    if (k.anisotropic()) anisotropic = 1;

  EQCompat::request_full_list(neighbor, this, instance_me);
  ncoeff_init = ncoeff;
  // every run or minimize sets up afresh (its setup may sort or migrate
  // the atoms): the field is recomputed at its first update
  key_set = false;
  eval_computed = -1;
}

int PairEQElastic::field_source_instance() const
{
  return source.instance();
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
      kidx[i][j] = static_cast<int>(kernels.size()) - 1;
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
   The one validity rule of the field.  h, K, the moments, the cached
   pairs and the ghosts' q and w belong to the key they were computed for
   (the source, the last neighbor list build, the numbers of local and
   ghost atoms, the box): any change of it (a run's setup, a list build,
   change_box, fix deform, box flips, atoms created, deleted, sorted,
   migrated or displaced, read_data, read_restart, new coefficients,
   another source) recomputes them all from the source's coordinates,
   once per force evaluation of the source.  Within a key the field
   follows the source's counters: a new evaluation (the positions moved)
   and new versions (changes at fixed positions).
------------------------------------------------------------------------- */

bool PairEQElastic::Key::operator==(const Key &o) const
{
  if (source != o.source || lastcall != o.lastcall || nlocal != o.nlocal || nghost != o.nghost)
    return false;
  for (int k = 0; k < 9; k++)
    if (box[k] != o.box[k]) return false;
  return true;
}

PairEQElastic::Key PairEQElastic::key_now() const
{
  Key k;
  k.source = source.instance();
  k.lastcall = neighbor->lastcall;
  k.nlocal = atom->nlocal;
  k.nghost = atom->nghost;
  for (int d = 0; d < 3; d++) {
    k.box[d] = domain->boxlo[d];
    k.box[3 + d] = domain->prd[d];
  }
  k.box[6] = domain->xy;
  k.box[7] = domain->xz;
  k.box[8] = domain->yz;
  return k;
}

// the source found at init, if it is still defined (else an error naming it)
EQCoordinateSource *PairEQElastic::live_source()
{
  EQCoordinateSource *s = EQLink::live_fix(source, modify);
  if (s) return s;
  if (!source)
    error->all(FLERR, "Pair style eq/elastic was not set up for this force evaluation (a "
                      "pair_style command during a run, e.g. in run N pre no every M: use pre yes)");
  error->all(FLERR, "Pair style eq/elastic: {}, the coordinate source found at the start of the "
                    "run, was removed or replaced during the run (e.g. unfix in run N pre no every "
                    "M); the field cannot go on without it: use pre yes, or define the fix anew "
                    "between runs", source_label);
  return nullptr;
}

void PairEQElastic::refresh()
{
  EQCoordinateSource *src = live_source();
  if (ncoeff != ncoeff_init)
    error->all(FLERR, "Pair style eq/elastic: pair_style or pair_coeff during a run (run N pre no "
                      "every M) is not supported: the kernels and cutoffs are set up when a run "
                      "starts; use pre yes");
  grow();
  member_bit = site_distance ? 0 : src->source_groupbit();
  const bigint eval = src->source_evaluation();
  const bigint version = src->source_version();
  const Key now = key_now();
  const bool built = neighbor->ago == 0 && eval != eval_built;
  if (!key_set || built || !(now == key)) {
    if (key_set && !built && now.lastcall == key.lastcall &&
        (now.nlocal != key.nlocal || now.nghost != key.nghost))
      error->all(FLERR, "Pair style eq/elastic: the atoms changed ({} local and {} ghost atoms, "
                        "{} and {} at the last neighbor list build) without a new neighbor list "
                        "(a command during a run with pre no?): use pre yes",
                 now.nlocal, now.nghost, key.nlocal, key.nghost);
    key = now;
    key_set = true;
    eval_built = eval_seen = eval;
    version_seen = version;
    ++n_update;
    ++n_rebuild;
    recompute(src);
    return;
  }
  if (eval != eval_seen) {    // the positions may have moved
    // and contacts may have joined the field there (a set of members: the
    // end of formation delays); a new version that is neither: recompute
    EQChangeSet set;
    const bool newer = version != version_seen;
    const bool one_set = newer && src->source_changes(version_seen, set);
    const bool joins = one_set && set.members;
    eval_seen = eval;
    version_seen = version;
    ++n_update;
    if ((newer && !one_set) || (joins && !set.exact)) {
      ++n_joined;
      recompute(src);
    } else if (check_every > 0 && n_update % check_every == 0)
      drift_check(src, joins ? &set : nullptr);
    else
      update(src, joins ? &set : nullptr, true);
    return;
  }
  if (version != version_seen) {    // changes at fixed positions
    EQChangeSet set;
    const bool one_set = src->source_changes(version_seen, set);
    version_seen = version;
    if (!one_set || !set.exact) {    // the set of coupled atoms changed, or changes too large
      if (!one_set || set.members) ++n_joined;
      recompute(src);
    } else if (set.members)
      change_members(src, set, false);
    else
      scatter(set);
  }
}

// a new evaluation: the positions (follow()), then the members that
// joined or left there (set, or nullptr)
void PairEQElastic::update(EQCoordinateSource *src, const EQChangeSet *set, bool count)
{
  if (!set) {
    follow(src, count);
    return;
  }
  for (int m = 0; m < set->n; m++) mark_member(set->list[m]);
  follow(src, count);    // the members of the set as they were
  change_members(src, *set, true);
}

// everything from the source's coordinates (ghosts from their owners)
void PairEQElastic::recompute(EQCoordinateSource *src)
{
  memcpy(q, src->source_coordinates(), atom->nlocal * sizeof(double));
  pending = 0;
  rebuild(true);
}

/* ----------------------------------------------------------------------
   owners' coordinates to their ghosts; w = x - q along dir for all atoms
------------------------------------------------------------------------- */

void PairEQElastic::sync_ghosts()
{
  comm_mode = COMM_ALL;
  EQCompat::forward_comm(comm, this);
  double **x = atom->x;
  const int nall = atom->nlocal + atom->nghost;
  for (int i = 0; i < nall; i++) w[i] = x[i][idir] - q[i];
  clear_changed();
}

// after change sets: only the atoms they changed, to their ghosts (the
// other ghosts' w = x - q still hold)
void PairEQElastic::sync_changed()
{
  comm_mode = COMM_CHANGED;
  EQCompat::forward_comm(comm, this);
  clear_changed();
}

void PairEQElastic::clear_changed()
{
  for (const int i : csync) cmark[i] = 0;
  csync.clear();
  ghost_version = version_seen;
}

/* ----------------------------------------------------------------------
   the coupled pairs of the neighbor list with their k_ij (at the atoms'
   distance; blocks: at their sites' distance), h, K, the moments of the
   virial and this rank's share of it.  fresh_ghosts: the ghosts' q come
   from their owners (forward communication), else from x - w.
------------------------------------------------------------------------- */

void PairEQElastic::rebuild(bool fresh_ghosts)
{
  double **x = atom->x;
  const int *type = atom->type;
  const int *mask = atom->mask;
  const tagint *tag = atom->tag;
  const double *special_lj = force->special_lj;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int d = idir;
  const int mbit = member_bit;
  // the coupled ghosts of the lists: from the owners at a list build (and
  // after breaks), else from x - w (glist is that of the same list)
  if (fresh_ghosts) {
    sync_ghosts();
    for (int i = 0; i < nall; i++) memcpy(xq[i], x[i], sizeof(double[3]));
    glist.clear();
    gmark.assign(nall - nlocal, 0);
  } else {
    for (int i = 0; i < nlocal; i++) memcpy(xq[i], x[i], sizeof(double[3]));
    for (const int i : glist) {
      q[i] = x[i][d] - w[i];
      memcpy(xq[i], x[i], sizeof(double[3]));
    }
  }

  const int inum = list->inum;
  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  first.assign(2 * static_cast<size_t>(nlocal), 0);
  rowlocal.assign(nlocal, 1);
  pj.clear();
  pk.clear();
  for (int i = 0; i < nlocal; i++) {
    h[i] = ksum[i] = 0.0;
    mom[i][0] = mom[i][1] = mom[i][2] = 0.0;
  }
  double dubig = 0.0;
  int ibig = -1, jbig = -1;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    first[2 * i] = static_cast<int>(pj.size());
    const double qi = q[i];
    const bool coupled_i = !std::isnan(qi);
    if (!coupled_i && !(mask[i] & mbit)) {
      first[2 * i + 1] = static_cast<int>(pj.size());
      continue;
    }
    const int itype = type[i];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    double hi = 0.0, ki = 0.0, m0 = 0.0, m1 = 0.0, m2 = 0.0;
    for (int jj = 0; jj < jnum; jj++) {
      int j = jlist[jj];
      const double factor = special_lj[sbmask(j)];
      j &= NEIGHMASK;
      const double qj = q[j];
      const bool coupled_j = !std::isnan(qj);
      if (!coupled_j && !(mask[j] & mbit)) continue;
      if (fresh_ghosts && j >= nlocal) gmark[j - nlocal] = 1;
      // a periodic image of the atom itself is the same contact or block:
      // no interaction (it would only enter K_i and the re-forming of a
      // broken contact, as if its own stretch stayed behind)
      if (tag[j] == tag[i]) continue;
      const int jtype = type[j];
      double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      if (site_distance) del[d] -= qi - qj;
      const double rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
      if (rsq > cutsq_in[itype][jtype]) continue;
      if (!(rsq > OVERLAP * OVERLAP * cutsq_in[itype][jtype])) overlap_error(i, j);
      const double k = factor * kval(itype, jtype, rsq, del);
      pj.push_back(j);
      pk.push_back(k);
      if (j >= nlocal) rowlocal[i] = 0;
      if (!coupled_i || !coupled_j) continue;    // a pair cached for a change of members
      const double dq = qi - qj;
      if (site_distance && k != 0.0 && std::fabs(dq) > dubig) {
        dubig = std::fabs(dq);
        ibig = i;
        jbig = j;
      }
      ki += k;
      hi += k * dq;
      m0 += k * del[0];
      m1 += k * del[1];
      m2 += k * del[2];
    }
    h[i] = hi;
    ksum[i] = ki;
    mom[i][0] = m0;
    mom[i][1] = m1;
    mom[i][2] = m2;
    first[2 * i + 1] = static_cast<int>(pj.size());
  }
  // the coupled ghosts of the lists in the order of their index (a
  // sequential pass over the ghosts' arrays at every update)
  if (fresh_ghosts)
    for (int i = nlocal; i < nall; i++)
      if (gmark[i - nlocal]) glist.push_back(i);
  ++nfield;
  mom_valid = true;
  virial_now();
  // blocks: a coupled pair stays in the list while the displacements of
  // its blocks differ by less than the skin (see site_field())
  if (site_distance && dubig > 0.5 * neighbor->skin) skin_error(ibig, jbig, dubig);
}

// this rank's share of the virial, (1/2) sum_j del_a f_j along dir with
// f = -k (q_i - q_j), from the pairs (the moments alone do not give it);
// after a change of members the moments too
void PairEQElastic::virial_now()
{
  if (mom_valid) virial_pairs<false>();
  else virial_pairs<true>();
  mom_valid = true;
  vir_at = nfield;
  vir_pending.clear();
}

template <bool MOMENTS> void PairEQElastic::virial_pairs()
{
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  double vir[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < nlocal; i++) {
    const double qi = q[i];
    if (std::isnan(qi)) continue;
    double m0 = 0.0, m1 = 0.0, m2 = 0.0;
    for (int m = first[2 * i]; m < first[2 * i + 1]; m++) {
      const int j = pj[m];
      if (std::isnan(q[j])) continue;    // not coupled now (cached for a change of members)
      const double dq = qi - q[j], fd = -pk[m] * dq;
      double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
      if (site_distance) del[idir] -= dq;
      vir[0] += 0.5 * del[0] * fd;
      vir[1] += 0.5 * del[1] * fd;
      vir[2] += 0.5 * del[2] * fd;
      if (MOMENTS) {
        m0 += pk[m] * del[0];
        m1 += pk[m] * del[1];
        m2 += pk[m] * del[2];
      }
    }
    if (MOMENTS) {
      mom[i][0] = m0;
      mom[i][1] = m1;
      mom[i][2] = m2;
    }
  }
  wvir[0] = vir[0];
  wvir[1] = vir[1];
  wvir[2] = vir[2];
}

void PairEQElastic::skin_error(int i, int j, double du)
{
  error->one(FLERR,
             "Pair eq/elastic: the displacements of coupled blocks {} and {} differ by {:.6g}, "
             "more than half the neighbor skin {}: coupled pairs may be missing from the neighbor "
             "list; raise the skin (neighbor SKIN bin) above twice the largest difference, or, "
             "if the blocks were close a few steps ago, the integration is unstable: reduce the "
             "time step (overdamped: dt < 2 gamma/(4 g + k_c + K))",
             atom->tag[i], atom->tag[j], du, neighbor->skin);
}

void PairEQElastic::overlap_error(int i, int j)
{
  error->one(FLERR,
             "Pair eq/elastic: atoms {} and {} of {} are at the same {} (closer than 1e-10 of the "
             "cutoff, where the kernel k(r) ~ 1/r diverges): two {} at one place; check the "
             "positions (e.g. create_atoms on top of another, or change_box ... remap with fix "
             "move, which puts its atoms back at the positions it stored)",
             atom->tag[i], atom->tag[j], source_label, site_distance ? "site" : "position",
             site_distance ? "blocks" : "contacts");
}

/* ----------------------------------------------------------------------
   the positions may have moved since the last update (a new evaluation
   of the source).  Blocks: q = x - w, h over the cached pairs, computed
   with the forces in compute() (or when asked for).  Contacts: the
   source's stretches; when every coupled atom this rank holds moved by the
   same distance along dir, h, K and the virial hold (a rigid slider: no
   pair work), else the field is recomputed over the cached pairs with
   k_ij at the new distances.  Every decision that leads to communication
   depends only on what all ranks share.  count: in the report's counts
   (not for a drift check, counted as such)
------------------------------------------------------------------------- */

void PairEQElastic::follow(EQCoordinateSource *src, bool count)
{
  if (site_distance) {
    pending = 1;
    ++nfield;
    if (count) ++n_advance;
    return;
  }
  const double *qin = src->source_coordinates();
  double **x = atom->x;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int d = idir;
  const int mbit = member_bit;

  // displacements since the last update of every atom of the cached pairs
  // this rank holds (coupled, or a member that may join), along every
  // direction (motion across dir changes the k_ij of contacts); the set
  // of coupled atoms changes only with the key, a set of members (marked:
  // applied after this by change_members(), which needs the q before) or
  // a new version that is not a change set
  Spread spread;
  int changed = -1, nchanged = 0;
  for (int i = 0; i < nlocal; i++) {
    const double qi = qin[i];
    if (std::isnan(q[i])) {
      if (!std::isnan(qi)) {
        changed = i;
        ++nchanged;
      }
      if (mask[i] & mbit) spread.add(x[i], xq[i]);
      continue;
    }
    spread.add(x[i], xq[i]);
    if (FEQ_UNLIKELY(std::isnan(qi))) {
      changed = i;
      ++nchanged;
      continue;
    }
    q[i] = qi;
  }
  // the changes of a set of members are expected (all of them, none else)
  if (nchanged > 0 && !smarked.empty()) {
    if (nchanged == expected_changes(qin)) changed = -1;
    else
      for (int i = 0; i < nlocal; i++)    // name one that was not expected
        if (!smark[i] && std::isnan(q[i]) != std::isnan(qin[i])) changed = i;
  }
  if (changed >= 0 && !std::isfinite(x[changed][d]))    // a NaN stretch looks uncoupled
    error->one(FLERR, "Pair eq/elastic: position of atom {} of {} is {} (numerical instability: "
                      "check the timestep, the forces and the integrator)",
               atom->tag[changed], source_label, x[changed][d]);
  if (changed >= 0)
    error->one(FLERR, "Pair eq/elastic: atom {} of {} became {} between two neighbor list builds "
                      "without notice (internal error)", atom->tag[changed], source_label,
               std::isnan(qin[changed]) ? "uncoupled" : "coupled");
  if (ghost_version != version_seen) sync_changed();    // after breaks: the owners' new coordinates
  // only the coupled ghosts of the lists enter h (and can become partners
  // before the next list build): a box with many ghosts beyond the cutoff
  // (periodic images in a thin dimension) costs nothing per update
  for (const int i : glist) {
    spread.add(x[i], xq[i]);
    q[i] = x[i][d] - w[i];
  }
  if (spread.rigid()) {
    if (count) ++n_uniform;    // a rigid translation: h, K and the virial hold
  } else {
    if (count) ++n_nonuniform;
    rebuild(false);    // k_ij at the atoms' new distances
  }
}

// the local atoms of the marked set of members whose coordinate turned
// NaN or stopped being NaN (the changes follow() may see)
int PairEQElastic::expected_changes(const double *qin) const
{
  int n = 0;
  for (const int i : smarked)
    if (i < atom->nlocal && std::isnan(q[i]) != std::isnan(qin[i])) ++n;
  return n;
}

/* ----------------------------------------------------------------------
   blocks: h_i = sum_j k_ij (q_i - q_j) over the cached pairs (k_ij at the
   sites' distance do not change between list builds) with q = x - w; q of
   local atoms and of the ghosts of the lists follow.  A coupled pair stays
   in the neighbor list of the current positions as long as the blocks'
   displacements differ by less than the skin: checked with a margin of a
   factor 2 for the motion until the next list build.  f: the forces -h_i
   are added in the same pass (from compute())
------------------------------------------------------------------------- */

void PairEQElastic::site_field(double **f)
{
  pending = 0;
  const double *const *const x = atom->x;
  const int nlocal = atom->nlocal;
  const int d = idir;
  const int *fr = first.data();
  const int *jv = pj.data();
  const double *kv = pk.data();
  for (const int i : glist) q[i] = x[i][d] - w[i];
  const double dumax = 0.5 * neighbor->skin;
  double dubig = 0.0;
  int ibig = -1, jbig = -1;
  for (int i = 0; i < nlocal; i++) {
    const double qi = x[i][d] - w[i];    // NaN: not coupled (w = x - NaN)
    q[i] = qi;
    if (std::isnan(qi)) continue;
    double hi = 0.0;
    for (int m = fr[2 * i]; m < fr[2 * i + 1]; m++) {
      const int j = jv[m];
      const double dq = qi - (x[j][d] - w[j]);
      hi += kv[m] * dq;
      if (kv[m] != 0.0 && std::fabs(dq) > dubig) {
        dubig = std::fabs(dq);
        ibig = i;
        jbig = j;
      }
    }
    h[i] = hi;
    if (f) f[i][d] -= hi;
  }
  if (dubig > dumax) skin_error(ibig, jbig, dubig);
}

/* ----------------------------------------------------------------------
   the incremental field of this update, compared with the one computed
   from scratch (which is kept)
------------------------------------------------------------------------- */

void PairEQElastic::drift_check(EQCoordinateSource *src, const EQChangeSet *set)
{
  const int nlocal = atom->nlocal;
  update(src, set, false);    // the incremental field at the current positions
  if (pending) site_field(nullptr);
  std::vector<double> hold(h, h + nlocal), kold(ksum, ksum + nlocal);
  recompute(src);
  ++n_check;
  // the scale of h: |h| and the size of its terms, K |q| (rigidly moving
  // atoms have h ~ 0 but terms of K |q| each); K (changed incrementally
  // by changes of members) against its own size
  for (int i = 0; i < nlocal; i++) {
    if (std::isnan(q[i])) continue;
    drift_max = std::fmax(drift_max, std::fabs(hold[i] - h[i]));
    hscale_max = std::fmax(hscale_max, std::fmax(std::fabs(h[i]), ksum[i] * std::fabs(q[i])));
    kdrift_max = std::fmax(kdrift_max, std::fabs(kold[i] - ksum[i]));
    kscale_max = std::fmax(kscale_max, std::fabs(ksum[i]));
  }
}

/* ----------------------------------------------------------------------
   a change set of the source (breaks at fixed positions): h_i += K_i dq_i
   and h_j -= k_ij dq_i for all partners j, the ghosts' shares summed in dh
   and returned to their owners; the virial changes by -dq_i M_i.  The cost
   is that of the partners: local h are updated in place, and only the
   touched ghosts are sent and cleared.
------------------------------------------------------------------------- */

void PairEQElastic::scatter(const EQChangeSet &set)
{
  const int nlocal = atom->nlocal;
  if (pending) site_field(nullptr);
  const bool vir_current = vir_at == nfield;
  // local copies: the stores to h cannot alias them (kept in registers)
  double *const hv = h;
  const int *const fr = first.data();
  const int *const jv = pj.data();
  const double *const kv = pk.data();
  std::size_t bound = 0;
  for (int m = 0; m < set.n; m++) {
    const int i = set.list[m];
    bound += 1 + fr[2 * i + 1] - fr[2 * i];
  }
  // (grown, never cleared: only the first nhchanged entries are read)
  if (hchanged.size() < bound) hchanged.resize(bound);
  int *const hc = hchanged.data();
  int nc = 0;
  gtouched.clear();
  for (int m = 0; m < set.n; m++) {
    const int i = set.list[m];
    const double dq = set.dq[i];
    q[i] += dq;
    if (site_distance) w[i] -= dq;    // contacts: w of local atoms is not read
    hv[i] += ksum[i] * dq;
    hc[nc++] = i;
    const int pend = fr[2 * i + 1];
    if (rowlocal[i]) {
      for (int p = fr[2 * i]; p < pend; p++) {
        const int j = jv[p];
        hv[j] -= kv[p] * dq;
        hc[nc++] = j;
      }
    } else {
      for (int p = fr[2 * i]; p < pend; p++) {
        const int j = jv[p];
        if (j < nlocal) {
          hv[j] -= kv[p] * dq;
          hc[nc++] = j;
        } else
          ghost_share(j, -kv[p] * dq);
      }
    }
    if (vir_current) vir_pending.emplace_back(i, dq);
    sync_mark(i);
  }
  nhchanged = nc;
  comm_mode = COMM_SHARES;
  EQCompat::reverse_comm(comm, this);
  for (const int j : gtouched) {
    dh[j] = 0.0;
    tmark[j] = 0;
  }
  ++nfield;
  changed_at = nfield;
  if (vir_current) {
    vir_at = nfield;
    if (vir_pending.size() > static_cast<size_t>(nlocal)) virial_pending();
  }
  n_change += set.n;
}

// the virial's change by the scattered changes since it was computed,
// -dq_i M_i, in their order (deferred until the virial is read)
void PairEQElastic::virial_pending()
{
  for (const auto &c : vir_pending) {
    const int i = c.first;
    const double dq = c.second;
    wvir[0] -= dq * mom[i][0];
    wvir[1] -= dq * mom[i][1];
    wvir[2] -= dq * mom[i][2];
  }
  vir_pending.clear();
}

/* ----------------------------------------------------------------------
   a set of members of the source (contacts that leave the field while
   they wait to re-form, or detach for good, and contacts that re-form):
   their partners' fields change by their share only.  A leaver i takes
   k_ij from K_j and k_ij (q_j - q_i) from h_j, at its last q_i; a joiner
   gets h_i and K_i from its cached pairs and gives its partners the
   same shares back.  A partner j changes by K_j += c, h_j += c q_j - m
   (c = -k_ij, m = -k_ij q_i for a leave; +k_ij, +k_ij q_i for a join),
   so that a ghost's share needs no q_j on the rank that sends it.
   Joiners get no share from each other (each one's h is from scratch,
   with the others' new q, which reach their ghosts first).  Cost: that
   of the partners, one forward and one reverse communication; the
   moments and the virial are recomputed when next read.
------------------------------------------------------------------------- */

void PairEQElastic::change_members(EQCoordinateSource *src, const EQChangeSet &set, bool moved)
{
  const double *qin = src->source_coordinates();
  const int *const fr = first.data();
  const int *const jv = pj.data();
  const double *const kv = pk.data();
  nhchanged = 0;
  gtouched.clear();
  joined.clear();
  for (int m = 0; m < set.n; m++) mark_member(set.list[m]);
  for (int m = 0; m < set.n; m++) {    // leavers: at their q before
    const int i = set.list[m];
    const double qi = q[i];
    if (std::isnan(qi)) continue;
    // (the source's contract, eq_field.h: a member of a set joins or
    // leaves, and leaves only at fixed positions, where q_i is current)
    if (!std::isnan(qin[i])) member_error(i, "stayed in the field");
    if (moved) member_error(i, "left the field with a new evaluation");
    for (int p = fr[2 * i]; p < fr[2 * i + 1]; p++) {
      const int j = jv[p];
      if (!std::isnan(q[j])) member_share(j, -kv[p], -kv[p] * qi);
    }
    q[i] = NOT_COUPLED;
    sync_mark(i);
  }
  for (int m = 0; m < set.n; m++) {    // joiners' q, to their ghosts with the leavers'
    const int i = set.list[m];
    if (!std::isnan(q[i]) || std::isnan(qin[i])) continue;
    q[i] = qin[i];
    sync_mark(i);
    joined.push_back(i);
  }
  smark_ghosts = true;    // the ghosts that join are flagged as they arrive
  sync_changed();
  smark_ghosts = false;
  for (const int i : joined) {
    const double qi = q[i];
    double hi = 0.0, ki = 0.0;
    for (int p = fr[2 * i]; p < fr[2 * i + 1]; p++) {
      const int j = jv[p];
      if (std::isnan(q[j])) continue;
      const double k = kv[p];
      hi += k * (qi - q[j]);
      ki += k;
      if (!smark[j]) member_share(j, k, k * qi);
    }
    h[i] = hi;
    ksum[i] = ki;
    add_changed(i);
  }
  comm_mode = COMM_MEMBERS;
  EQCompat::reverse_comm(comm, this);
  for (const int j : gtouched) {
    dh[j] = dk[j] = 0.0;
    tmark[j] = 0;
  }
  for (const int i : smarked) smark[i] = 0;
  smarked.clear();
  ++nfield;
  changed_at = nfield;
  mom_valid = false;
  vir_at = -1;
  vir_pending.clear();
  n_members += set.n;
}

// a set of members that breaks the source's contract (eq_field.h)
void PairEQElastic::member_error(int i, const char *what)
{
  error->one(FLERR, "Pair eq/elastic: atom {} of {} {} in a change of members (internal error: "
                    "the field cannot follow it)", atom->tag[i], source_label, what);
}

// one partner's share of a change of members: K_j += kj, h_j += kj q_j - m
// (a local atom that is coupled), or summed for its owner (a ghost)
void PairEQElastic::member_share(int j, double kj, double m)
{
  if (j < atom->nlocal) {
    if (std::isnan(q[j])) return;
    ksum[j] += kj;
    h[j] += kj * q[j] - m;
    add_changed(j);
    return;
  }
  if (!tmark[j]) {
    tmark[j] = 1;
    gtouched.push_back(j);
    gsorted = false;
  }
  dk[j] += kj;
  dh[j] += m;
}

/* ----------------------------------------------------------------------
   what the sources read: h and K at the current positions
------------------------------------------------------------------------- */

EQFieldView PairEQElastic::field_view()
{
  refresh();
  if (pending) site_field(nullptr);
  EQFieldView v;
  v.h = h;
  v.k = ksum;
  if (changed_at == nfield) {
    v.changed = hchanged.data();
    v.nchanged = nhchanged;
  }
  return v;
}

/* ----------------------------------------------------------------------
   end of a run: what the updates were and how far the field drifted
------------------------------------------------------------------------- */

void PairEQElastic::field_report()
{
  double local[4] = {drift_max, hscale_max, kdrift_max, kscale_max}, all[4];
  MPI_Allreduce(local, all, 4, MPI_DOUBLE, MPI_MAX, world);
  bigint counts[3] = {n_change, n_nonuniform, n_members}, sums[3];
  MPI_Allreduce(counts, sums, 3, MPI_LMP_BIGINT, MPI_SUM, world);
  if (comm->me == 0 && n_update > 0) {
    std::string drift = n_check > 0
        ? fmt::format("{} drift checks: max |h_incremental - h_full| = {:.3g} (scale of h: "
                      "{:.3g}), max |K_incremental - K_full| = {:.3g} (scale of K: {:.3g})",
                      n_check, all[0], all[1], all[2], all[3])
        : (check_every > 0 ? fmt::format("no drift check (one every {} updates)", check_every)
                           : std::string("no drift check (check 0)"));
    utils::logmesg(lmp, "pair eq/elastic: {} field updates on rank 0: {} rigid translations (no "
                        "pair work), {} recomputed after list builds, {} non-uniform, {} followed the "
                        "blocks' positions{}; {} coordinate changes scattered on all ranks{}; {}\n",
                   n_update, n_uniform, n_rebuild, n_nonuniform, n_advance,
                   n_joined > 0 ? fmt::format(", {} recomputed for a new set of coupled atoms",
                                              n_joined)
                                : std::string(),
                   sums[0],
                   sums[2] > 0 ? fmt::format("; {} contacts joined or left the field, followed "
                                             "by their partners", sums[2])
                               : std::string(),
                   drift);
    if (n_check > 0 && (all[0] > 1e-9 * all[1] || all[2] > 1e-9 * all[3]))
      error->warning(FLERR, "Pair eq/elastic: the incremental field drifted by {:.3g} from the "
                            "recomputed one (scale of h {:.3g}), its K by {:.3g} (scale {:.3g}); "
                            "lower the check interval (pair_style eq/elastic rcut check N)",
                     all[0], all[1], all[2], all[3]);
  }
  n_update = n_uniform = n_rebuild = n_nonuniform = n_advance = n_change = n_check = n_joined = 0;
  n_members = 0;
  drift_max = hscale_max = kdrift_max = kscale_max = 0.0;
}

/* ----------------------------------------------------------------------
   forces -h_i along dir; energy and virial from what the field holds.
   Under pair hybrid the list is the sub-style's: the field couples the
   type pairs given to eq/elastic only.
------------------------------------------------------------------------- */

void PairEQElastic::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  EQCoordinateSource *src = live_source();
  // the contacts' stretches are those of the source's last evaluation: a
  // second force evaluation without one would see old stretches
  if (!site_distance && key_set && src->source_evaluation() == eval_computed)
    error->all(FLERR, "Pair eq/elastic: forces evaluated again without a new evaluation of {} (a "
                      "command that evaluates forces outside run, minimize or rerun is not "
                      "supported with contacts)", source_label);
  refresh();
  eval_computed = src->source_evaluation();
  // after breaks the ghosts hold their owners' coordinates of before: the
  // energy below and single() (compute pair/local) need the new ones
  if (ghost_version != version_seen) sync_changed();

  double **f = atom->f;
  const int nlocal = atom->nlocal;
  const int d = idir;
  if (pending) site_field(f);    // blocks between list builds: h and forces in one pass
  else
    for (int i = 0; i < nlocal; i++)
      if (!std::isnan(q[i])) f[i][d] -= h[i];
  if (!evflag) return;

  double **x = atom->x;
  if (eflag_atom || vflag_atom) {
    // per-atom tallies over the pairs (global ones included)
    double fv[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < nlocal; i++) {
      const double qi = q[i];
      if (std::isnan(qi)) continue;
      for (int m = first[2 * i]; m < first[2 * i + 1]; m++) {
        const int j = pj[m];
        if (std::isnan(q[j])) continue;
        const double k = pk[m], dq = qi - q[j];
        double del[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
        if (site_distance) del[d] -= dq;
        fv[d] = -k * dq;
        ev_tally_xyz_full(i, 0.5 * k * dq * dq, 0.0, fv[0], fv[1], fv[2], del[0], del[1], del[2]);
      }
    }
    return;
  }
  // E = (1/2) sum_i q_i h_i: each pair's (1/2) k (q_i - q_j)^2 once over all
  // ranks (k symmetric, ghosts carry their owners' q)
  if (eflag_global) {
    double e = 0.0;
    for (int i = 0; i < nlocal; i++)
      if (!std::isnan(q[i])) e += q[i] * h[i];
    eng_vdwl += 0.5 * e;
  }
  if (vflag_global) {
    if (vir_at != nfield) virial_now();
    else virial_pending();
    // LAMMPS' components xx yy zz xy xz yz of del_a f_b for f along dir
    if (d == 0) virial[0] += wvir[0];
    else if (d == 1) {
      virial[1] += wvir[1];
      virial[3] += wvir[0];
    } else {
      virial[2] += wvir[2];
      virial[4] += wvir[0];
      virial[5] += wvir[1];
    }
  }
}

/* ----------------------------------------------------------------------
   one pair: its energy (1/2) k_ij (q_i - q_j)^2 and its force on atom i,
   -k_ij (q_i - q_j) along the source's direction.  The force is not
   central: fforce is its component along del = x_i - x_j (fforce del is
   the central part), svector[0..2] the force on i, svector[3..5] the
   torque on i (0), svector[6] = k_ij
------------------------------------------------------------------------- */

double PairEQElastic::single(int i, int j, int itype, int jtype, double rsq,
                             double /*factor_coul*/, double factor_lj, double &fforce)
{
  fforce = 0.0;
  for (int k = 0; k < 7; k++) svector[k] = 0.0;
  if (!key_set || i >= nmax || j >= nmax) return 0.0;
  // ghosts: q = x - w (current for all ghosts after compute(); the field
  // keeps q itself current only for the ghosts of its lists)
  double **x = atom->x;
  const int nlocal = atom->nlocal;
  const double qi = i < nlocal ? q[i] : x[i][idir] - w[i];
  const double qj = j < nlocal ? q[j] : x[j][idir] - w[j];
  if (std::isnan(qi) || std::isnan(qj)) return 0.0;
  if (atom->tag[i] == atom->tag[j] || rsq > cutsq_in[itype][jtype]) return 0.0;
  const double delx[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
  double del[3] = {delx[0], delx[1], delx[2]};
  if (site_distance) del[idir] -= qi - qj;
  const double rsq_k = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
  if (rsq_k > cutsq_in[itype][jtype] || !(rsq_k > 0.0)) return 0.0;
  const double k = factor_lj * kval(itype, jtype, rsq_k, del);
  const double dq = qi - qj;
  const double fi = -k * dq;
  if (rsq > 0.0) fforce = fi * delx[idir] / rsq;
  svector[idir] = fi;
  svector[6] = k;
  return 0.5 * k * dq * dq;
}

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
  if (strcmp(str, "ftilde") == 0) return static_cast<void *>(ftilde);
  if (strcmp(str, "lambda_c") == 0) return static_cast<void *>(lambda);
  if (strcmp(str, "cut") == 0) return static_cast<void *>(cut);
  return nullptr;
}

/* ---------------------------------------------------------------------- */

// COMM_ALL: q of every atom of the swap; COMM_CHANGED: a count, then
// (index in the swap, q) of the changed ones
int PairEQElastic::pack_forward_comm(int n, int *list_, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  if (comm_mode == COMM_ALL) {
    for (int i = 0; i < n; i++) buf[i] = q[list_[i]];
    return n;
  }
  int c = 0;
  for (int i = 0; i < n; i++) {
    const int j = list_[i];
    if (!cmark[j]) continue;
    buf[1 + 2 * c] = i;
    buf[2 + 2 * c] = q[j];
    ++c;
  }
  buf[0] = c;
  return 1 + 2 * c;
}

void PairEQElastic::unpack_forward_comm(int n, int first_, double *buf)
{
  if (comm_mode == COMM_ALL) {
    for (int i = 0; i < n; i++) q[first_ + i] = buf[i];
    return;
  }
  if (n == 0) return;    // nothing was sent
  double **x = atom->x;
  const int c = static_cast<int>(buf[0]);
  for (int k = 0; k < c; k++) {
    const int g = first_ + static_cast<int>(buf[1 + 2 * k]);
    const double qg = buf[2 + 2 * k];
    if (smark_ghosts && std::isnan(q[g]) && !std::isnan(qg)) mark_member(g);    // it joins
    q[g] = qg;
    w[g] = x[g][idir] - qg;
    sync_mark(g);    // a ghost that passes it on in a later swap
  }
}

// the touched ghosts of this swap (ghosts first_ .. first_ + n): their
// count, then their index in the swap and their share
int PairEQElastic::pack_reverse_comm(int n, int first_, double *buf)
{
  if (!gsorted) {
    std::sort(gtouched.begin(), gtouched.end());
    gsorted = true;
  }
  const int width = comm_mode == COMM_MEMBERS ? 3 : 2;
  int c = 0;
  for (auto it = std::lower_bound(gtouched.begin(), gtouched.end(), first_);
       it != gtouched.end() && *it < first_ + n; ++it) {
    double *b = buf + 1 + width * c;
    b[0] = *it - first_;
    if (width == 3) {
      b[1] = dk[*it];
      b[2] = dh[*it];
    } else
      b[1] = dh[*it];
    ++c;
  }
  buf[0] = c;
  return 1 + width * c;
}

// shares into their owners (or into ghosts that pass them on in a later
// swap); n == 0: nothing was sent
void PairEQElastic::unpack_reverse_comm(int n, int *list_, double *buf)
{
  if (n == 0) return;
  const int nlocal = atom->nlocal;
  const int c = static_cast<int>(buf[0]);
  if (comm_mode == COMM_MEMBERS) {
    for (int k = 0; k < c; k++) {
      const double *b = buf + 1 + 3 * k;
      member_share(list_[static_cast<int>(b[0])], b[1], b[2]);
    }
    return;
  }
  for (int k = 0; k < c; k++) {
    const int j = list_[static_cast<int>(buf[1 + 2 * k])];
    if (j < nlocal) {
      h[j] += buf[2 + 2 * k];
      add_changed(j);
    } else
      ghost_share(j, buf[2 + 2 * k]);
  }
}

/* ----------------------------------------------------------------------
   restart: settings and every explicitly set kernel (tables included)
------------------------------------------------------------------------- */

void PairEQElastic::write_restart_settings(FILE *fp)
{
  fwrite(&cut_global, sizeof(double), 1, fp);
  fwrite(&mix_flag, sizeof(int), 1, fp);
  fwrite(&check_every, sizeof(int), 1, fp);
}

void PairEQElastic::read_restart_settings(FILE *fp)
{
  if (comm->me == 0) {
    utils::sfread(FLERR, &cut_global, sizeof(double), 1, fp, nullptr, error);
    utils::sfread(FLERR, &mix_flag, sizeof(int), 1, fp, nullptr, error);
    utils::sfread(FLERR, &check_every, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(&cut_global, 1, MPI_DOUBLE, 0, world);
  MPI_Bcast(&mix_flag, 1, MPI_INT, 0, world);
  MPI_Bcast(&check_every, 1, MPI_INT, 0, world);
}

void PairEQElastic::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (!setflag[i][j]) continue;
      const feq::Kernel &k = kernels[kidx[i][j]];
      const int kind = static_cast<int>(k.kind);
      const int n = static_cast<int>(k.r.size());
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
      kidx[i][j] = static_cast<int>(kernels.size()) - 1;
      ftilde[i][j] = k.ftilde;
      lambda[i][j] = k.lambda;
    }
}

/* ---------------------------------------------------------------------- */

double PairEQElastic::memory_usage()
{
  double bytes = Pair::memory_usage();
  bytes += 10.0 * nmax * sizeof(double);
  bytes += static_cast<double>(pj.capacity()) * sizeof(int) + pk.capacity() * sizeof(double);
  bytes += static_cast<double>(rowlocal.capacity());
  bytes += static_cast<double>(first.capacity()) * sizeof(int);
  return bytes;
}
