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
#include "group.h"
#include "memory.h"
#include "respa.h"
#include "update.h"
#include "utils.h"

#include "eq_lammps_util.h"
#include "eq_random.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
// a contact may break at most this often within one time step
constexpr int MAX_BREAKS_PER_STEP = 1000;
// sums kept per rank: friction force, breaks in step, attached, energy,
// sum of stretches, contacts, breaks since the fix was defined
enum { SUM_FORCE, SUM_BREAKS, SUM_ATTACHED, SUM_ENERGY, SUM_STRETCH, SUM_COUNT, SUM_TOTAL, NSUM };
const char *KEYWORDS = "threshold, reform, stiffness, dir, crossing, start";
}    // namespace

/* ---------------------------------------------------------------------- */

FixEQContacts::FixEQContacts(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), state(nullptr)
{
  if (narg < 5)
    error->all(FLERR,
               "Illegal fix eq/contacts command: expected 'fix ID group eq/contacts kc seed "
               "threshold <style> <values> [keyword values ...]'");
  if (!atom->tag_enable) error->all(FLERR, "Fix eq/contacts requires atom IDs (atom_modify id yes)");

  kc = utils::numeric(FLERR, arg[3], false, lmp);
  if (!(kc > 0.0)) error->all(FLERR, "Fix eq/contacts: kc must be > 0 (got {})", arg[3]);
  seed = utils::bnumeric(FLERR, arg[4], false, lmp);
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
                   "{}; stiffness {} (<k_i> = {:.6g}); crossing {}\n",
                   ncontacts, "xyz"[idir], threshold.text, threshold.dist->mean(), reform.text,
                   stiffness.text, kc * stiffness.dist->mean(), exact ? "exact" : "step");

  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 7;
  global_freq = 1;
  extscalar = 1;
  extvector = -1;
  extlist = new int[size_vector]{1, 1, 1, 1, 1, 0, 1};
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
  delete[] extlist;
}

/* ---------------------------------------------------------------------- */

int FixEQContacts::setmask()
{
  int mask = 0;
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

void FixEQContacts::setup(int vflag)
{
  mark_departed();
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
  mark_departed();
  apply(false);
}

void FixEQContacts::post_force(int /*vflag*/)
{
  apply(true);
}

void FixEQContacts::post_force_respa(int vflag, int ilevel, int /*iloop*/)
{
  if (ilevel == ilevel_respa) post_force(vflag);
}

// during minimization the contacts hold (no breaking): the energy is then
// a smooth function of the positions
void FixEQContacts::min_post_force(int /*vflag*/)
{
  apply(false);
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
  while (!(std::fabs(s) < st[THRESHOLD])) {
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
    if (!(std::fabs(s) < th) && allow_breaks) {
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
