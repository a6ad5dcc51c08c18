/* -*- c++ -*- ----------------------------------------------------------
   FRICTION-EQ package for LAMMPS: pair_style eq/elastic

   Elastic interaction between the atoms of one coordinate source (fix
   eq/contacts: contact stretches; fix eq/substrate: block displacements;
   Braun et al., Secs. III-V): energy (1/2) sum_ij k_ij (q_i - q_j)^2 with
   k(r) = ftilde/r below lambda_c and ftilde lambda_c^2/r^3 beyond (or a
   table).  The style is the source's elastic field (eq_field.h): it keeps
   h_i = sum_j k_ij (q_i - q_j) and K_i = sum_j k_ij, updates them
   incrementally and applies -h_i along the source's direction.
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

#include "eq_field.h"
#include "eq_kernel.h"

#include <vector>

namespace LAMMPS_NS {

class PairEQElastic : public Pair, public EQElasticField {
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

  // EQElasticField
  const EQCoordinateSource *field_source() const override { return source; }
  void field_update(const double *q, bool full) override;
  bool field_advance() override;
  void field_change(const int *list, int n, const double *dq) override;
  const double *field_h() override
  {
    if (pending) site_field(nullptr);
    return h;
  }
  const double *field_k() const override { return ksum; }
  void field_report() override;

 protected:
  double cut_global;
  int check_every;             // drift check every this many uniform updates (0: never)
  double **cut, **cutsq_in;    // cutoffs; squared with a 1e-12 relative margin
  double **ftilde, **lambda;   // crossover coefficients (for extract)
  int **kidx;                  // kernel of a type pair (index into kernels)
  int **mixed;                 // 1: the kernel of a type pair was mixed by init_one
  std::vector<feq::Kernel> kernels;
  int anisotropic;

  const EQCoordinateSource *source;
  int idir, sgroupbit;
  bool site_distance;

  // per-atom arrays (local and ghost unless noted), valid between two
  // neighbor list builds: q the coordinates; xq the positions along dir
  // at the last update; w = x - q along dir at the last synchronization
  // of the ghosts (for ghosts: q = x - w while no coordinate changes at
  // fixed positions); h, ksum, mom (local) the field, K_i, and the first
  // moments M_i,a = sum_j k_ij del_ij,a of the virial; dh scattered changes
  int nmax;
  double *q, *xq, *w, *h, *ksum, *dh;
  double (*mom)[3];

  // coupled pairs of the current neighbor list: atom i's partners are
  // pj[first[i] .. first[i+1]) with k_ij pk (special factor included)
  std::vector<int> first, pj;
  std::vector<double> pk;
  // the coupled ghosts in the lists of local coupled atoms (the only ghosts
  // whose q is kept current between list builds; the others: x - w)
  std::vector<int> glist;
  std::vector<char> gmark;

  int valid;             // arrays and pairs match the current list and atoms
  int ghosts_current;    // ghost q equal their owners' q
  int ready;             // field_update since the last compute()
  int pending;           // field_advance: h to be computed (with the forces)
  int advanced;          // field_advance since the last field_update (xq not kept)
  double wbox[6];        // box (prd, tilts) when w was set: the ghosts' shifts
  int vir_valid;         // wvir holds this rank's share of the virial
  double wvir[3];        // sum over local i of (1/2) sum_j del_ij,a f_ij (f along dir)
  int comm_mode;

  // what the updates cost and how far the incremental field drifted
  bigint n_update, n_uniform, n_rebuild, n_nonuniform, n_advance, n_change, n_check;
  double drift_max, hscale_max;

  void allocate();
  void grow();
  void sync_ghosts();
  void box_now(double *box) const;
  bool box_changed() const;
  void rebuild(bool fresh_ghosts);
  void site_field(double **f);
  void drift_check();
  void skin_error(int i, int j, double du);
  double kval(int itype, int jtype, double rsq, const double *del) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
