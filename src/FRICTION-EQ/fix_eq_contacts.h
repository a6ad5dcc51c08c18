/* -*- c++ -*- ----------------------------------------------------------
   FRICTION-EQ package for LAMMPS: earthquake-like (EQ) model of friction.

   fix ID group eq/contacts kc seed keyword values ...

   Each atom of the group is one contact: a spring of stiffness k_i
   between the atom (top end, on the slider) and an anchor (bottom end, on
   the substrate) stored per atom.  A contact breaks when its force
   reaches k_i x_si, with the threshold x_si drawn from P_c; it re-forms
   with a stretch drawn from R.  See doc/src/fix_eq_contacts.rst.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(eq/contacts,FixEQContacts);
// clang-format on
#else

#ifndef LMP_FIX_EQ_CONTACTS_H
#define LMP_FIX_EQ_CONTACTS_H

#include "fix.h"

#include "eq_distribution.h"

namespace LAMMPS_NS {

class FixEQContacts : public Fix {
 public:
  FixEQContacts(class LAMMPS *, int, char **);
  ~FixEQContacts() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void setup_pre_force(int) override;
  void pre_force(int) override;
  void min_setup(int) override;
  void post_force(int) override;
  void post_force_respa(int, int, int) override;
  void min_post_force(int) override;
  double compute_scalar() override;
  double compute_vector(int) override;

  void write_restart(FILE *) override;
  void restart(char *) override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  void *extract(const char *, int &) override;

  // columns of the per-atom state (also the per-atom output array);
  // INTERACT is the interaction force h_i of pair eq/elastic (0 without)
  enum { STRETCH, THRESHOLD, FORCE, NBREAK, STIFFNESS, ANCHOR, INTERACT, NCOL };

  // --- for pair eq/elastic and fix eq/quasistatic ---
  // stretches of all local contacts from the current positions (no breaks)
  void update_stretches();
  // slider advance (along +dir) that brings the first contact to its
  // threshold; global minimum over all ranks (infinite: no contact)
  double next_event();
  // relative tolerance of the breaking test (quasi-static driving)
  void set_break_tolerance(double tol) { break_tol = tol; }
  // all contacts were translated rigidly along dir since the last step:
  // the interaction field is unchanged (fix eq/quasistatic)
  void note_rigid_shift() { rigid_shift = 1; }

 private:
  double kc;
  bigint seed;
  int idir;          // sliding direction 0,1,2
  int exact;         // 1: threshold crossing resolved exactly within a step
  int start_reform;  // 1: initial stretch drawn from R, else 0
  int ilevel_respa;
  int reform_force;       // 1: a re-formed contact carries force k_i r (interaction included)
  double break_tol;       // relative tolerance of the breaking test
  class PairEQElastic *pair;    // the interaction, or nullptr
  FILE *avfp;             // avalanche records (rank 0), or nullptr
  int av_flag;            // avalanche records requested
  int rounds_last;        // generations of the last step's avalanche
  int rigid_shift;        // see note_rigid_shift()
  int nmax_list;
  int *blist;             // contacts breaking in an avalanche round
  double *dsv;            // their stretch changes

  feq::DistributionSpec threshold, reform, stiffness;
  bool reform_point, stiffness_const;
  double reform_value;
  double reform_cdf_lo, reform_cdf_hi;    // R truncated to |r| < max threshold
  double reform_top;                      // max threshold (effective for unbounded P_c)

  double **state;    // per-atom state, NCOL columns (array_atom)

  // local sums of the last force evaluation; reduced on demand
  double local_sum[7];
  double global_sum[7];
  bigint local_breaks_total, breaks_offset;
  bigint reduced_step;
  int reduced_valid;

  void apply(bool allow_breaks);
  void init_contact(int i);
  void mark_departed();
  double draw_reform(tagint tag, bigint event, uint32_t stream);
  double resolve_breaks(int i, double s);
  void reduce();
  void interact_step(bool allow_breaks);
  void cascade();
  double break_once(int i, double e);
  void apply_interacting();
  void record_avalanche(bigint size, bigint trigger, int rounds);
  inline double unwrap_fix(double s) const;
  double unwrapped(int i) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
