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
   FRICTION-EQ package for LAMMPS: earthquake-like (EQ) model of friction.

   fix ID group eq/contacts kc seed keyword values ...

   Each atom of the group is one contact: a spring of stiffness k_i
   between the atom (top end, on the slider) and an anchor (bottom end, on
   the substrate) stored per atom.  A contact breaks when its force
   reaches k_i x_si, with the threshold x_si drawn from P_c; it re-forms
   with a stretch drawn from R.  The break engine is lib/eq_contact; the
   stretches are the coordinates of an elastic field (pair eq/elastic)
   when there is one.  See doc/src/fix_eq_contacts.rst.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(eq/contacts,FixEQContacts);
// clang-format on
#else

#ifndef LMP_FIX_EQ_CONTACTS_H
#define LMP_FIX_EQ_CONTACTS_H

#include "eq_field.h"
#include "eq_fix_peratom.h"
#include "eq_record.h"

#include <memory>
#include <string>
#include <vector>

namespace feq {
class ContactModel;
struct AvalancheField;
struct ThermalStepResult;
}

namespace LAMMPS_NS {
namespace EQUtil {
  class Unwrap;
}

class FixEQContacts : public FixEQPerAtom, public EQCoordinateSource, public EQEventSource {
 public:
  FixEQContacts(class LAMMPS *, int, char **);
  ~FixEQContacts() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void setup_pre_force(int) override;
  void pre_force(int) override;
  void min_setup(int) override;
  void min_pre_force(int) override;
  void post_force(int) override;
  void post_force_respa(int, int, int) override;
  void min_post_force(int) override;
  void post_run() override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  double memory_usage() override;
  int modify_param(int, char **) override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;

 protected:
  void check_restored(int i) override;
  std::string layout_hint(long stored) const override;

 public:

  // EQCoordinateSource: the contacts' stretches
  const char *eq_name() const override { return name.c_str(); }
  int eq_instance() const override { return instance_me; }
  int source_dir() const override { return idir; }
  int source_groupbit() const override { return groupbit; }
  bool source_site_distance() const override { return false; }
  bigint source_evaluation() const override { return nevaluation; }
  bigint source_version() const override { return nversion; }
  const double *source_coordinates() override;
  bool source_changes(bigint since, EQChangeSet &set) const override;

  // EQEventSource (fix eq/quasistatic)
  int event_dir() const override { return idir; }
  int event_groupbit() const override { return groupbit; }
  double next_event() override;

 private:
  std::unique_ptr<feq::ContactModel> model;
  feq::Signature shaping;    // the arguments the stored contacts depend on
  std::string name;    // "fix ID eq/contacts"
  bigint seed;
  int idir;            // sliding direction 0,1,2
  int ilevel_respa;
  int respa_run;       // this run is run_style respa (init())
  double break_tol;    // relative tolerance of the breaking test (from a driver, see init())
  EQHeld<EQElasticField> field;    // the interaction of this run, or none
  int interacting;                 // the last run had one (output semantics)
  FILE *avfp;                      // avalanche records (rank 0), or nullptr
  int av_flag;                     // avalanche records requested
  int rounds_last;                 // rounds of the last step's avalanche
  int ran;                         // a run or minimization has set this fix up
  int in_setup;                    // in setup(): no time passes
  // the loops may skip the masks (group all, every local atom with its
  // bit): valid while neighbor->ncalls equals masks_builds (-1 at the
  // fix's definition and after every run); never with a fix that
  // rewrites masks within a step
  int masks_full, mask_writer;
  bigint masks_builds;

  // the coordinates this fix owns for the field: the stretches of the
  // local contacts at the current evaluation (NaN: not a contact), the
  // counters of evaluations and versions, and the last change set (the
  // breaks of an avalanche round, from version chg_from)
  std::vector<double> qbuf, dsv;
  // at T > 0 with pair eq/elastic, by row: the effective stretch at the
  // end of the last step, and this step's thermal breaks (their e, NaN for
  // none; the age of the new contact); valid within one field_step()
  std::vector<double> eprev, tbreak, tage;
  std::vector<int> members, blist;
  std::vector<int> joins;    // contacts whose delay ended in this step (count_down())
  std::vector<int> broke;    // contacts re-formed in this step's avalanche (once per round)
  // the time on the clock of this fix's contacts (thermal rows keep their
  // budgets and ages as times on it: feq::to_engine()); it goes on by dt
  // at each step of a run, and is restart data
  double clock;
  // keyword peratom N > 1 (thermal rows only): the per-atom output (the
  // state rows) is valid every N steps, and within a run the common step
  // works on compact rows `hot` (HotColumn in the .cpp).  Validity rule:
  // while hot_live (from a run's first evaluation to its post_run()) the
  // stretch and force of a local atom are those of its hot row (and the
  // anchor and delay left of a waiting contact), the rest of the hot row
  // is made from its state row by load_hot() whenever that changes, and
  // sync_row() writes them back (every N steps, at the set-up and end of
  // a run, throughout a minimization, before a row leaves in an exchange
  // or a restart file, before the engine takes the row; init(), setup()
  // and min_setup() end a period that a failed run left open)
  int peratom_every;
  int hot_live;
  bool hot_T;    // T > 0: the rows have a rate bound and a run-out time
  std::vector<double> hot;
  void load_hot(int i);
  void sync_row(int i);
  void sync_rows();
  void make_hot_live();
  void end_hot();
  bigint nevaluation, nversion, chg_from;
  EQChangeSet chg;

  // local sums of the last force evaluation; reduced on demand
  double local_sum[7];
  double global_sum[7];
  bigint local_breaks_total, breaks_offset;
  bigint reduced_step;
  int reduced_valid;

  class Hooks;
  friend class Hooks;

  struct Args;
  void parse(int narg, char **arg, Args &a);
  bigint check(const Args &a);
  void make_model(const Args &a);
  void open_avalanches(const std::string &file);
  void mark_departed();
  EQElasticField *field_now();
  void stretches(double t);
  void field_step(bool allow_breaks, double dt);
  void save_effective();
  void thermal_stage(const feq::AvalancheField &f, double dt);
  void reform_waiting();
  void new_run();
  void count_down(double dt);
  void rejoin(Hooks &hooks);
  void record_changes(const int *list, int n, const double *ds, bool exact);
  void record_members(const int *list, int n, bool exact);
  void new_version(const int *list, int n, const double *dq, bool exact, bool members_changed);
  void apply(bool allow_breaks);
  double step_dt() const;
  template <bool ORTHOGONAL, bool ALL> long scan(const EQUtil::Unwrap &unwrap, bool allow_breaks);
  inline bool attached(const double *st) const;    // defined in the .cpp, used there only
  void check_masks();
  bool masks_skippable();
  void store_sums(double fsum, double esum, double ssum, double natt, double ncount);
  template <bool ORTHOGONAL, bool THERMAL, bool ALL>
  long scan_thermal(const EQUtil::Unwrap &unwrap, bool allow_breaks, double dt);
  template <bool ORTHOGONAL, bool ALL>
  long scan_hot(const EQUtil::Unwrap &unwrap, bool allow_breaks, double dt);
  bool step_attached(double *st, int i, const EQUtil::Unwrap &unwrap, double xu, double d,
                     double dt, long &nb);
  bool took_step(double *st, const feq::ThermalStepResult &r, const EQUtil::Unwrap &unwrap,
                 double xu);
  static bool absent_zeroed(double *st);
  bool settle_thermal(int i, const EQUtil::Unwrap &unwrap, bool allow_breaks, double dt, long &nb);
  bool settle_thermal_scan(int i, const EQUtil::Unwrap &unwrap, double xu, bool allow_breaks,
                           double dt, long &nb);
  bool settle(double *st, int i, double xu, const EQUtil::Unwrap &unwrap, bool allow_breaks,
              long &nb);
  bool settle_scan(double *st, int i, double xu, const EQUtil::Unwrap &unwrap, bool allow_breaks,
                   long &nb);
  void apply_forces();
  void tally(double **f);
  void outputs_before_run();
  void record_avalanche(bigint size, bigint trigger, int rounds);
  void reduce();
};

}    // namespace LAMMPS_NS

#endif
#endif
