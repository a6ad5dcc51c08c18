/* ----------------------------------------------------------------------
   FRICTION-EQ package for LAMMPS: fix eq/contacts

   Breaking / re-forming contact springs of the earthquake-like model of
   friction (Braun, Peyrard, Stryzheus, Tosatti, "Collective effects at
   frictional interfaces", Sec. II).  The physics (distributions, random
   draws) lives in the LAMMPS-free library under lib/; this fix adapts it
   to LAMMPS atoms, forces, output, exchange and restart.
------------------------------------------------------------------------- */

#include "fix_eq_contacts.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "memory.h"
#include "neighbor.h"
#include "pair_eq_elastic.h"
#include "respa.h"
#include "update.h"
#include "utils.h"

#include "eq_lammps_util.h"
#include "eq_random.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
// a contact may break at most this often within one time step
constexpr int MAX_BREAKS_PER_STEP = 1000;
// an avalanche (interacting contacts) may take at most this many rounds
constexpr int MAX_ROUNDS = 100000;
// sums kept per rank: friction force, breaks in step, attached, energy,
// sum of stretches, contacts, breaks since the fix was defined
enum { SUM_FORCE, SUM_BREAKS, SUM_ATTACHED, SUM_ENERGY, SUM_STRETCH, SUM_COUNT, SUM_TOTAL, NSUM };
const char *KEYWORDS = "threshold, reform, stiffness, dir, crossing, start, reform_as, avalanches";
}    // namespace

/* ---------------------------------------------------------------------- */

FixEQContacts::FixEQContacts(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), reform_force(1), break_tol(0.0), pair(nullptr), avfp(nullptr),
    av_flag(0), rounds_last(0), rigid_shift(0), nmax_list(0), blist(nullptr), dsv(nullptr), state(nullptr)
{
  if (narg < 5)
    error->all(FLERR,
               "Illegal fix eq/contacts command: expected 'fix ID group eq/contacts kc seed "
               "threshold <style> <values> [keyword values ...]'");
  if (!atom->tag_enable) error->all(FLERR, "Fix eq/contacts requires atom IDs (atom_modify id yes)");

  kc = EQUtil::numeric(lmp, "Fix eq/contacts: kc", arg[3]);
  if (!(kc > 0.0) || !std::isfinite(kc))
    error->all(FLERR, "Fix eq/contacts: kc must be finite and > 0 (got {})", arg[3]);
  seed = EQUtil::bnumeric(lmp, "Fix eq/contacts: seed", arg[4]);
  if (seed <= 0) error->all(FLERR, "Fix eq/contacts: seed must be a positive integer (got {})", arg[4]);

  // defaults
  idir = 0;
  exact = 1;
  start_reform = 0;
  bool have_threshold = false;
  reform.dist = feq::make_delta(0.0);
  reform.text = "delta 0";
  stiffness.dist = feq::make_delta(1.0);
  stiffness.text = "constant";

  std::string avfile;
  const std::vector<std::string> args(arg, arg + narg);
  const feq::NumberParser number = EQUtil::number_parser(lmp);
  const feq::FileLoader load = EQUtil::file_loader(lmp);

  size_t iarg = 5;
  while (iarg < args.size()) {
    const std::string &kw = args[iarg++];
    try {
      if (kw == "threshold") {
        threshold = feq::parse_distribution(feq::Role::THRESHOLD, args, iarg, number, load);
        have_threshold = true;
      } else if (kw == "reform") {
        reform = feq::parse_distribution(feq::Role::REFORM, args, iarg, number, load);
      } else if (kw == "stiffness") {
        stiffness = feq::parse_distribution(feq::Role::STIFFNESS, args, iarg, number, load);
      } else if (kw == "dir") {
        if (iarg >= args.size()) throw feq::SpecError("dir: missing value; allowed: x, y, z");
        const std::string &v = args[iarg++];
        if (v == "x") idir = 0;
        else if (v == "y") idir = 1;
        else if (v == "z") idir = 2;
        else throw feq::SpecError("dir: unknown value '" + v + "'; allowed: x, y, z");
      } else if (kw == "crossing") {
        if (iarg >= args.size())
          throw feq::SpecError("crossing: missing value; allowed: exact, step");
        const std::string &v = args[iarg++];
        if (v == "exact") exact = 1;
        else if (v == "step") exact = 0;
        else throw feq::SpecError("crossing: unknown value '" + v + "'; allowed: exact, step");
      } else if (kw == "start") {
        if (iarg >= args.size())
          throw feq::SpecError("start: missing value; allowed: relaxed, reform");
        const std::string &v = args[iarg++];
        if (v == "relaxed") start_reform = 0;
        else if (v == "reform") start_reform = 1;
        else throw feq::SpecError("start: unknown value '" + v + "'; allowed: relaxed, reform");
      } else if (kw == "reform_as") {
        if (iarg >= args.size())
          throw feq::SpecError("reform_as: missing value; allowed: stretch, force");
        const std::string &v = args[iarg++];
        if (v == "stretch") reform_force = 0;
        else if (v == "force") reform_force = 1;
        else throw feq::SpecError("reform_as: unknown value '" + v + "'; allowed: stretch, force");
      } else if (kw == "avalanches") {
        if (iarg >= args.size()) throw feq::SpecError("avalanches: missing file name");
        avfile = args[iarg++];
        av_flag = 1;
      } else {
        throw feq::SpecError("unknown keyword '" + kw + "'; allowed: " + KEYWORDS);
      }
    } catch (const feq::SpecError &e) {
      error->all(FLERR, "Fix eq/contacts {}", e.what());
    }
  }
  if (!have_threshold)
    error->all(FLERR,
               "Fix eq/contacts: the threshold keyword is required; allowed styles: {}",
               feq::role_styles(feq::Role::THRESHOLD));
  if (idir == 2 && domain->dimension == 2)
    error->all(FLERR, "Fix eq/contacts: dir z is not allowed in a 2d simulation; allowed: x, y");
  if (start_reform && !reform.dist)
    error->all(FLERR, "Fix eq/contacts: start reform needs contacts that re-form (reform none given)");
  // a contact must be able to form below its threshold
  try {
    feq::check_reform(*threshold.dist, reform);
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix eq/contacts {}", e.what());
  }
  if (group->dynamic[igroup])
    error->all(FLERR, "Fix eq/contacts: group {} is dynamic; contacts need a static group",
               group->names[igroup]);
  const bigint ncontacts = group->count(igroup);
  if (ncontacts == 0)
    error->all(FLERR, "Fix eq/contacts: group {} has no atoms", group->names[igroup]);

  reform_point = reform.dist && reform.dist->is_point();
  reform_value = reform.dist ? reform.dist->mean() : 0.0;
  stiffness_const = stiffness.text == "constant";
  // re-forming stretches are drawn from R truncated to |r| < max x_s (a
  // weight below 1e-12, checked above) so that no draw can abort a run
  reform_top = threshold.dist->effective_upper();
  if (reform.dist) {
    reform_cdf_lo = reform.dist->cdf(-reform_top);
    reform_cdf_hi = reform.dist->cdf(std::nextafter(reform_top, -reform_top));
  } else {
    reform_cdf_lo = 0.0;
    reform_cdf_hi = 1.0;
  }

  if (comm->me == 0)
    utils::logmesg(lmp,
                   "fix eq/contacts: {} contacts along {}; thresholds {} (<x_s> = {:.6g}); reform "
                   "{} (as {}); stiffness {} (<k_i> = {:.6g}); crossing {}\n",
                   ncontacts, "xyz"[idir], threshold.text, threshold.dist->mean(), reform.text,
                   reform_force ? "force" : "stretch", stiffness.text,
                   kc * stiffness.dist->mean(), exact ? "exact" : "step");
  if (av_flag && comm->me == 0) {
    avfp = fopen(avfile.c_str(), "w");
    if (!avfp)
      error->one(FLERR, "Fix eq/contacts avalanches: cannot open file {}: {}", avfile,
                 utils::getsyserror());
    fmt::print(avfp, "# fix {} eq/contacts avalanches: one line per step with breaks\n"
                     "# step size trigger rounds\n", id);
    fflush(avfp);
  }

  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 8;
  global_freq = 1;
  extscalar = 1;
  extvector = -1;
  extlist = new int[size_vector]{1, 1, 1, 1, 1, 0, 1, 0};
  peratom_flag = 1;
  size_peratom_cols = NCOL;
  peratom_freq = 1;
  energy_global_flag = 1;
  respa_level_support = 1;
  ilevel_respa = 0;
  maxexchange = NCOL;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);

  // relaxed contacts at the current positions (or stretched by R)
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    set_arrays(i);
    if (atom->mask[i] & groupbit) init_contact(i);
  }

  for (double &v : local_sum) v = 0.0;
  for (double &v : global_sum) v = 0.0;
  local_breaks_total = breaks_offset = 0;
  reduced_step = -1;
  reduced_valid = 0;
}

/* ---------------------------------------------------------------------- */

FixEQContacts::~FixEQContacts()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(state);
  memory->destroy(blist);
  memory->destroy(dsv);
  if (avfp) fclose(avfp);
  delete[] extlist;
}

/* ---------------------------------------------------------------------- */

int FixEQContacts::setmask()
{
  int mask = 0;
  mask |= PRE_FORCE;
  mask |= POST_FORCE;
  mask |= POST_FORCE_RESPA;
  mask |= MIN_POST_FORCE;
  return mask;
}

/* ---------------------------------------------------------------------- */

void FixEQContacts::init()
{
  if (utils::strmatch(update->integrate_style, "^respa")) {
    ilevel_respa = ((Respa *) update->integrate)->nlevels - 1;
    if (respa_level >= 0) ilevel_respa = MIN(respa_level, ilevel_respa);
  }
  // the interaction between contacts, when a pair style provides it
  pair = force->pair ? dynamic_cast<PairEQElastic *>(force->pair_match("^eq/elastic", 0)) : nullptr;
  if (pair && utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix eq/contacts with pair style eq/elastic does not support run_style "
                      "respa; allowed: run_style verlet");
}

/* ----------------------------------------------------------------------
   group membership can change only between runs (the fix does not allow
   dynamic groups): an atom that left the group stops being a contact and
   forms a fresh contact, relaxed where it is, if it comes back
------------------------------------------------------------------------- */

void FixEQContacts::mark_departed()
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    double *const st = state[i];
    if (!(mask[i] & groupbit) && st[THRESHOLD] > 0.0) {
      st[THRESHOLD] = 0.0;
      st[STIFFNESS] = -1.0;    // marks a re-entry for init_contact()
      st[STRETCH] = st[FORCE] = 0.0;
    }
  }
}

void FixEQContacts::setup_pre_force(int /*vflag*/)
{
  if (!pair) return;
  mark_departed();
  // contacts break during runs only, not during minimization
  interact_step(update->whichflag == 1);
}

void FixEQContacts::pre_force(int /*vflag*/)
{
  if (pair) interact_step(true);
}

void FixEQContacts::setup(int vflag)
{
  if (!pair) {
    mark_departed();
    // no interaction in this run: a field left by an earlier run with
    // pair eq/elastic would be stale (per-atom output, next_event())
    for (int i = 0; i < atom->nlocal; i++) state[i][INTERACT] = 0.0;
  }
  if (utils::strmatch(update->integrate_style, "^verlet"))
    post_force(vflag);
  else {
    ((Respa *) update->integrate)->copy_flevel_f(ilevel_respa);
    post_force_respa(vflag, ilevel_respa, 0);
    ((Respa *) update->integrate)->copy_f_flevel(ilevel_respa);
  }
}

void FixEQContacts::min_setup(int /*vflag*/)
{
  if (pair) {
    apply_interacting();
    return;
  }
  mark_departed();
  apply(false);
}

void FixEQContacts::post_force(int /*vflag*/)
{
  if (pair) {
    apply_interacting();
    return;
  }
  apply(true);
  if (av_flag) {
    // avalanches without interaction: the breaks of a step
    double nb = local_sum[SUM_BREAKS], all = nb;
    MPI_Allreduce(&nb, &all, 1, MPI_DOUBLE, MPI_SUM, world);
    rounds_last = all > 0.0 ? 1 : 0;
    if (all > 0.0) record_avalanche((bigint) all, (bigint) all, 1);
  }
}

void FixEQContacts::post_force_respa(int vflag, int ilevel, int /*iloop*/)
{
  if (ilevel == ilevel_respa) post_force(vflag);
}

// during minimization the contacts hold (no breaking): the energy is then
// a smooth function of the positions
void FixEQContacts::min_post_force(int /*vflag*/)
{
  if (pair) apply_interacting();
  else apply(false);
}

/* ----------------------------------------------------------------------
   unwrapped coordinate of atom i along the sliding direction
------------------------------------------------------------------------- */

inline double FixEQContacts::unwrapped(int i) const
{
  const imageint img = atom->image[i];
  int n;
  if (idir == 0) n = (img & IMGMASK) - IMGMAX;
  else if (idir == 1) n = (img >> IMGBITS & IMGMASK) - IMGMAX;
  else n = (img >> IMG2BITS) - IMGMAX;
  double xu = atom->x[i][idir];
  if (!domain->triclinic) return xu + n * domain->prd[idir];
  double u[3];
  domain->unmap(atom->x[i], img, u);
  return u[idir];
}

/* ----------------------------------------------------------------------
   re-forming stretch; R is truncated to |r| < max threshold, which only
   matters for draws of probability below 1e-12 (checked at definition)
------------------------------------------------------------------------- */

double FixEQContacts::draw_reform(tagint tag, bigint event, uint32_t stream)
{
  if (reform_point) return reform_value;
  const feq::Uniform u = feq::draw(seed, tag, event, stream);
  const double r = reform.dist->sample(u);
  if (std::fabs(r) < reform_top) return r;
  return reform.dist->quantile(reform_cdf_lo + u.u * (reform_cdf_hi - reform_cdf_lo));
}

/* ----------------------------------------------------------------------
   a contact forms at atom i: its first formation uses the draws of event
   0; a re-entry into the group uses the re-entry streams at its current
   break count.  The threshold is drawn above the initial stretch.
------------------------------------------------------------------------- */

void FixEQContacts::init_contact(int i)
{
  const tagint tag = atom->tag[i];
  double *s = state[i];
  const bool reentry = s[STIFFNESS] < 0.0;
  const bigint event = reentry ? (bigint) s[NBREAK] : 0;
  const uint32_t off = reentry ? feq::STREAM_REENTRY : 0;
  const double s0 = start_reform ? draw_reform(tag, event, feq::STREAM_REFORM + off) : 0.0;
  const double k = stiffness_const
      ? kc
      : kc * stiffness.dist->sample(feq::draw(seed, tag, event, feq::STREAM_STIFFNESS + off));
  const double th = threshold.dist->sample_above(
      std::fabs(s0), feq::draw(seed, tag, event, feq::STREAM_THRESHOLD + off));
  if (!(th > 0.0))
    error->one(FLERR, "Fix eq/contacts: initial stretch {} of contact {} is not below the largest "
               "breaking threshold", s0, tag);
  s[STRETCH] = s0;
  s[THRESHOLD] = th;
  s[FORCE] = k * s0;
  s[NBREAK] = (double) event;
  s[STIFFNESS] = k;
  s[ANCHOR] = unwrapped(i) - s0;
  s[INTERACT] = 0.0;
}

/* ----------------------------------------------------------------------
   break contact i (stretch s with |s| >= threshold) as often as needed.
   exact crossing: the contact broke when |s| reached the threshold, so
   the displacement beyond it (the overshoot) is carried over into the
   re-formed contact; step crossing: the contact re-forms at the end of
   the step (cellular-automaton convention).  A contact broken with
   negative stretch re-forms with the mirrored stretch -r.
   Returns the new stretch.
------------------------------------------------------------------------- */

double FixEQContacts::resolve_breaks(int i, double s)
{
  const tagint tag = atom->tag[i];
  double *st = state[i];
  // LAMMPS keeps the image count in IMGBITS bits: after IMGMAX periodic
  // crossings it wraps, and the unwrapped coordinate jumps by 2 IMGMAX box
  // lengths.  No stretch can be that large: undo the jump.
  if (!domain->triclinic && domain->periodicity[idir]) {
    const double wrap = 2.0 * IMGMAX * domain->prd[idir];
    if (std::fabs(s) > 0.5 * wrap) s -= wrap * std::round(s / wrap);
  }
  int nb = 0;
  const double tol = break_tol > 0.0 ? break_tol * (1.0 + std::fabs(st[ANCHOR]) + std::fabs(s)) : 0.0;
  while (!(std::fabs(s) < st[THRESHOLD] - tol)) {
    if (!std::isfinite(s))
      error->one(FLERR,
                 "Fix eq/contacts: stretch of contact {} is {} (numerical instability: check the "
                 "timestep, the forces and the integrator)",
                 tag, s);
    if (++nb > MAX_BREAKS_PER_STEP)
      error->one(FLERR,
                 "Fix eq/contacts: contact {} broke more than {} times in one step (stretch {}); "
                 "reduce the timestep or check the reform and threshold distributions",
                 tag, MAX_BREAKS_PER_STEP, s);
    const double sign = s > 0.0 ? 1.0 : -1.0;
    const double over = exact ? s - sign * st[THRESHOLD] : 0.0;
    const bigint event = (bigint) st[NBREAK] + 1;
    st[NBREAK] = (double) event;
    ++local_breaks_total;
    local_sum[SUM_BREAKS] += 1.0;
    if (!reform.dist) {    // never re-forms: detached for good
      st[THRESHOLD] = -1.0;
      st[STIFFNESS] = 0.0;
      return 0.0;
    }
    const double r = draw_reform(tag, event, feq::STREAM_REFORM);
    if (!stiffness_const)
      st[STIFFNESS] = kc * stiffness.dist->sample(feq::draw(seed, tag, event, feq::STREAM_STIFFNESS));
    const double th = threshold.dist->sample_above(
        std::fabs(r), feq::draw(seed, tag, event, feq::STREAM_THRESHOLD));
    if (!(th > 0.0))    // only if the survival function underflows at |r|
      error->one(FLERR,
                 "Fix eq/contacts: contact {} re-formed with stretch {}, where no breaking "
                 "threshold of {} lies above it; check the reform distribution",
                 tag, r, threshold.text);
    st[THRESHOLD] = th;
    s = sign * r + over;
  }
  return s;
}

/* ----------------------------------------------------------------------
   contact forces -k_i s_i; breaking when allowed
------------------------------------------------------------------------- */

void FixEQContacts::apply(bool allow_breaks)
{
  double *const *const x = atom->x;
  double *const *const f = atom->f;
  const int *const mask = atom->mask;
  const imageint *const image = atom->image;
  const int nlocal = atom->nlocal;
  const int d = idir;
  const int bits = (d == 0) ? 0 : (d == 1 ? IMGBITS : IMG2BITS);
  const double prd = domain->prd[d];
  const bool triclinic = domain->triclinic;

  double fsum = 0.0, esum = 0.0, ssum = 0.0, natt = 0.0, ncount = 0.0;
  local_sum[SUM_BREAKS] = 0.0;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *const st = state[i];
    ncount += 1.0;
    double th = st[THRESHOLD];
    if (th <= 0.0) {
      if (th == 0.0) {    // atom created, or added to the group, after the fix
        init_contact(i);
        th = st[THRESHOLD];
      } else {            // detached for good
        st[STRETCH] = st[FORCE] = 0.0;
        continue;
      }
    }
    // unwrapped coordinate along the sliding direction
    double xu;
    if (!triclinic) {
      const int n = int((image[i] >> bits) & IMGMASK) - IMGMAX;
      xu = x[i][d] + n * prd;
    } else {
      xu = unwrapped(i);
    }
    double s = xu - st[ANCHOR];
    // the force that decides breaking is k_i s: the stretch test is equivalent
    if (!(std::fabs(s) < th - (break_tol > 0.0 ? break_tol * (1.0 + std::fabs(st[ANCHOR]) + std::fabs(s)) : 0.0))
        && allow_breaks) {
      s = resolve_breaks(i, s);
      if (st[THRESHOLD] < 0.0) {
        st[STRETCH] = st[FORCE] = 0.0;
        continue;
      }
      st[ANCHOR] = xu - s;
    }
    const double fc = st[STIFFNESS] * s;
    st[STRETCH] = s;
    st[FORCE] = fc;
    f[i][d] -= fc;
    fsum += fc;
    esum += fc * s;
    ssum += s;
    natt += 1.0;
  }
  local_sum[SUM_FORCE] = fsum;
  local_sum[SUM_ATTACHED] = natt;
  local_sum[SUM_ENERGY] = 0.5 * esum;
  local_sum[SUM_STRETCH] = ssum;
  local_sum[SUM_COUNT] = ncount;
  local_sum[SUM_TOTAL] = (double) local_breaks_total;
  reduced_valid = 0;
}

/* ----------------------------------------------------------------------
   one reduction serves the scalar and all vector entries of a step
------------------------------------------------------------------------- */

void FixEQContacts::reduce()
{
  if (reduced_valid && reduced_step == update->ntimestep) return;
  MPI_Allreduce(local_sum, global_sum, NSUM, MPI_DOUBLE, MPI_SUM, world);
  reduced_step = update->ntimestep;
  reduced_valid = 1;
}

double FixEQContacts::compute_scalar()
{
  reduce();
  return global_sum[SUM_ENERGY];
}

double FixEQContacts::compute_vector(int n)
{
  switch (n) {
    case 0: reduce(); return global_sum[SUM_FORCE];
    case 1: reduce(); return global_sum[SUM_BREAKS];
    case 2: reduce(); return global_sum[SUM_TOTAL] + (double) breaks_offset;
    case 3: reduce(); return global_sum[SUM_ATTACHED];
    case 4: reduce(); return global_sum[SUM_ENERGY];
    case 5:
      reduce();
      return global_sum[SUM_ATTACHED] > 0.0 ? global_sum[SUM_STRETCH] / global_sum[SUM_ATTACHED]
                                            : 0.0;
    case 6: reduce(); return global_sum[SUM_COUNT];
    case 7:
      if (!pair && !av_flag) {
        reduce();
        return global_sum[SUM_BREAKS] > 0.0 ? 1.0 : 0.0;
      }
      return (double) rounds_last;
  }
  return 0.0;
}

/* ----------------------------------------------------------------------
   global restart: total breaks and the seed
------------------------------------------------------------------------- */

void FixEQContacts::write_restart(FILE *fp)
{
  bigint all = 0;
  MPI_Allreduce(&local_breaks_total, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  double list[2] = {(double) (all + breaks_offset), (double) seed};
  if (comm->me == 0) {
    int size = 2 * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 2, fp);
  }
}

void FixEQContacts::restart(char *buf)
{
  const double *list = (const double *) buf;
  breaks_offset = (bigint) list[0];
  local_breaks_total = 0;
  if ((bigint) list[1] != seed && comm->me == 0)
    error->warning(FLERR,
                   "Fix eq/contacts: seed {} differs from the restart file's seed {}; the break "
                   "sequence does not continue that of the original run",
                   seed, (bigint) list[1]);
}

/* ---------------------------------------------------------------------- */

double FixEQContacts::memory_usage()
{
  return (double) atom->nmax * NCOL * sizeof(double);
}

void FixEQContacts::grow_arrays(int nmax)
{
  memory->grow(state, nmax, NCOL, "eq/contacts:state");
  array_atom = state;
}

void FixEQContacts::copy_arrays(int i, int j, int /*delflag*/)
{
  memcpy(state[j], state[i], NCOL * sizeof(double));
}

// a new atom carries no contact until it is first seen in the group
void FixEQContacts::set_arrays(int i)
{
  for (int c = 0; c < NCOL; c++) state[i][c] = 0.0;
}

int FixEQContacts::pack_exchange(int i, double *buf)
{
  for (int c = 0; c < NCOL; c++) buf[c] = state[i][c];
  return NCOL;
}

int FixEQContacts::unpack_exchange(int nlocal, double *buf)
{
  for (int c = 0; c < NCOL; c++) state[nlocal][c] = buf[c];
  return NCOL;
}

int FixEQContacts::pack_restart(int i, double *buf)
{
  // buf[0] is the count of values, as other fixes read it
  buf[0] = NCOL + 1;
  for (int c = 0; c < NCOL; c++) buf[c + 1] = state[i][c];
  return NCOL + 1;
}

void FixEQContacts::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  for (int c = 0; c < NCOL; c++) state[nlocal][c] = extra[nlocal][m++];
}

int FixEQContacts::size_restart(int /*nlocal*/)
{
  return NCOL + 1;
}

int FixEQContacts::maxsize_restart()
{
  return NCOL + 1;
}

/* ----------------------------------------------------------------------
   access for other styles of the package (pair eq/elastic)
------------------------------------------------------------------------- */

void *FixEQContacts::extract(const char *name, int &dim)
{
  if (strcmp(name, "state") == 0) {
    dim = 2;
    return (void *) state;
  }
  if (strcmp(name, "kc") == 0) {
    dim = 0;
    return (void *) &kc;
  }
  if (strcmp(name, "dir") == 0) {
    dim = 0;
    return (void *) &idir;
  }
  return nullptr;
}

/* ======================================================================
   interacting contacts (pair eq/elastic)

   Each step: stretches from the positions, the field h_i of the pair
   style, then the avalanche: all contacts whose force k_i x_i + h_i has
   reached k_i x_si break at once (one round), the field changes by the
   scattered stretch changes, and rounds repeat until no contact is over
   its threshold anywhere (cellular-automaton update, independent of the
   decomposition).  The pair style then applies -h_i from the final state.
====================================================================== */

inline double FixEQContacts::unwrap_fix(double s) const
{
  // see resolve_breaks(): undo a wrap of the image counter
  if (!domain->triclinic && domain->periodicity[idir]) {
    const double wrap = 2.0 * IMGMAX * domain->prd[idir];
    if (std::fabs(s) > 0.5 * wrap) s -= wrap * std::round(s / wrap);
  }
  return s;
}

void FixEQContacts::update_stretches()
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *const st = state[i];
    if (st[THRESHOLD] == 0.0) init_contact(i);
    if (st[THRESHOLD] < 0.0) {
      st[STRETCH] = st[FORCE] = st[INTERACT] = 0.0;
      continue;
    }
    st[STRETCH] = unwrap_fix(unwrapped(i) - st[ANCHOR]);
  }
}

void FixEQContacts::interact_step(bool allow_breaks)
{
  update_stretches();
  // a rigid translation leaves h (and the local order of atoms, unless
  // they were re-neighbored) unchanged: the field of the last step holds
  if (!(rigid_shift && neighbor->ago > 0 && update->setupflag == 0)) pair->field();
  rigid_shift = 0;
  local_sum[SUM_BREAKS] = 0.0;
  rounds_last = 0;
  if (allow_breaks) cascade();
  pair->set_fresh();
}

/* ----------------------------------------------------------------------
   one break of contact i whose effective stretch e = x_i + h_i/k_i has
   reached its threshold.  exact crossing carries the overshoot e - x_s
   into the new contact: the load that took the contact past its
   threshold (the slider's advance, or in a later avalanche round the
   field jump from partners that broke) is continuous, the contact breaks
   where it reaches x_s and the rest of the load goes on to the new
   contact; its force drops by exactly k_i (x_s - r) (Abelian cascade).
   step crossing carries nothing.  reform_as stretch: the new spring has
   stretch r (+ carry); force: the new contact carries force k_i r (+ carry),
   the interaction with its partners included.  Returns the new stretch.
------------------------------------------------------------------------- */

double FixEQContacts::break_once(int i, double e)
{
  const tagint tag = atom->tag[i];
  double *const st = state[i];
  if (!std::isfinite(e))
    error->one(FLERR,
               "Fix eq/contacts: force of contact {} is {} (numerical instability: check the "
               "timestep, the forces, the integrator and the pair eq/elastic coefficients{})",
               tag, e * st[STIFFNESS],
               reform_force ? ""
                            : "; with reform_as stretch a re-formed contact can carry its "
                              "partners' force beyond its threshold and break without end: use "
                              "reform_as force or a smaller ftilde");
  const double sign = e > 0.0 ? 1.0 : -1.0;
  const double over = exact ? e - sign * st[THRESHOLD] : 0.0;
  const double s_old = st[STRETCH];
  const double h_old = st[INTERACT];
  const bigint event = (bigint) st[NBREAK] + 1;
  st[NBREAK] = (double) event;
  ++local_breaks_total;
  local_sum[SUM_BREAKS] += 1.0;
  if (!reform.dist) {    // never re-forms: detached for good
    st[THRESHOLD] = -1.0;
    st[STIFFNESS] = 0.0;
    st[STRETCH] = st[FORCE] = st[INTERACT] = 0.0;
    return 0.0;
  }
  const double r = draw_reform(tag, event, feq::STREAM_REFORM);
  if (!stiffness_const)
    st[STIFFNESS] = kc * stiffness.dist->sample(feq::draw(seed, tag, event, feq::STREAM_STIFFNESS));
  const double th = threshold.dist->sample_above(
      std::fabs(r), feq::draw(seed, tag, event, feq::STREAM_THRESHOLD));
  if (!(th > 0.0))
    error->one(FLERR,
               "Fix eq/contacts: contact {} re-formed with stretch {}, where no breaking "
               "threshold of {} lies above it; check the reform distribution",
               tag, r, threshold.text);
  st[THRESHOLD] = th;
  const double target = sign * r + over;    // new force / k_i
  double s_new = target;
  if (reform_force) {
    const double ksum = pair->coupling(i);
    const double k = st[STIFFNESS];
    const double m = s_old * ksum - h_old;    // sum_j k_ij x_j
    s_new = (k * target + m) / (k + ksum);
  }
  st[STRETCH] = s_new;
  st[ANCHOR] += s_old - s_new;
  return s_new;
}

void FixEQContacts::cascade()
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  if (nlocal > nmax_list) {
    nmax_list = atom->nmax;
    memory->destroy(blist);
    memory->destroy(dsv);
    memory->create(blist, nmax_list, "eq/contacts:blist");
    memory->create(dsv, nmax_list, "eq/contacts:dsv");
  }
  bigint size = 0, trigger = 0;
  int rounds = 0;
  while (true) {
    // all contacts over their thresholds at the start of the round
    int nb = 0;
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      const double *st = state[i];
      const double th = st[THRESHOLD];
      if (th <= 0.0) continue;
      const double e = st[STRETCH] + st[INTERACT] / st[STIFFNESS];
      const double tol =
          break_tol > 0.0 ? break_tol * (1.0 + std::fabs(st[ANCHOR]) + std::fabs(st[STRETCH])) : 0.0;
      if (!(std::fabs(e) < th - tol)) blist[nb++] = i;
    }
    bigint all = nb;
    if (comm->nprocs > 1) {
      bigint mine = nb;
      MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    }
    if (all == 0) break;
    if (++rounds > MAX_ROUNDS)
      error->all(FLERR,
                 "Fix eq/contacts: avalanche did not stop after {} rounds ({} breaks); the "
                 "interaction is too strong for the contacts (check the pair eq/elastic "
                 "coefficients against k_i{})", MAX_ROUNDS, size,
                 reform_force ? "" : "; with reform_as stretch use reform_as force or a smaller ftilde");
    if (rounds == 1) trigger = all;
    size += all;
    for (int m = 0; m < nb; m++) {
      const int i = blist[m];
      const double *st = state[i];
      const double e = st[STRETCH] + st[INTERACT] / st[STIFFNESS];
      const double s_old = st[STRETCH];
      dsv[i] = break_once(i, e) - s_old;
    }
    if (!reform.dist) pair->field();    // detached contacts leave the interaction
    else pair->scatter(blist, nb, dsv);
  }
  rounds_last = rounds;
  if (size > 0 && av_flag) record_avalanche(size, trigger, rounds);
}

void FixEQContacts::record_avalanche(bigint size, bigint trigger, int rounds)
{
  if (!avfp) return;
  fmt::print(avfp, "{} {} {} {}\n", update->ntimestep, size, trigger, rounds);
}

/* ----------------------------------------------------------------------
   spring forces -k_i x_i of the current state (interacting path: the
   stretches were set in pre_force, or by the pair style's own update)
------------------------------------------------------------------------- */

void FixEQContacts::apply_interacting()
{
  double *const *const f = atom->f;
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int d = idir;
  double fsum = 0.0, esum = 0.0, ssum = 0.0, natt = 0.0, ncount = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *const st = state[i];
    ncount += 1.0;
    if (st[THRESHOLD] <= 0.0) continue;
    const double s = st[STRETCH];
    const double fc = st[STIFFNESS] * s;
    st[FORCE] = fc;
    f[i][d] -= fc;
    fsum += fc;
    esum += fc * s;
    ssum += s;
    natt += 1.0;
  }
  local_sum[SUM_FORCE] = fsum;
  local_sum[SUM_ATTACHED] = natt;
  local_sum[SUM_ENERGY] = 0.5 * esum;
  local_sum[SUM_STRETCH] = ssum;
  local_sum[SUM_COUNT] = ncount;
  local_sum[SUM_TOTAL] = (double) local_breaks_total;
  reduced_valid = 0;
}

/* ----------------------------------------------------------------------
   distance the slider (moving along +dir) has to advance until the first
   contact reaches its threshold: x_si - (x_i + h_i/k_i), minimum over all
   contacts and ranks.  A uniform advance leaves h_i unchanged.
------------------------------------------------------------------------- */

double FixEQContacts::next_event()
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  double dmin = std::numeric_limits<double>::infinity();
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double *st = state[i];
    if (st[THRESHOLD] <= 0.0) continue;
    const double e = st[STRETCH] + st[INTERACT] / st[STIFFNESS];
    const double d = st[THRESHOLD] - e;
    if (d < dmin) dmin = d;
  }
  double all = dmin;
  MPI_Allreduce(&dmin, &all, 1, MPI_DOUBLE, MPI_MIN, world);
  return all > 0.0 ? all : 0.0;
}
