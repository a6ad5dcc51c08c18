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
   FRICTION-EQ package for LAMMPS: fix eq/contacts

   Breaking / re-forming contact springs of the earthquake-like model of
   friction (Braun, Peyrard, Stryzheus, Tosatti, "Collective effects at
   frictional interfaces", Secs. II and IV).  The physics (distributions,
   random draws, the break engine) lives in the LAMMPS-free library under
   lib/; this fix adapts it to LAMMPS atoms, forces, output, exchange and
   restart.  With pair eq/elastic the contacts' stretches are the
   coordinates of its elastic field (eq_field.h): this fix drives every
   step (stretches, field update, avalanche) before the pair style
   applies the field's forces.
------------------------------------------------------------------------- */

#include "fix_eq_contacts.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "modify.h"
#include "neighbor.h"
#include "pair.h"
#include "respa.h"
#include "update.h"
#include "utils.h"

#include "eq_cite.h"
#include "eq_contact.h"
#include "eq_keywords.h"
#include "eq_lammps_util.h"
#include "eq_link.h"
#include "eq_record_lammps.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;
using namespace feq;

namespace {
// sums kept per rank: friction force, breaks in step, attached, energy,
// sum of stretches, contacts, breaks since the fix was defined
enum { SUM_FORCE, SUM_BREAKS, SUM_ATTACHED, SUM_ENERGY, SUM_STRETCH, SUM_COUNT, SUM_TOTAL, NSUM };
const char *KEYWORDS = "threshold, reform, stiffness, dir, crossing, start, reform_as, avalanches, "
                       "peratom, thermal, barrier, aging, delay, rest";

// the columns of a compact row (keyword peratom N > 1): what the common
// thermal step reads and writes.  LIMIT: the common step holds while
// |s| < LIMIT and the step ends before RUNOUT (ContactModel::stored_quick()
// in one test, load_hot()).  A contact that waits to re-form has LIMIT
// HOT_WAITING and its delay left (CT_WAIT) in RUNOUT, and the step of one
// whose delay goes on (ContactModel::quick_wait()) is made on the compact
// row too: its anchor follows its atom and its delay shortens there
enum HotColumn : int { H_ANCHOR, H_STIFFNESS, H_LIMIT, H_RUNOUT, H_STRETCH, H_FORCE, H_NCOL };
constexpr double HOT_WAITING = -2.0;    // (any other contact not attached: -1)

// the sums of a contact loop (scan(), scan_thermal(), scan_hot()), a local
// of the loop that the compiler keeps in registers
struct LoopSums {
  double f = 0.0, e = 0.0, s = 0.0, natt = 0.0, ncount;
  explicit LoopSums(double n) : ncount(n) {}
  // an attached contact with stretch s_ and force fc: the force on its
  // atom (fdi: the atom's force component along dir) and its terms
  void add(double *fdi, double fc, double s_)
  {
    *fdi -= fc;
    f += fc;
    e += fc * s_;
    s += s_;
    natt += 1.0;
  }
};
constexpr double NOT_A_CONTACT = std::numeric_limits<double>::quiet_NaN();
// the bit of group all (Group: group 0; set in the mask of every atom
// LAMMPS creates, cleared only by commands such as group all subtract)
constexpr int ALL_GROUPBIT = 1;
}    // namespace

/* ----------------------------------------------------------------------
   what the avalanche of lib/eq_contact needs: MPI, the field, atom IDs
------------------------------------------------------------------------- */

class FixEQContacts::Hooks : public AvalancheHooks {
 public:
  Hooks(FixEQContacts *f, EQElasticField *fld) : fix(f), elastic(fld), tags(f->atom->tag) {}
  void global_sum(long *v, int n) override
  {
    if (fix->comm->nprocs > 1) MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_LONG, MPI_SUM, fix->world);
  }
  AvalancheField field() override { return pull(); }
  // the fix records the change set; the field pulls it when asked for h
  AvalancheField changed(const int *list, int n, const double *ds, bool exact) override
  {
    fix->record_changes(list, n, ds, exact);
    return pull();
  }
  // contacts detached for good or waiting: the field without them, at
  // fixed positions
  AvalancheField detached(const int *list, int n, bool exact) override
  {
    fix->record_members(list, n, exact);
    return pull();
  }
  uint64_t tag(int i) const override { return static_cast<uint64_t>(tags[i]); }
  const EQFieldView &last_view() const { return view; }

 private:
  FixEQContacts *fix;
  EQElasticField *elastic;
  EQFieldView view;
  const tagint *tags;

  AvalancheField pull()
  {
    view = elastic->field_view();
    AvalancheField f;
    f.h = view.h;
    f.k = view.k;
    f.changed = view.changed;
    f.nchanged = view.nchanged;
    return f;
  }
};

/* ---------------------------------------------------------------------- */

// what the command says
struct FixEQContacts::Args {
  double kc = 0.0;
  bool exact = true, start_reform = false, reform_force = true;
  bool have_threshold = false;
  feq::DistributionSpec threshold, reform, stiffness;
  feq::ThermalKeywords thermal;
  std::string avfile;
  int peratom_every = 1;
};

FixEQContacts::FixEQContacts(LAMMPS *lmp, int narg, char **arg) :
    FixEQPerAtom(lmp, narg, arg), break_tol(0.0), interacting(0), avfp(nullptr), av_flag(0),
    rounds_last(0), ran(0), in_setup(0), masks_full(0), mask_writer(0), masks_builds(-1),
    nevaluation(0), nversion(0), chg_from(-1), clock(0.0), peratom_every(1), hot_live(0),
    hot_T(false)
{
  EQCite::add(lmp);
  name = fmt::format("fix {} eq/contacts", id);
  Args a;
  parse(narg, arg, a);
  const bigint ncontacts = check(a);
  make_model(a);
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "fix eq/contacts: {} contacts along {}; thresholds {} (<x_s> = {:.6g}); reform "
                   "{} (as {}); stiffness {} (<k_i> = {:.6g}); crossing {}\n",
                   ncontacts, "xyz"[idir], a.threshold.text, a.threshold.dist->mean(),
                   a.reform.text, a.reform_force ? "force" : "stretch", a.stiffness.text,
                   a.kc * a.stiffness.dist->mean(), a.exact ? "exact" : "step");
  if (model->thermal_active() && comm->me == 0)
    utils::logmesg(lmp, "fix eq/contacts: {} (theta = k_B T/eps_a = {:.6g})\n", a.thermal.text(),
                   model->thermal_model().params().theta);
  if (av_flag) open_avalanches(a.avfile);

  restart_global = 1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 9;
  global_freq = 1;
  extscalar = 1;
  extvector = -1;
  extlist = new int[size_vector]{1, 1, 1, 1, 1, 0, 1, 0, 0};
  energy_global_flag = 1;
  respa_level_support = 1;
  ilevel_respa = 0;
  respa_run = 0;
  peratom_every = a.peratom_every;
  hot_T = model->thermal_model().params().thermal();
  if (peratom_every > 1 && !model->thermal_active())
    error->all(FLERR, "Fix {} eq/contacts: peratom {} needs thermal rows (keywords {}): the row of "
                      "athermal contacts is the compact one already; use peratom 1", id,
               peratom_every, THERMAL_KEYWORDS);
  peratom_setup(model->columns(), model->outputs());
  peratom_freq = peratom_every;

  // relaxed contacts at the current positions (or stretched by R), with
  // their stretches as every evaluation at these positions finds them (x -
  // anchor), so that a run 0 changes no output read before it
  const int nlocal = atom->nlocal;
  EQUtil::Unwrap unwrap(atom, domain, idir);
  for (int i = 0; i < nlocal; i++)
    if (atom->mask[i] & groupbit) {
      double *st = state[i];
      try {
        model->form(st, static_cast<uint64_t>(atom->tag[i]), unwrap(i));
      } catch (const BreakError &e) {
        error->one(FLERR, "Fix eq/contacts: {}", e.what());
      }
      st[CS_STRETCH] = unwrap.stretch(unwrap(i) - st[CS_ANCHOR]);
      if (model->thermal_active()) {
        st[CT_AGE] = model->thermal_model().params().rest;
        feq::from_engine(st, clock);
      }
    }

  for (double &v : local_sum) v = 0.0;
  for (double &v : global_sum) v = 0.0;
  local_breaks_total = breaks_offset = 0;
  reduced_step = -1;
  reduced_valid = 0;
  // the outputs before the first run: those of the contacts just formed
  tally(nullptr);
}

// kc seed, then the keywords (messages name the keyword and the allowed values)
void FixEQContacts::parse(int narg, char **arg, Args &a)
{
  if (narg < 5)
    error->all(FLERR,
               "Illegal fix eq/contacts command: expected 'fix ID group eq/contacts kc seed "
               "threshold <style> <values> [keyword values ...]'");
  if (!atom->tag_enable) error->all(FLERR, "Fix eq/contacts requires atom IDs (atom_modify id yes)");
  a.kc = EQUtil::numeric(lmp, "Fix eq/contacts: kc", arg[3]);
  if (!(a.kc > 0.0) || !std::isfinite(a.kc))
    error->all(FLERR, "Fix eq/contacts: kc must be finite and > 0 (got {})", arg[3]);
  seed = EQUtil::bnumeric(lmp, "Fix eq/contacts: seed", arg[4]);
  if (seed <= 0) error->all(FLERR, "Fix eq/contacts: seed must be a positive integer (got {})", arg[4]);

  idir = 0;
  a.reform.dist = feq::make_delta(0.0);
  a.reform.text = "delta 0";
  a.stiffness.dist = feq::make_delta(1.0);
  a.stiffness.text = "constant";
  const std::vector<std::string> args(arg, arg + narg);
  const feq::NumberParser number = EQUtil::number_parser(lmp);
  const feq::FileLoader load = EQUtil::file_loader(lmp);
  size_t iarg = 5;
  while (iarg < args.size()) {
    const std::string &kw = args[iarg++];
    try {
      if (kw == "threshold") {
        a.threshold = feq::parse_distribution(feq::Role::THRESHOLD, args, iarg, number, load);
        a.have_threshold = true;
      } else if (kw == "reform") {
        a.reform = feq::parse_distribution(feq::Role::REFORM, args, iarg, number, load);
      } else if (kw == "stiffness") {
        a.stiffness = feq::parse_distribution(feq::Role::STIFFNESS, args, iarg, number, load);
      } else if (kw == "dir") {
        idir = feq::parse_dir(args, iarg);
      } else if (kw == "crossing") {
        a.exact = feq::parse_choice(args, iarg, kw, {"exact", "step"}) == 0;
      } else if (kw == "start") {
        a.start_reform = feq::parse_choice(args, iarg, kw, {"relaxed", "reform"}) == 1;
      } else if (kw == "reform_as") {
        a.reform_force = feq::parse_choice(args, iarg, kw, {"stretch", "force"}) == 1;
      } else if (feq::parse_thermal_keyword(kw, args, iarg, number, a.thermal)) {
        // temperature, aging, delays (lib/eq_thermal)
      } else if (kw == "avalanches") {
        if (iarg >= args.size()) throw feq::SpecError("avalanches: missing file name");
        a.avfile = args[iarg++];
        av_flag = 1;
      } else if (kw == "peratom") {
        if (iarg >= args.size()) throw feq::SpecError("peratom: missing N (steps)");
        const bigint n = EQUtil::bnumeric(lmp, "Fix eq/contacts: peratom", args[iarg++]);
        if (n < 1 || n > MAXSMALLINT)
          throw feq::SpecError("peratom: N must be an integer from 1 to " +
                               std::to_string(MAXSMALLINT) + " (got " + args[iarg - 1] + ")");
        a.peratom_every = static_cast<int>(n);
      } else {
        throw feq::SpecError("unknown keyword '" + kw + "'; allowed: " + KEYWORDS);
      }
    } catch (const feq::SpecError &e) {
      error->all(FLERR, "Fix eq/contacts {}", e.what());
    }
  }
}

// what the arguments must satisfy together; returns the number of contacts
bigint FixEQContacts::check(const Args &a)
{
  if (!a.have_threshold)
    error->all(FLERR,
               "Fix eq/contacts: the threshold keyword is required; allowed styles: {}",
               feq::role_styles(feq::Role::THRESHOLD));
  if (idir == 2 && domain->dimension == 2)
    error->all(FLERR, "Fix eq/contacts: dir z is not allowed in a 2d simulation; allowed: x, y");
  if (a.start_reform && !a.reform.dist)
    error->all(FLERR, "Fix eq/contacts: start reform needs contacts that re-form (reform none given)");
  // a contact must be able to form below its threshold
  try {
    feq::check_reform(*a.threshold.dist, a.reform);
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix eq/contacts {}", e.what());
  }
  if (group->dynamic[igroup])
    error->all(FLERR, "Fix eq/contacts: group {} is dynamic; contacts need a static group",
               group->names[igroup]);
  const bigint ncontacts = group->count(igroup);
  if (ncontacts == 0)
    error->all(FLERR, "Fix eq/contacts: group {} has no atoms", group->names[igroup]);
  // the largest contact force k x_s and energy k x_s^2/2 must be finite
  const double kmax = a.kc * a.stiffness.dist->effective_upper();
  const double xmax = a.threshold.dist->effective_upper();
  constexpr double EMAX = 1e300;
  if (!(kmax * xmax <= EMAX) || !(0.5 * kmax * xmax * xmax <= EMAX))
    error->all(FLERR, "Fix eq/contacts: kc = {} with stiffness {} (k up to {:.6g}) and "
                      "threshold {} (x_s up to {:.6g}) would overflow the contacts' forces or "
                      "energies (k x_s and k x_s^2/2 must stay <= {:g}): lower kc, the "
                      "stiffness or the thresholds", a.kc, a.stiffness.text, kmax,
               a.threshold.text, xmax, EMAX);
  return ncontacts;
}

// the break engine, and what the stored contacts are made with (restart check)
void FixEQContacts::make_model(const Args &a)
{
  try {
    const ThermalSpec thermal = a.thermal.finish(force->boltz, a.threshold.dist->mean());
    model.reset(new ContactModel(a.kc, static_cast<uint64_t>(seed), a.threshold, a.reform,
                                 a.stiffness, a.exact, a.reform_force, a.start_reform, thermal));
  } catch (const feq::SpecError &e) {
    error->all(FLERR, "Fix eq/contacts {}", e.what());
  }
  shaping.add("kc", EQRecord::number(a.kc));
  shaping.add("threshold", EQRecord::distribution(a.threshold));
  shaping.add("reform", EQRecord::distribution(a.reform));
  shaping.add("stiffness", EQRecord::distribution(a.stiffness));
  shaping.add("dir", std::string(1, "xyz"[idir]));
}

void FixEQContacts::open_avalanches(const std::string &file)
{
  if (comm->me != 0) return;
  avfp = fopen(file.c_str(), "w");
  if (!avfp)
    error->one(FLERR, "Fix eq/contacts avalanches: cannot open file {}: {}", file,
               utils::getsyserror());
  fmt::print(avfp, "# fix {} eq/contacts avalanches: one line per step with breaks\n"
                   "# step size trigger rounds\n", id);
  fflush(avfp);
}

/* ---------------------------------------------------------------------- */

FixEQContacts::~FixEQContacts()
{
  if (avfp) fclose(avfp);
  delete[] extlist;
}

/* ---------------------------------------------------------------------- */

int FixEQContacts::setmask()
{
  int mask = 0;
  mask |= PRE_FORCE;
  mask |= MIN_PRE_FORCE;
  mask |= POST_FORCE;
  mask |= POST_FORCE_RESPA;
  mask |= MIN_POST_FORCE;
  mask |= POST_RUN;
  return mask;
}

/* ---------------------------------------------------------------------- */

void FixEQContacts::init()
{
  end_hot();    // (a run that ended in an error had no post_run())
  respa_run = utils::strmatch(update->integrate_style, "^respa") ? 1 : 0;
  if (respa_run) {
    ilevel_respa = static_cast<Respa *>(update->integrate)->nlevels - 1;
    if (respa_level >= 0) ilevel_respa = MIN(respa_level, ilevel_respa);
  }
  // the interaction between contacts: the pair style eq/elastic that is
  // their field this run (its init_style() ran before and found its
  // source); with pair_modify compute no it is not used
  field.clear();
  int count = 0;
  Pair *pair = EQLink::elastic_pair(force, count);
  auto *elastic = pair ? dynamic_cast<EQElasticField *>(pair) : nullptr;
  if (elastic && count == 1 && pair->compute_flag && elastic->field_source_instance() == instance_me)
    field.set(elastic, pair);
  interacting = field ? 1 : 0;
  if (field && peratom_every > 1)
    error->all(FLERR, "Fix {} eq/contacts: peratom {} does not work with pair style eq/elastic "
                      "(its avalanches read the state rows at every step); use peratom 1", id,
               peratom_every);
  if (field && utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix eq/contacts with pair style eq/elastic does not support run_style "
                      "respa; allowed: run_style verlet");
  // fixes that rewrite atoms' masks within a step (insertions and
  // exclusions of the MC package, pair srp's bond particles (fix SRP), fix
  // bond/react's new atoms): the loops then read every mask
  mask_writer = 0;
  for (int i = 0; i < modify->nfix; i++)
    for (const char *writer : {"^gcmc", "^gemc", "^charge/regulation", "^SRP", "^bond/react"})
      if (utils::strmatch(modify->fix[i]->style, writer)) mask_writer = 1;
  // thermal rows keep times on the clock, which runs forward only
  if (model->thermal_active() && (update->dt < 0.0 || clock < 0.0))
    error->all(FLERR, "Fix {} eq/contacts: the keywords {} need time to run forward: timestep {} "
                      "(the fix's clock {}); use a positive timestep", id, THERMAL_KEYWORDS,
               update->dt, clock);
  // the tolerance of the breaking test: that of a driver that lands the
  // slider exactly on the next break (fix eq/quasistatic), else none
  break_tol = 0.0;
  for (int i = 0; i < modify->nfix; i++) {
    auto *driver = dynamic_cast<EQEventDriver *>(modify->fix[i]);
    if (driver && strcmp(driver->driver_target(), id) == 0) {
      break_tol = std::max(break_tol, driver->driver_tolerance());
      if (model->thermal_active())
        error->all(FLERR, "Fix {} eq/contacts: the keywords {} need time, and fix {} moves the "
                          "slider from break to break without it: drive the slider with an "
                          "integrator (fix move, fix nve) instead", id, THERMAL_KEYWORDS,
                   modify->fix[i]->id);
    }
  }
}

// formed, and not waiting to re-form (temperature, aging or delays).
// (inline: called per contact and step by the loops of this file; a
// function of a shared library that is not could be interposed, and
// every call would go through the PLT)
inline bool FixEQContacts::attached(const double *st) const
{
  return st[CS_THRESHOLD] > 0.0 && !model->waiting(st);
}

// the field of this run, if it is still the one found at init
EQElasticField *FixEQContacts::field_now()
{
  EQElasticField *f = EQLink::live_pair(field, force);
  if (!f)
    error->all(FLERR, "Fix {} eq/contacts: pair style eq/elastic, the field of its contacts at the "
                      "start of the run, was removed or replaced during the run (e.g. pair_style in "
                      "run N pre no every M); the contacts cannot go on without it: use pre yes",
               id);
  return f;
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
    if (mask[i] & groupbit) continue;
    double *st = state[i];
    if (model->thermal_active())
      feq::engine_call(st, clock, clock, [&] { model->depart(st); });
    else
      model->depart(st);
  }
}

// whether every local atom carries group all's bit (LAMMPS can clear it:
// group all subtract all G); atoms arrive and are created only at a
// neighbor build, so the answer holds until the next one
void FixEQContacts::check_masks()
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  int full = 1;
  for (int i = 0; i < nlocal && full; i++) full = mask[i] & ALL_GROUPBIT;
  masks_full = full ? 1 : 0;
  masks_builds = neighbor->ncalls;
}

// the loops may skip the masks (see masks_full)
bool FixEQContacts::masks_skippable()
{
  if (groupbit != ALL_GROUPBIT || mask_writer) return false;
  if (masks_builds != neighbor->ncalls) check_masks();
  return masks_full != 0;
}

void FixEQContacts::setup_pre_force(int /*vflag*/)
{
  ++nevaluation;
  if (!field) return;
  mark_departed();
  // contacts break during runs only, not during minimization
  field_step(update->whichflag == 1, 0.0);
}

void FixEQContacts::pre_force(int /*vflag*/)
{
  ++nevaluation;
  if (field) field_step(true, update->dt);
}

void FixEQContacts::min_pre_force(int /*vflag*/)
{
  ++nevaluation;
  if (field) field_step(false, 0.0);
}

void FixEQContacts::setup(int vflag)
{
  ran = 1;
  end_hot();
  if (!field) {
    mark_departed();
    // no interaction in this run: a field left by an earlier run with
    // pair eq/elastic would be stale (per-atom output, next_event())
    for (int i = 0; i < atom->nlocal; i++) state[i][CS_FIELD] = 0.0;
  }
  in_setup = 1;    // no time passes in the set-up of a run
  if (utils::strmatch(update->integrate_style, "^verlet"))
    post_force(vflag);
  else {
    static_cast<Respa *>(update->integrate)->copy_flevel_f(ilevel_respa);
    post_force_respa(vflag, ilevel_respa, 0);
    static_cast<Respa *>(update->integrate)->copy_f_flevel(ilevel_respa);
  }
  in_setup = 0;
}

void FixEQContacts::min_setup(int /*vflag*/)
{
  ran = 1;
  end_hot();
  if (field) {
    apply_forces();
    return;
  }
  mark_departed();
  apply(false);
}

void FixEQContacts::post_force(int /*vflag*/)
{
  if (field) {
    apply_forces();
    return;
  }
  apply(true);
  if (av_flag) {
    // avalanches without interaction: the breaks of a step
    double nb = local_sum[SUM_BREAKS], all = nb;
    MPI_Allreduce(&nb, &all, 1, MPI_DOUBLE, MPI_SUM, world);
    rounds_last = all > 0.0 ? 1 : 0;
    if (all > 0.0) record_avalanche(static_cast<bigint>(all), static_cast<bigint>(all), 1);
  }
}

void FixEQContacts::post_force_respa(int vflag, int ilevel, int /*iloop*/)
{
  if (ilevel == ilevel_respa) post_force(vflag);
}

// the duration of a step of this fix's force evaluations (its r-RESPA
// level: the time between two of them; fix_modify respa with an inner
// level evaluates loop times per outer step, each dt/loop long)
double FixEQContacts::step_dt() const
{
  if (respa_run) return static_cast<Respa *>(update->integrate)->step[ilevel_respa];
  return update->dt;
}

// during minimization the contacts hold (no breaking): the energy is then
// a smooth function of the positions
void FixEQContacts::min_post_force(int /*vflag*/)
{
  if (field) apply_forces();
  else apply(false);
}

// the field reports on its run (or on this part of it: run N every M).
// The link stays for the parts of a run that follow without a new init()
// (pre no); it is checked before each use and found afresh in init()
void FixEQContacts::post_run()
{
  // the masks are checked anew at the next run's first evaluation (group
  // all subtract may come in between; a run with pre no has no set-up)
  masks_builds = -1;
  if (EQElasticField *f = EQLink::live_pair(field, force)) f->field_report();
  end_hot();
}

/* ----------------------------------------------------------------------
   contact forces -k_i s_i and the sums of the output; breaking (without
   interaction: each contact on its own) when allowed.  One pass in index
   order; one test picks the common step, and a contact that forms,
   breaks or needs the unwrap's correction goes out of line (settle_scan(),
   settle_thermal_scan()); the rest of the loop makes no call and reads
   everything by offset from local copies that no store to the rows can
   alias, so that its sums and pointers stay in registers; on group all
   it reads no masks (issue 24: 8.0 -> 5.2 -> 4.3 -> 2.7 ns per
   contact-step, the same numbers to the last bit)
------------------------------------------------------------------------- */

void FixEQContacts::apply(bool allow_breaks)
{
  const EQUtil::Unwrap unwrap(atom, domain, idir);
  long nb = 0;
  const double dt = in_setup || !allow_breaks ? 0.0 : step_dt();
  try {
    const bool hot = model->thermal_model().params().thermal();
    const bool orthogonal = unwrap.orthogonal();
    const bool all = orthogonal && masks_skippable();
    if (peratom_every > 1) make_hot_live();
    if (hot_live && all)
      nb = scan_hot<true, true>(unwrap, allow_breaks, dt);
    else if (hot_live)
      nb = orthogonal ? scan_hot<true, false>(unwrap, allow_breaks, dt)
                      : scan_hot<false, false>(unwrap, allow_breaks, dt);
    else if (model->thermal_active() && all)
      nb = hot ? scan_thermal<true, true, true>(unwrap, allow_breaks, dt)
               : scan_thermal<true, false, true>(unwrap, allow_breaks, dt);
    else if (model->thermal_active() && orthogonal)
      nb = hot ? scan_thermal<true, true, false>(unwrap, allow_breaks, dt)
               : scan_thermal<true, false, false>(unwrap, allow_breaks, dt);
    else if (model->thermal_active())
      nb = hot ? scan_thermal<false, true, false>(unwrap, allow_breaks, dt)
               : scan_thermal<false, false, false>(unwrap, allow_breaks, dt);
    else if (all)
      nb = scan<true, true>(unwrap, allow_breaks);
    else if (orthogonal)
      nb = scan<true, false>(unwrap, allow_breaks);
    else
      nb = scan<false, false>(unwrap, allow_breaks);
  } catch (const BreakError &e) {
    error->one(FLERR, "Fix eq/contacts: {}", e.what());
  }
  local_sum[SUM_BREAKS] = static_cast<double>(nb);
  clock += dt;
  // the per-atom output, valid every peratom_every steps, at a set-up and
  // throughout a minimization
  if (hot_live && (in_setup || !allow_breaks || update->ntimestep % peratom_every == 0))
    sync_rows();
}

// returns the number of breaks.  ALL: the fix's group is all and every
// local atom has its bit (masks_skippable()): the masks are not read
template <bool ORTHOGONAL, bool ALL>
long FixEQContacts::scan(const EQUtil::Unwrap &unwrap_arg, bool allow_breaks)
{
  // the common step in line: a formed contact (x_s > 0) whose stretch is
  // below its threshold less the tolerance and below the reach of the
  // unwrap's correction (so that the correction is the identity).  One
  // test covers them all (x_s <= 0 fails it).  Contacts detached for good
  // stay in line; every other contact goes out of line (settle_scan()).
  const EQUtil::Unwrap unwrap = unwrap_arg;
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int bit = groupbit;
  const double rel = break_tol;
  const double reach = unwrap.stretch_reach();
  const std::size_t width = ncol;
  double *const rows = nlocal > 0 ? state[0] : nullptr;    // nmax x ncol in one block
  double *const fd = nlocal > 0 ? atom->f[0] + idir : nullptr;
  LoopSums sum(ALL ? nlocal : 0.0);
  long nb = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!ALL) {
      if (!(mask[i] & bit)) continue;
      sum.ncount += 1.0;
    }
    double *const st = rows + i * width;
    const double xu = ORTHOGONAL ? unwrap.orthogonal_coordinate(i) : unwrap(i);
    double s = xu - st[CS_ANCHOR];
    const double tol = ContactModel::tolerance(st[CS_ANCHOR], s, rel);
    const bool common = std::fabs(s) < std::min(st[CS_THRESHOLD] - tol, reach);
    if (FEQ_UNLIKELY(!common)) {
      if (st[CS_THRESHOLD] < 0.0) {    // detached for good
        st[CS_STRETCH] = st[CS_FORCE] = 0.0;
        continue;
      }
      if (!settle_scan(st, i, xu, unwrap_arg, allow_breaks, nb)) continue;
      s = st[CS_STRETCH];
    } else {
      st[CS_STRETCH] = s;
    }
    const double fc = st[CS_STIFFNESS] * s;
    st[CS_FORCE] = fc;
    sum.add(&fd[3 * i], fc, s);
  }
  local_breaks_total += nb;
  store_sums(sum.f, sum.e, sum.s, sum.natt, sum.ncount);
  return nb;
}

// scan()'s contacts off the common step other than those detached for
// good (scan() keeps them): not formed yet, at or over their threshold,
// or with a stretch the unwrap corrects; false when it has no contact
// (stretch and force 0).  st: its row, xu: its atom's unwrapped coordinate
bool FixEQContacts::settle_scan(double *st, int i, double xu, const EQUtil::Unwrap &unwrap,
                                bool allow_breaks, long &nb)
{
  const double xs = st[CS_THRESHOLD];
  if (xs == 0.0) return settle(st, i, xu, unwrap, allow_breaks, nb);
  const double s = unwrap.stretch(xu - st[CS_ANCHOR]);
  st[CS_STRETCH] = s;
  if (allow_breaks && !(std::fabs(s) < xs - ContactModel::tolerance(st, break_tol)))
    return settle(st, i, xu, unwrap, allow_breaks, nb);
  return true;
}

/* ----------------------------------------------------------------------
   with temperature, aging or delays: each contact advances by the time
   step in lib/eq_contact (ContactModel::advance()); dt = 0 in the set-up
   of a run.  Without breaks (minimization) the contacts hold and do not
   age.  A waiting contact's anchor follows its atom (the motion of the
   next step is measured from it).
------------------------------------------------------------------------- */

template <bool ORTHOGONAL, bool THERMAL, bool ALL>
long FixEQContacts::scan_thermal(const EQUtil::Unwrap &unwrap_arg, bool allow_breaks, double dt)
{
  // as scan(): the common step (ContactModel::stored_quick(): the rows are
  // in stored form, and the step writes only the stretch and the force) in
  // line, everything else out of line (settle_thermal_scan()); ALL as scan()'s
  const EQUtil::Unwrap unwrap = unwrap_arg;
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int bit = groupbit;
  const bool quick = allow_breaks && dt > 0.0;
  const double t_end = clock + dt;    // the rows are in stored form (feq::to_engine())
  const double reach = unwrap.stretch_reach();
  const std::size_t width = ncol;
  double *const rows = nlocal > 0 ? state[0] : nullptr;    // nmax x ncol in one block
  double *const fd = nlocal > 0 ? atom->f[0] + idir : nullptr;
  LoopSums sum(ALL ? nlocal : 0.0);
  long nb = 0;
  for (int i = 0; i < nlocal; i++) {
    if (!ALL) {
      if (!(mask[i] & bit)) continue;
      sum.ncount += 1.0;
    }
    double *const st = rows + i * width;
    const double xu = ORTHOGONAL ? unwrap.orthogonal_coordinate(i) : unwrap(i);
    double s = xu - st[CS_ANCHOR];
    // the common step: formed, attached, within the unwrap's reach (where
    // its correction is the identity) and stored_quick() (at T > 0 that
    // fails for a contact not formed, detached or waiting: no bound)
    const bool common = quick && (THERMAL || (st[CS_THRESHOLD] > 0.0 && !(st[CT_WAIT] > 0.0))) &&
        std::fabs(s) < reach && ContactModel::stored_quick<THERMAL>(st, s, t_end);
    if (FEQ_UNLIKELY(!common)) {
      if (!settle_thermal_scan(i, unwrap_arg, xu, allow_breaks, dt, nb)) continue;
      s = st[CS_STRETCH];
    }
    const double fc = st[CS_STIFFNESS] * s;
    st[CS_FORCE] = fc;
    sum.add(&fd[3 * i], fc, s);
  }
  local_breaks_total += nb;
  store_sums(sum.f, sum.e, sum.s, sum.natt, sum.ncount);
  return nb;
}

/* ----------------------------------------------------------------------
   keyword peratom N > 1: scan_thermal() on compact rows.  The common step
   reads 6 doubles and writes 2 (stretch and force) where the state row
   is 15; every other contact goes out of line on its state row, made
   current first (sync_row()) and copied back after (load_hot()), so that
   the numbers are scan_thermal()'s to the last bit
------------------------------------------------------------------------- */

template <bool ORTHOGONAL, bool ALL>
long FixEQContacts::scan_hot(const EQUtil::Unwrap &unwrap_arg, bool allow_breaks, double dt)
{
  // in blocks of BLOCK contacts: first the stretches and the common-step
  // test of the whole block (a bit of `off`: off the common step), with
  // the state rows of the members off it fetched ahead (prefetched), then
  // the block in index order.  Nothing the second pass writes (rows,
  // compact rows and forces of other contacts) enters a test of the first
  constexpr int BLOCK = 32;    // (the bits of `off`)
  const EQUtil::Unwrap unwrap = unwrap_arg;
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int bit = groupbit;
  const bool quick = allow_breaks && dt > 0.0;
  const double t_end = clock + dt;
  const double reach = unwrap.stretch_reach();
  double *const rows = hot.data();
  const double *const cold = nlocal > 0 ? state[0] : nullptr;    // nmax x ncol in one block
  const std::size_t width = ncol;
  double *const fd = nlocal > 0 ? atom->f[0] + idir : nullptr;
  LoopSums sum(ALL ? nlocal : 0.0);
  long nb = 0;
  double sblock[BLOCK];
  for (int i0 = 0; i0 < nlocal; i0 += BLOCK) {
    const int n = std::min(BLOCK, nlocal - i0);
    // (no common step in a set-up or minimization: every contact off it)
    uint32_t off = quick ? 0u : ~0u;
    for (int k = 0; quick && k < n; k++) {
      const int j = i0 + k;
      const double *const h = rows + static_cast<std::size_t>(j) * H_NCOL;
      const double s = (ORTHOGONAL ? unwrap.orthogonal_coordinate(j) : unwrap(j)) - h[H_ANCHOR];
      sblock[k] = s;
      const bool common = std::fabs(s) < std::min(h[H_LIMIT], reach) && t_end < h[H_RUNOUT];
      if (FEQ_UNLIKELY(!common)) {
        off |= 1u << k;
        if (h[H_LIMIT] != HOT_WAITING && (ALL || (mask[j] & bit))) {
          const double *const st = cold + j * width;    // (15 doubles: up to 3 cache lines)
          FEQ_PREFETCH(st);
          FEQ_PREFETCH(st + 7);
          FEQ_PREFETCH(st + width - 1);
        }
      }
    }
    for (int k = 0; k < n; k++) {
      const int i = i0 + k;
      if (!ALL) {
        if (!(mask[i] & bit)) continue;
        sum.ncount += 1.0;
      }
      double *const h = rows + static_cast<std::size_t>(i) * H_NCOL;
      double s = sblock[k];
      if (FEQ_UNLIKELY((off >> k) & 1u)) {
        const double xu = ORTHOGONAL ? unwrap.orthogonal_coordinate(i) : unwrap(i);
        if (h[H_LIMIT] == HOT_WAITING && quick &&
            model->wait_goes_on(h[H_RUNOUT], unwrap.stretch(xu - h[H_ANCHOR]), dt)) {
          h[H_RUNOUT] -= dt;    // (settle_thermal_scan()'s waiting contact)
          h[H_ANCHOR] = xu;
          h[H_STRETCH] = h[H_FORCE] = 0.0;
          continue;
        }
        sync_row(i);
        const bool present = settle_thermal_scan(i, unwrap_arg, xu, allow_breaks, dt, nb);
        load_hot(i);
        if (!present) continue;
        s = h[H_STRETCH];
      } else {
        h[H_STRETCH] = s;
      }
      const double fc = h[H_STIFFNESS] * s;
      h[H_FORCE] = fc;
      sum.add(&fd[3 * i], fc, s);
    }
  }
  local_breaks_total += nb;
  store_sums(sum.f, sum.e, sum.s, sum.natt, sum.ncount);
  return nb;
}

// the next double above b >= 0 (std::nextafter(b, HUGE_VAL) without a call)
static inline double next_up(double b)
{
  uint64_t u;
  std::memcpy(&u, &b, sizeof(u));
  ++u;
  std::memcpy(&b, &u, sizeof(b));
  return b;
}

// the compact row of atom i from its state row: stored_quick()'s tests as
// one bound of |s| (|s| <= b as |s| < the next double above b) and a
// run-out time (none for T = 0: aging or delays alone)
void FixEQContacts::load_hot(int i)
{
  const double *st = state[i];
  double *h = &hot[static_cast<std::size_t>(i) * H_NCOL];
  h[H_ANCHOR] = st[CS_ANCHOR];
  h[H_STIFFNESS] = st[CS_STIFFNESS];
  h[H_STRETCH] = st[CS_STRETCH];
  h[H_FORCE] = st[CS_FORCE];
  if (st[CS_THRESHOLD] > 0.0 && st[CT_WAIT] > 0.0) {
    h[H_LIMIT] = HOT_WAITING;
    h[H_RUNOUT] = st[CT_WAIT];
  } else if (hot_T) {
    // (+ 0.0: a bound of -0 is 0; a bound of +inf gives NaN, and then
    // XS_LOW, as |s| <= inf holds)
    h[H_LIMIT] =
        st[CT_BOUND_S] >= 0.0 ? std::min(st[CT_XS_LOW], next_up(st[CT_BOUND_S] + 0.0)) : -1.0;
    h[H_RUNOUT] = st[CT_RUNOUT];
  } else {
    h[H_LIMIT] = st[CS_THRESHOLD] > 0.0 && !(st[CT_WAIT] > 0.0) ? st[CT_XS_LOW] : -1.0;
    h[H_RUNOUT] = HUGE_VAL;
  }
}

void FixEQContacts::sync_row(int i)
{
  const double *h = &hot[static_cast<std::size_t>(i) * H_NCOL];
  double *st = state[i];
  st[CS_STRETCH] = h[H_STRETCH];
  st[CS_FORCE] = h[H_FORCE];
  if (h[H_LIMIT] == HOT_WAITING) {
    st[CS_ANCHOR] = h[H_ANCHOR];
    st[CT_WAIT] = h[H_RUNOUT];
  }
}

void FixEQContacts::sync_rows()
{
  for (int i = 0; i < atom->nlocal; i++) sync_row(i);
}

// the compact rows of a run's first evaluation (its set-up, or the first
// step of a run with pre no), from the state rows
void FixEQContacts::make_hot_live()
{
  if (hot_live) return;
  hot.resize(static_cast<std::size_t>(atom->nmax) * H_NCOL);
  for (int i = 0; i < atom->nlocal; i++) load_hot(i);
  hot_live = 1;
}

// between runs (and at the set-up of one) the state rows are the whole
// state: what the compact rows hold written back (sync_row())
void FixEQContacts::end_hot()
{
  if (hot_live) sync_rows();
  hot_live = 0;
}

// the per-atom state with compact rows: they go where the state rows go
void FixEQContacts::grow_arrays(int nmax)
{
  FixEQPerAtom::grow_arrays(nmax);
  if (peratom_every > 1) hot.resize(static_cast<std::size_t>(nmax) * H_NCOL);
}

void FixEQContacts::copy_arrays(int i, int j, int delflag)
{
  FixEQPerAtom::copy_arrays(i, j, delflag);
  if (hot_live && i != j)
    std::copy_n(&hot[std::size_t(i) * H_NCOL], H_NCOL, &hot[std::size_t(j) * H_NCOL]);
}

void FixEQContacts::set_arrays(int i)
{
  FixEQPerAtom::set_arrays(i);
  if (hot_live) load_hot(i);
}

int FixEQContacts::pack_exchange(int i, double *buf)
{
  if (hot_live) sync_row(i);
  return FixEQPerAtom::pack_exchange(i, buf);
}

int FixEQContacts::unpack_exchange(int nlocal, double *buf)
{
  const int n = FixEQPerAtom::unpack_exchange(nlocal, buf);
  if (hot_live) load_hot(nlocal);
  return n;
}

int FixEQContacts::pack_restart(int i, double *buf)
{
  if (hot_live) sync_row(i);
  return FixEQPerAtom::pack_restart(i, buf);
}

// settle_thermal() of an attached contact in a step of dt > 0 (d: its
// atom's unwrapped coordinate xu less its anchor), without its checks for
// formation and a new run.  Within the unwrap's reach the stretch is d,
// and scan_thermal()'s inline test found stored_quick() false for it
// (quick_attached() on the engine form is then false too, to rounding;
// advance() takes the same step either way)
inline bool FixEQContacts::step_attached(double *st, int i, const EQUtil::Unwrap &unwrap,
                                         double xu, double d, double dt, long &nb)
{
  const uint64_t id = static_cast<uint64_t>(atom->tag[i]);
  const ThermalStepResult r = std::fabs(d) < unwrap.stretch_reach()
      ? model->advance(st, id, d, dt, nb)
      : model->step(st, id, unwrap.stretch(d), dt, nb);
  return took_step(st, r, unwrap, xu);
}

// the end of a step taken by ContactModel::step() or advance(): a new
// anchor where the contact broke or re-formed; false when it is absent
// (waiting, detached for good) with stretch and force 0
inline bool FixEQContacts::took_step(double *st, const ThermalStepResult &r,
                                     const EQUtil::Unwrap &unwrap, double xu)
{
  if (r.attached && r.renewed) {
    st[CS_ANCHOR] = xu - r.stretch;
    model->hold(st, unwrap.stretch(xu - st[CS_ANCHOR]));
  } else if (!r.attached && st[CS_THRESHOLD] > 0.0) {
    st[CS_ANCHOR] = xu;
  }
  return absent_zeroed(st);
}

// false, with stretch and force 0, for a contact absent (not formed,
// detached for good, waiting); true otherwise
inline bool FixEQContacts::absent_zeroed(double *st)
{
  if (!(st[CS_THRESHOLD] > 0.0) || st[CT_WAIT] > 0.0) {
    st[CS_STRETCH] = st[CS_FORCE] = 0.0;
    return false;
  }
  return true;
}

// scan_thermal()'s contacts off the common step (xu: the atom's unwrapped
// coordinate), called only after its inline test failed: a waiting
// contact whose delay goes on (its anchor follows its atom; its stored
// times hold: it forms when its wait ends, and no bound counts its
// budget down), else, on its row in engine form over the step from the
// clock to clock + dt, an attached contact's step (step_attached()) or
// settle_thermal()
bool FixEQContacts::settle_thermal_scan(int i, const EQUtil::Unwrap &unwrap, double xu,
                                        bool allow_breaks, double dt, long &nb)
{
  double *const st = state[i];
  const bool stepping = allow_breaks && dt > 0.0 && st[CS_THRESHOLD] > 0.0;
  const double d = xu - st[CS_ANCHOR];
  if (stepping && st[CT_WAIT] > 0.0 && model->quick_wait(st, unwrap.stretch(d), dt)) {
    st[CS_ANCHOR] = xu;
    st[CS_FORCE] = 0.0;
    return false;
  }
  return feq::engine_call(st, clock, clock + dt, [&] {
    return stepping && !(st[CT_WAIT] > 0.0) ? step_attached(st, i, unwrap, xu, d, dt, nb)
                                            : settle_thermal(i, unwrap, allow_breaks, dt, nb);
  });
}

// a contact off the common step: formed, its step taken (or held), its
// stretch stored; false when it is absent (waiting, detached for good)
// with stretch and force 0
bool FixEQContacts::settle_thermal(int i, const EQUtil::Unwrap &unwrap, bool allow_breaks,
                                   double dt, long &nb)
{
  double *const st = state[i];
  const uint64_t id = static_cast<uint64_t>(atom->tag[i]);
  if (st[CS_THRESHOLD] == 0.0) model->form(st, id, unwrap(i));
  // a new run (dt = 0 in its set-up) may come with other parameters
  if (dt == 0.0) model->new_run(st);
  const double xu = unwrap(i);
  if (!(st[CS_THRESHOLD] > 0.0)) return absent_zeroed(st);
  const double m = unwrap.stretch(xu - st[CS_ANCHOR]);
  if (allow_breaks) return took_step(st, model->step(st, id, m, dt, nb), unwrap, xu);
  if (st[CT_WAIT] > 0.0) st[CS_ANCHOR] = xu;
  else model->hold(st, m);
  return absent_zeroed(st);
}

// the local sums of a force evaluation (reduced when an output asks)
void FixEQContacts::store_sums(double fsum, double esum, double ssum, double natt, double ncount)
{
  local_sum[SUM_FORCE] = fsum;
  local_sum[SUM_ATTACHED] = natt;
  local_sum[SUM_ENERGY] = 0.5 * esum;
  local_sum[SUM_STRETCH] = ssum;
  local_sum[SUM_COUNT] = ncount;
  local_sum[SUM_TOTAL] = static_cast<double>(local_breaks_total);
  reduced_valid = 0;
}

// a contact that forms or reaches its threshold (st: its row, xu: its
// atom's unwrapped coordinate): formed, its breaks resolved, its stretch
// stored; false when it detached for good
bool FixEQContacts::settle(double *st, int i, double xu, const EQUtil::Unwrap &unwrap,
                           bool allow_breaks, long &nb)
{
  const uint64_t id = static_cast<uint64_t>(atom->tag[i]);
  if (st[CS_THRESHOLD] == 0.0) model->form(st, id, xu);
  if (st[CS_THRESHOLD] < 0.0) {
    st[CS_STRETCH] = st[CS_FORCE] = 0.0;
    return false;
  }
  double s = unwrap.stretch(xu - st[CS_ANCHOR]);
  st[CS_STRETCH] = s;
  const double tol = ContactModel::tolerance(st, break_tol);
  if (allow_breaks && !(std::fabs(s) < st[CS_THRESHOLD] - tol)) {
    s = model->resolve(st, id, s, tol, nb);
    if (st[CS_THRESHOLD] < 0.0) {
      st[CS_STRETCH] = st[CS_FORCE] = 0.0;
      return false;
    }
    st[CS_ANCHOR] = xu - s;
    // the stretch as every later evaluation at these positions finds it
    // (x - anchor), so that run 0 or a restart changes nothing
    s = unwrap.stretch(xu - st[CS_ANCHOR]);
  }
  st[CS_STRETCH] = s;
  return true;
}

/* ----------------------------------------------------------------------
   interacting contacts: stretches from the positions, the field's update,
   then the avalanche (lib/eq_contact: synchronous rounds, the field
   follows every round's breaks); the pair style applies -h_i afterwards
------------------------------------------------------------------------- */

// t: the time at which contacts that form now form (the end of the step)
void FixEQContacts::stretches(double t)
{
  const int *const mask = atom->mask;
  const tagint *const tag = atom->tag;
  const int nlocal = atom->nlocal;
  const EQUtil::Unwrap unwrap(atom, domain, idir);
  if (static_cast<int>(qbuf.size()) < atom->nmax) qbuf.resize(atom->nmax);
  members.clear();
  try {
    for (int i = 0; i < nlocal; i++) {
      qbuf[i] = NOT_A_CONTACT;
      if (!(mask[i] & groupbit)) continue;
      double *const st = state[i];
      if (st[CS_THRESHOLD] == 0.0) {
        model->form(st, static_cast<uint64_t>(tag[i]), unwrap(i));
        if (model->thermal_active()) feq::from_engine(st, t);
      }
      if (st[CS_THRESHOLD] < 0.0) {
        st[CS_STRETCH] = st[CS_FORCE] = st[CS_FIELD] = 0.0;
        continue;
      }
      if (model->waiting(st)) {    // out of the field; its anchor follows its atom
        st[CS_ANCHOR] = unwrap(i);
        st[CS_STRETCH] = st[CS_FORCE] = st[CS_FIELD] = 0.0;
        continue;
      }
      const double s = unwrap.stretch(unwrap(i) - st[CS_ANCHOR]);
      st[CS_STRETCH] = s;
      qbuf[i] = s;
      members.push_back(i);
    }
  } catch (const BreakError &e) {
    error->one(FLERR, "Fix eq/contacts: {}", e.what());
  }
}

/* ----------------------------------------------------------------------
   what the field reads: the stretches of this evaluation, and the change
   set of the last avalanche round (valid until the next round)
------------------------------------------------------------------------- */

const double *FixEQContacts::source_coordinates()
{
  if (static_cast<int>(qbuf.size()) < atom->nlocal) stretches(clock);
  return qbuf.data();
}

bool FixEQContacts::source_changes(bigint since, EQChangeSet &set) const
{
  if (since != chg_from) return false;
  set = chg;
  return true;
}

void FixEQContacts::record_changes(const int *list, int n, const double *ds, bool exact)
{
  // the engine's new stretches themselves (not old + ds: exact whatever
  // the size of the change)
  for (int m = 0; m < n; m++) qbuf[list[m]] = state[list[m]][CS_STRETCH];
  broke.insert(broke.end(), list, list + n);
  new_version(list, n, ds, exact, false);
}

// the change set of a new version (valid until the next one)
void FixEQContacts::new_version(const int *list, int n, const double *dq, bool exact,
                                bool members_changed)
{
  chg.list = list;
  chg.n = n;
  chg.dq = dq;
  chg.exact = exact;
  chg.members = members_changed;
  chg_from = nversion++;
}

// contacts list[0..n) left the field (detached for good, or waiting to
// re-form) or joined it (re-formed after their delay): a set of members
// (their coordinates become NaN, or the stretch they joined with)
void FixEQContacts::record_members(const int *list, int n, bool exact)
{
  for (int m = 0; m < n; m++) {
    const int i = list[m];
    qbuf[i] = attached(state[i]) ? state[i][CS_STRETCH] : NOT_A_CONTACT;
  }
  new_version(list, n, nullptr, exact, true);
}

// dt: the time of the step (0 at the set-up of a run and in minimization)
void FixEQContacts::field_step(bool allow_breaks, double dt)
{
  EQElasticField *elastic = field_now();
  // at T > 0 or with aging: a step probes the thermal breaks; the set-up
  // of a run (dt = 0) makes the rows valid for this run's parameters
  const bool hot = model->thermal_active() && allow_breaks;
  const bool probed = hot && dt > 0.0, hot_setup = hot && dt == 0.0;
  const bool delays = model->leaves_field();
  if (hot_setup && !delays) reform_waiting();
  if (probed) save_effective();
  if (probed && delays) count_down(dt);
  stretches(clock + dt);
  local_sum[SUM_BREAKS] = 0.0;
  rounds_last = 0;
  broke.clear();
  EQFieldView view;
  if (allow_breaks) {
    Hooks hooks(this, elastic);
    AvalancheResult res;
    try {
      // the contacts whose delay ended join the field, the thermal breaks
      // of the step, then the avalanche
      if (probed && delays) rejoin(hooks);
      if (probed) thermal_stage(hooks.field(), dt);
      if (hot_setup) new_run();
      // (thermal rows stay in stored form: the avalanche takes the time)
      res = avalanche(*model, state, members.data(), static_cast<int>(members.size()), break_tol,
                      hooks, blist, dsv, probed ? tbreak.data() : nullptr,
                      probed ? tage.data() : nullptr, model->thermal_active() ? clock + dt : NAN);
    } catch (const BreakError &e) {
      error->one(FLERR, "Fix eq/contacts: {}", e.what());
    }
    local_breaks_total += res.local;
    local_sum[SUM_BREAKS] = static_cast<double>(res.local);
    rounds_last = res.rounds;
    if (res.size > 0 && av_flag) record_avalanche(res.size, res.trigger, res.rounds);
    view = hooks.last_view();
  } else {
    view = elastic->field_view();
  }
  clock += dt;
  // the field of the final state, for the output and next_event(); the
  // stretches of re-formed contacts as every later evaluation at these
  // positions finds them (x - anchor), so that run 0 or a restart changes
  // nothing (they differ from the engine's by rounding)
  for (const int i : members) {
    double *st = state[i];
    st[CS_FIELD] = attached(st) ? view.h[i] : 0.0;
  }
  if (broke.empty()) return;
  const EQUtil::Unwrap unwrap(atom, domain, idir);
  for (const int i : broke) {
    double *st = state[i];
    if (attached(st)) st[CS_STRETCH] = unwrap.stretch(unwrap(i) - st[CS_ANCHOR]);
  }
}

// a new run's parameters for every formed contact of the group (waiting
// ones included)
void FixEQContacts::new_run()
{
  const int *const mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    double *st = state[i];
    if ((mask[i] & groupbit) && st[CS_THRESHOLD] > 0.0)
      feq::engine_call(st, clock, clock, [&] { model->new_run(st); });
  }
}

/* ----------------------------------------------------------------------
   formation delays with the field (ContactModel::leaves_field()): a
   broken contact waits out of the field, its anchor following its atom.
   count_down(), before stretches(): the waits go on by dt; a contact
   whose wait ends within the step re-forms (ContactModel::rejoin()) with
   the stretch it is to have at the end of the step without a field, and
   is listed in joins.  rejoin(), on every rank: if any contact joined,
   they join the field (a set of members: their partners' fields follow
   them, pair eq/elastic), then with reform_as force each joiner's stretch is solved in
   the field of its partners, k e = k (r + motion since), e = s + h/k:
   s = (k s0 + K s0 - h)/(k + K), a change set at fixed positions (with
   reform_as stretch it keeps s0).
   (Joiners of one step see each other at s0: the reference re-forms
   them in the field of the contacts attached before; the difference
   vanishes with the step, as the chance that partners join together.)
------------------------------------------------------------------------- */

void FixEQContacts::count_down(double dt)
{
  const EQUtil::Unwrap unwrap(atom, domain, idir);
  const int *const mask = atom->mask;
  joins.clear();
  for (int i = 0; i < atom->nlocal; i++) {
    double *st = state[i];
    if (!(mask[i] & groupbit) || !model->waiting(st)) continue;
    const double xu = unwrap(i);
    const double m = unwrap.stretch(xu - st[CS_ANCHOR]);
    if (!std::isfinite(m))
      error->one(FLERR, "Fix {} eq/contacts: the motion of the atom of waiting contact {} is {} "
                        "(numerical instability: check the timestep, the forces and the "
                        "integrator)", id, atom->tag[i], m);
    if (model->quick_wait(st, m, dt)) continue;    // its anchor: stretches()
    const double s =
        feq::engine_call(st, clock, clock + dt, [&] { return model->rejoin(st, m, dt); });
    st[CS_ANCHOR] = xu - s;
    joins.push_back(i);
  }
}

void FixEQContacts::rejoin(Hooks &hooks)
{
  // how many join, and how many with a stretch an incremental field
  // cannot follow (as avalanche()), over all ranks
  long n[2] = {static_cast<long>(joins.size()), 0};
  for (const int i : joins)
    if (!change_followable(qbuf[i], 0.0)) ++n[1];
  hooks.global_sum(n, 2);
  if (n[0] == 0) return;
  record_members(joins.data(), static_cast<int>(joins.size()), n[1] == 0);
  const feq::AvalancheField f = hooks.field();
  if (!model->reform_as_force()) return;
  int top = -1;
  for (const int i : joins) top = std::max(top, i);
  if (static_cast<int>(dsv.size()) <= top) dsv.resize(top + 1);
  long big = 0;    // changes an incremental update cannot follow (as avalanche())
  for (const int i : joins) {
    double *st = state[i];
    const double k = st[CS_STIFFNESS];
    const double ds = -f.h[i] / (k + f.k[i]);
    st[CS_STRETCH] += ds;
    st[CS_ANCHOR] -= ds;
    dsv[i] = ds;
    if (!change_followable(ds, st[CS_STRETCH])) ++big;
  }
  hooks.global_sum(&big, 1);
  hooks.changed(joins.data(), static_cast<int>(joins.size()), dsv.data(), big == 0);
}

// the effective stretch e = s + h/k of every formed contact at the end of
// the last step (NaN: none), before stretches() takes the new positions
void FixEQContacts::save_effective()
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  if (static_cast<int>(eprev.size()) < atom->nmax) eprev.resize(atom->nmax);
  for (int i = 0; i < nlocal; i++) {
    const double *st = state[i];
    eprev[i] = (mask[i] & groupbit) && attached(st)
        ? st[CS_STRETCH] + st[CS_FIELD] / st[CS_STIFFNESS]
        : NAN;
  }
}

// the thermal part of the step at the field f of its start (for a rigid
// slider the field changes only at breaks): each formed contact's
// effective stretch goes linearly from eprev to s + h/k; a contact that
// breaks thermally is marked for the avalanche's first round (tbreak: its
// e then; NaN: no thermal break)
void FixEQContacts::thermal_stage(const feq::AvalancheField &f, double dt)
{
  const tagint *const tag = atom->tag;
  if (static_cast<int>(tbreak.size()) < atom->nmax) {
    tbreak.resize(atom->nmax);
    tage.resize(atom->nmax);
  }
  const bool hot = model->thermal_model().params().thermal();
  const double t_end = clock + dt;    // the rows are in stored form (feq::to_engine())
  for (const int i : members) {
    double *st = state[i];
    tbreak[i] = NAN;
    tage[i] = 0.0;
    if (!(st[CS_THRESHOLD] > 0.0) || !std::isfinite(eprev[i])) continue;
    const double e1 = st[CS_STRETCH] + f.h[i] / st[CS_STIFFNESS];
    if (hot ? ContactModel::stored_quick_probe<true>(st, eprev[i], e1, t_end)
            : ContactModel::stored_quick_probe<false>(st, eprev[i], e1, t_end))
      continue;
    const uint64_t id = static_cast<uint64_t>(tag[i]);
    const ContactModel::ThermalProbe r =
        feq::engine_call(st, clock, t_end, [&] { return model->probe(st, id, eprev[i], e1, dt); });
    if (!r.broke) continue;
    tbreak[i] = eprev[i] + (e1 - eprev[i]) * r.frac;
    tage[i] = (1.0 - r.frac) * dt;
  }
}

// contacts of a restart file written with a delay that still wait, in a
// run with the pair style and without a delay: they re-form now, with
// the stretch they were to re-form with
void FixEQContacts::reform_waiting()
{
  const EQUtil::Unwrap unwrap(atom, domain, idir);
  const int *const mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    double *st = state[i];
    if (!(mask[i] & groupbit) || !(st[CS_THRESHOLD] > 0.0) || !(st[CT_WAIT] > 0.0)) continue;
    st[CS_ANCHOR] = unwrap(i) - st[CT_PENDING];
    st[CT_WAIT] = st[CT_PENDING] = 0.0;
    st[CT_FORMED] = clock;    // (age 0, as it waited)
  }
}

void FixEQContacts::record_avalanche(bigint size, bigint trigger, int rounds)
{
  if (!avfp) return;
  fmt::print(avfp, "{} {} {} {}\n", update->ntimestep, size, trigger, rounds);
}

// spring forces -k_i x_i of the state prepared by field_step()
void FixEQContacts::apply_forces()
{
  tally(atom->f);
}

// the sums of the output from the contacts' state, and their spring
// forces -k_i s_i into f (nullptr: the sums only, e.g. at definition)
void FixEQContacts::tally(double **f)
{
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int bit = groupbit;
  // rows and forces by offset (each one block in LAMMPS' arrays): no
  // reload of their row pointers after each store
  const std::size_t width = ncol;
  double *const rows = nlocal > 0 ? state[0] : nullptr;
  double *const fd = f && nlocal > 0 ? f[0] + idir : nullptr;
  double fsum = 0.0, esum = 0.0, ssum = 0.0, natt = 0.0, ncount = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & bit)) continue;
    double *const st = rows + i * width;
    ncount += 1.0;
    if (!attached(st)) continue;
    const double s = st[CS_STRETCH];
    const double fc = st[CS_STIFFNESS] * s;
    st[CS_FORCE] = fc;
    if (fd) fd[3 * i] -= fc;
    fsum += fc;
    esum += fc * s;
    ssum += s;
    natt += 1.0;
  }
  store_sums(fsum, esum, ssum, natt, ncount);
}

/* ----------------------------------------------------------------------
   distance the slider (moving along +dir) has to advance until the first
   contact reaches its threshold: x_si - (x_i + h_i/k_i), minimum over all
   contacts and ranks.  A uniform advance leaves h_i unchanged.
------------------------------------------------------------------------- */

double FixEQContacts::next_event()
{
  if (hot_live) sync_rows();
  const int *const mask = atom->mask;
  const int nlocal = atom->nlocal;
  double dmin = std::numeric_limits<double>::infinity();
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double *st = state[i];
    if (st[CS_THRESHOLD] <= 0.0) continue;
    const double e = st[CS_STRETCH] + st[CS_FIELD] / st[CS_STIFFNESS];
    const double dist = st[CS_THRESHOLD] - e;
    if (dist < dmin) dmin = dist;
  }
  double all = dmin;
  MPI_Allreduce(&dmin, &all, 1, MPI_DOUBLE, MPI_MIN, world);
  return all > 0.0 ? all : 0.0;
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

/* ----------------------------------------------------------------------
   before the first run the outputs follow the positions (displace_atoms
   after the fix's definition): the contacts' stretches and sums now
------------------------------------------------------------------------- */

void FixEQContacts::outputs_before_run()
{
  if (ran) return;
  const EQUtil::Unwrap unwrap(atom, domain, idir);
  const int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    double *st = state[i];
    if ((mask[i] & groupbit) && attached(st))
      st[CS_STRETCH] = unwrap.stretch(unwrap(i) - st[CS_ANCHOR]);
  }
  tally(nullptr);
}

double FixEQContacts::compute_scalar()
{
  outputs_before_run();
  reduce();
  return global_sum[SUM_ENERGY];
}

double FixEQContacts::compute_vector(int n)
{
  outputs_before_run();
  switch (n) {
    case 0: reduce(); return global_sum[SUM_FORCE];
    case 1: reduce(); return global_sum[SUM_BREAKS];
    case 2: reduce(); return global_sum[SUM_TOTAL] + static_cast<double>(breaks_offset);
    case 3: reduce(); return global_sum[SUM_ATTACHED];
    case 4: reduce(); return global_sum[SUM_ENERGY];
    case 5:
      reduce();
      return global_sum[SUM_ATTACHED] > 0.0 ? global_sum[SUM_STRETCH] / global_sum[SUM_ATTACHED]
                                            : 0.0;
    case 6: reduce(); return global_sum[SUM_COUNT];
    case 7:
      if (!interacting && !av_flag) {
        reduce();
        return global_sum[SUM_BREAKS] > 0.0 ? 1.0 : 0.0;
      }
      return static_cast<double>(rounds_last);
    case 8: return clock;
  }
  return 0.0;
}

/* ----------------------------------------------------------------------
   global restart: total breaks and the seed, and the signature of what
   the stored contacts were made with (kc, threshold, reform, stiffness,
   dir): a fix re-specified with another of these stops with an error
   naming it; another seed only warns (the breaks go on with new draws)
------------------------------------------------------------------------- */

void FixEQContacts::write_restart(FILE *fp)
{
  bigint all = 0;
  MPI_Allreduce(&local_breaks_total, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  EQRecord::write(lmp, fp,
                  {static_cast<double>(all + breaks_offset), static_cast<double>(seed), clock},
                  shaping);
}

void FixEQContacts::restart(char *buf)
{
  // a record of 2 values: written before the clock (its thermal rows kept
  // the budget and the age in engine form; athermal rows are the same)
  const auto *head = reinterpret_cast<const double *>(buf);
  const bool clockless = head[0] == feq::RECORD_MAGIC && head[1] == feq::RECORD_FORMAT && head[2] == 2.0;
  if (clockless && model->thermal_active())
    error->all(FLERR, "Fix {} eq/contacts: the restart file was written by an earlier version of "
                      "the package (before 28 Nov 2026), whose contacts with the keywords {} kept "
                      "their hazard budgets and ages in another form: such a file cannot be "
                      "continued with these keywords; start the run afresh, or continue it with "
                      "that version (a file written without these keywords: re-specify the fix "
                      "without them)", id, THERMAL_KEYWORDS);
  const std::vector<double> list =
      EQRecord::read(lmp, this, buf, clockless ? 2 : 3, shaping, "contacts");
  const double big = 9007199254740992.0;    // 2^53
  if (!(list[0] >= 0.0 && list[0] <= big && list[0] == std::floor(list[0])) ||
      !(list[1] >= 1.0 && list[1] <= big && list[1] == std::floor(list[1])))
    error->all(FLERR, "Fix {} eq/contacts: the restart file's record of this fix is unusable: "
                      "breaks {} and seed {} are not counts (a corrupt file)", id, list[0], list[1]);
  const double restored = clockless ? 0.0 : list[2];
  if (!std::isfinite(restored))
    error->all(FLERR, "Fix {} eq/contacts: the restart file's record of this fix is unusable: "
                      "clock {} (a corrupt file)", id, restored);
  // contacts formed at the fix's definition (atoms without stored rows)
  // formed at the restored time; stored rows replace the others
  if (model->thermal_active())
    for (int i = 0; i < atom->nlocal; i++)
      if (state[i][CS_THRESHOLD] > 0.0) state[i][CT_FORMED] += restored - clock;
  clock = restored;
  breaks_offset = static_cast<bigint>(list[0]);
  local_breaks_total = 0;
  if (static_cast<bigint>(list[1]) != seed && comm->me == 0)
    error->warning(FLERR,
                   "Fix eq/contacts: seed {} differs from the restart file's seed {}; the break "
                   "sequence does not continue that of the original run",
                   seed, static_cast<bigint>(list[1]));
}

/* ----------------------------------------------------------------------
   a contact restored from a restart file: a threshold that is 0 (not
   formed), -1 (detached for good) or positive with a positive stiffness,
   and a break count; an anchor within reach of its atom.  (The anchor is
   not compared with the stored stretch: the atoms may have been displaced
   between the last run and write_restart.)
------------------------------------------------------------------------- */

void FixEQContacts::check_restored(int i)
{
  const double *st = state[i];
  const double th = st[CS_THRESHOLD], nb = st[CS_NBREAK];
  std::string why;
  if (!(th == 0.0 || th == -1.0 || (th > 0.0 && st[CS_STIFFNESS] > 0.0)))
    why = fmt::format("threshold {} with stiffness {}", th, st[CS_STIFFNESS]);
  else if (!(nb >= 0.0 && nb <= 9007199254740992.0 && nb == std::floor(nb)))
    why = fmt::format("break count {}", nb);
  // (a budget is counted down only under a bound with a rate; otherwise
  // it is kept as its negative.  A row with no contact formed, that of an
  // atom outside the group, has no thermal state yet: form() makes it)
  const bool thermal_state = model->thermal_active() && th != 0.0;
  if (why.empty() && thermal_state &&
      !(st[CT_WAIT] >= 0.0 &&
        (std::signbit(st[CT_RUNOUT]) || (st[CT_BOUND_S] >= 0.0 && st[CT_BOUND_RATE] > 0.0))))
    why = fmt::format("delay left {}, budget run-out {} with rate bound {} up to {}", st[CT_WAIT],
                      st[CT_RUNOUT], st[CT_BOUND_RATE], st[CT_BOUND_S]);
  if (why.empty() && thermal_state &&
      !(st[CT_BOUND_RATE] >= 0.0 && st[CT_CANDIDATE] >= 0.0 &&
        st[CT_CANDIDATE] == std::floor(st[CT_CANDIDATE]) && st[CT_XS_LOW] >= 0.0))
    why = fmt::format("rate bound {}, candidate count {}, threshold bound {}", st[CT_BOUND_RATE],
                      st[CT_CANDIDATE], st[CT_XS_LOW]);
  if (!why.empty())
    error->one(FLERR, "Fix {} eq/contacts: the restart file's contact {} is garbled: {} (a "
                      "corrupt file)", id, atom->tag[i], why);
  if (th > 0.0) check_reach(i, idir, st[CS_ANCHOR], "anchor");
}

// only where the file holds another layout of this fix
std::string FixEQContacts::layout_hint(long stored) const
{
  if (stored == feq::CT_NCOL_HAZARD_BUDGET)
    return fmt::format("the file was written by an earlier version of the package, whose contacts "
                       "with the keywords {} kept {} values (thermal breaking against a hazard "
                       "budget; now sampled by thinning, {} values): such a file cannot be "
                       "continued; start the run afresh, or continue it with that version",
                       THERMAL_KEYWORDS, feq::CT_NCOL_HAZARD_BUDGET, static_cast<int>(CT_NCOL));
  if (stored != CS_NCOL && stored != CT_NCOL) return "";
  return fmt::format("the keywords {} add {} values per contact; give one of them in both the run "
                     "that wrote the file and this one, or in neither",
                     THERMAL_KEYWORDS, CT_NCOL - CS_NCOL);
}

/* ---------------------------------------------------------------------- */

double FixEQContacts::memory_usage()
{
  return FixEQPerAtom::memory_usage() +
      static_cast<double>(qbuf.capacity() + hot.capacity()) * sizeof(double) +
      static_cast<double>(dsv.capacity()) * sizeof(double) +
      static_cast<double>(members.capacity() + blist.capacity() + broke.capacity()) * sizeof(int);
}

/* ----------------------------------------------------------------------
   fix_modify: LAMMPS handles its own keywords (energy, virial, respa,
   dynamic/dof) before asking the fix; this fix has none of its own.
   Without this, LAMMPS 2021 answers 'Illegal fix_modify command'.
------------------------------------------------------------------------- */

int FixEQContacts::modify_param(int /*narg*/, char **arg)
{
  error->all(FLERR, "Fix_modify {}: unknown keyword '{}' for fix eq/contacts; allowed: LAMMPS' "
                    "energy, virial, respa (fix eq/contacts has no keywords of its own)", id, arg[0]);
  return 0;
}
