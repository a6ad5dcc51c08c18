/* -*- c++ -*- ----------------------------------------------------------
   FRICTION-EQ package for LAMMPS: pair_style eq/elastic

   Elastic interaction between the contacts of fix eq/contacts (Braun et
   al., Secs. III-IV): energy (1/2) sum_ij k_ij (x_i - x_j)^2 of the
   contacts' stretches x_i, with k(r) = ftilde/r below lambda_c and
   ftilde lambda_c^2/r^3 beyond (or a table).  Its per-contact force
   h_i = sum_j k_ij (x_i - x_j) enters the breaking test of the fix.
   With fix eq/substrate, x_i are the displacements of FK-ME blocks.
   See doc/src/pair_eq_elastic.rst.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(eq/elastic,PairEQElastic);
// clang-format on
#else

#ifndef LMP_PAIR_EQ_ELASTIC_H
#define LMP_PAIR_EQ_ELASTIC_H

#include "pair.h"

#include "eq_kernel.h"

#include <vector>

namespace LAMMPS_NS {

class PairEQElastic : public Pair {
 public:
  PairEQElastic(class LAMMPS *);
  ~PairEQElastic() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  double single(int, int, int, int, double, double, double, double &) override;
  void *extract(const char *, int &) override;
  void reinit() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  // --- interface for fix eq/contacts (the contact state lives there) ---
  // h_i (column INTERACT of the fix state) and K_i = sum_j k_ij of every
  // local contact from the stretches in the fix state (ghosts updated first)
  void field();
  // contacts list[0..n) changed their stretch by ds[list[m]]: update h of
  // all local contacts (scatter over the full neighbor list, reverse comm)
  void scatter(const int *list, int n, const double *ds);
  // K_i = sum_j k_ij of local contact i (valid after field())
  double coupling(int i) const { return ksum[i]; }
  // the fix has just computed h for the current positions (this step)
  void set_fresh() { fresh = 1; }

 protected:
  double cut_global;
  double **cut, **cutsq_in;    // cutoffs; squared with a 1e-12 relative margin
  double **ftilde, **lambda;   // crossover coefficients (for extract)
  int **kidx;                  // kernel of a type pair (index into kernels)
  int **mixed;                 // 1: the kernel of a type pair was mixed by init_one
  std::vector<feq::Kernel> kernels;
  int anisotropic;

  class FixEQContacts *fix;       // the contacts, or nullptr
  class FixEQSubstrate *sub;      // or the FK-ME blocks, or nullptr
  int hcol;                       // column of h_i in the fix's state
  int idir;
  int fresh;         // h in the fix state is current for this step
  int comm_mode;     // what forward comm carries
  int nmax;
  double *sx;        // stretches of local and ghost contacts (NaN: not a contact)
  double *dh;        // scattered changes of h (local and ghost)
  double *ksum;      // K_i of local contacts
  int ghosts_current;    // ghost stretches match the fix state

  // blocks of fix eq/substrate: their sites do not move, so the coupled
  // pairs of a neighbor list and their k_ij are found once per list build
  std::vector<int> bfirst, bj;    // offsets per ilist entry, partner j
  std::vector<double> bk;         // k_ij (special factor included)
  bigint bcache;                  // neighbor->ncalls of the cached list (-1: none)
  void block_pairs();
  void field_blocks();

  void allocate();
  void grow();
  void load_stretches();
  double **state();
  double kval(int itype, int jtype, double rsq, const double *del) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
