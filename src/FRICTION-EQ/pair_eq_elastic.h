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

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
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
  const char *eq_name() const override { return "pair_style eq/elastic"; }
  int eq_instance() const override { return instance_me; }
  int field_source_instance() const override;
  EQFieldView field_view() override;
  void field_report() override;

 protected:
  double cut_global;
  int check_every;             // drift check every this many updates (0: never)
  double **cut, **cutsq_in;    // cutoffs; squared with a 1e-12 relative margin
  double **ftilde, **lambda;   // crossover coefficients (for extract)
  int **kidx;                  // kernel of a type pair (index into kernels)
  int **mixed;                 // 1: the kernel of a type pair was mixed by init_one
  std::vector<feq::Kernel> kernels;
  int anisotropic;
  bigint ncoeff;               // pair_coeff commands so far
  bigint ncoeff_init;          // ... at the last init_style()

  // the coordinate source of this run (found by init_style)
  EQHeld<EQCoordinateSource> source;
  std::string source_label;    // its name, for messages after it is gone
  int idir;
  bool site_distance;

  // per-atom arrays (local and ghost unless noted), valid for the key
  // below: q the coordinates; xq the positions at the last update; w =
  // x - q along dir (constant while the coordinates change only by the
  // motion of the atoms; for contacts read of ghosts only, so that a
  // change set updates it for blocks only); h, ksum, mom (local) the
  // field, K_i, and the first moments M_i,a = sum_j k_ij del_ij,a of the
  // virial; dh the ghosts' shares of a change set, dk those of K (a
  // change of members)
  int nmax;
  double *q, *w, *h, *ksum, *dh, *dk;
  double (*xq)[3];
  double (*mom)[3];
  // the spread of the displacements since xq (rigid translation test)
  struct Spread {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double xmax = 0.0;
    // atoms count as moved rigidly when their displacements differ by less
    // than this many units of rounding of the positions
    static constexpr double ULPS = 8.0;
    // add() and rigid() are defined here to be inlined into the update
    // loops: a local Spread whose address never leaves the function keeps
    // lo, hi and xmax in registers (the stores to x0 cannot reach it).
    // add(): the displacement x - x0 of one atom (x0 then follows x), and
    // the size of its coordinates (for the rounding)
    void add(const double *x, double *x0)
    {
      for (int a = 0; a < 3; a++) {
        const double del = x[a] - x0[a];
        lo[a] = del < lo[a] ? del : lo[a];
        hi[a] = del > hi[a] ? del : hi[a];
        const double ax = std::fabs(x[a]);
        xmax = ax > xmax ? ax : xmax;
        x0[a] = x[a];
      }
    }
    // all atoms moved by the same vector, to the rounding of the positions
    bool rigid() const
    {
      const double eps = std::numeric_limits<double>::epsilon();
      for (int a = 0; a < 3; a++) {
        if (hi[a] < lo[a]) continue;    // no atom
        const double tol = ULPS * eps * (xmax + std::fmax(std::fabs(lo[a]), std::fabs(hi[a])));
        if (hi[a] - lo[a] > tol) return false;
      }
      return true;
    }
  };

  // coupled pairs of the current neighbor list: atom i's partners are
  // pj[first[2i] .. first[2i+1]) with k_ij pk (special factor included).
  // Contacts: the pairs of every atom of the source's group (member_bit),
  // coupled now or not (q NaN: a contact waiting to re-form), so that
  // contacts can join and leave the field between list builds; the sums
  // skip the uncoupled.  Blocks (member_bit 0): the coupled atoms only
  std::vector<int> first, pj;
  std::vector<double> pk;
  // 1 where every partner of row i is a local atom (the scatter's loop
  // without the test for ghosts); written with the lists
  std::vector<char> rowlocal;
  int member_bit;
  // the coupled ghosts in the lists of local coupled atoms (the only ghosts
  // whose q is kept current between list builds; the others: x - w)
  std::vector<int> glist;
  std::vector<char> gmark;

  // The validity of the field (h, K, the moments, the cached pairs, q, w):
  // the key it was computed for.  Any change of it recomputes everything
  // from the source's coordinates (see valid_for() and the doc page).
  struct Key {
    int source;          // instance of the source
    bigint lastcall;     // step of the last neighbor list build
    int nlocal, nghost;
    double box[9];       // boxlo, prd, tilts: the ghosts' periodic shifts
    bool operator==(const Key &o) const;
  };
  Key key;
  bool key_set;         // the field was computed for `key`
  // within a key, what of the source the field has followed: its force
  // evaluation (positions), its version (changes at fixed positions), the
  // version the ghosts' q and w hold, and the evaluation of the last
  // compute(); the evaluation the field was recomputed in after a build
  bigint eval_seen, version_seen, ghost_version, eval_computed, eval_built;
  int pending;          // blocks: h to be computed from q = x - w (with the forces)
  bigint nfield;        // changes of h so far
  bigint vir_at;        // nfield when wvir was computed (-1: never)
  bool mom_valid;       // mom holds for the coupled set (false after a change of members)
  double wvir[3];       // sum over local i of (1/2) sum_j del_ij,a f_ij (f along dir)
  // changes (i, dq_i) scattered since, not yet in wvir (part of it while
  // vir_at == nfield; cleared when wvir is computed)
  std::vector<std::pair<int, double>> vir_pending;
  // what the next forward/reverse communication carries: q of all
  // ghosts, q of the changed atoms, or the scattered shares of dh
  enum CommMode { COMM_ALL, COMM_CHANGED, COMM_SHARES, COMM_MEMBERS };
  CommMode comm_mode;
  // a change set's scatter: the ghosts it gave a share of dh (flagged in
  // tmark; dh and tmark are zero outside a scatter), in index order for
  // the sparse reverse communication (gsorted false: to be sorted), and
  // the local atoms whose h it changed (repeats possible; the first
  // nhchanged entries), valid while nfield == changed_at
  std::vector<int> gtouched, hchanged;
  int nhchanged = 0;
  void add_changed(int j)
  {
    if (static_cast<std::size_t>(nhchanged) == hchanged.size())
      hchanged.resize(std::max<std::size_t>(64, 2 * hchanged.size()));
    hchanged[nhchanged++] = j;
  }
  std::vector<char> tmark;
  bool gsorted;
  bigint changed_at;
  // the atoms whose q changed since the ghosts were last synchronized
  // (local: scattered; ghost: received), flagged in cmark (zero outside)
  std::vector<int> csync;
  std::vector<char> cmark;
  // a change of members: its local atoms, and the ghosts that joined in
  // it (received), flagged in smark (zero outside); smarked lists them
  std::vector<int> smarked, joined;
  std::vector<char> smark;
  bool smark_ghosts;    // unpack_forward_comm() flags the ghosts that join

  // what the updates cost and how far the incremental field drifted
  bigint n_update, n_uniform, n_rebuild, n_nonuniform, n_advance, n_change, n_check;
  bigint n_joined;    // recomputed for a new set of coupled atoms (not followed incrementally)
  bigint n_members;   // atoms that joined or left the field, followed incrementally
  double drift_max, hscale_max, kdrift_max, kscale_max;

  void allocate();
  void grow();
  EQCoordinateSource *live_source();
  Key key_now() const;
  void refresh();
  void recompute(EQCoordinateSource *src);
  void follow(EQCoordinateSource *src, bool count = true);
  void update(EQCoordinateSource *src, const EQChangeSet *set, bool count);
  int expected_changes(const double *qin) const;
  void scatter(const EQChangeSet &set);
  void change_members(EQCoordinateSource *src, const EQChangeSet &set, bool moved);
  void member_error(int i, const char *what);
  void sync_mark(int i)    // q[i] changed: sent to its ghosts by sync_changed()
  {
    if (cmark[i]) return;
    cmark[i] = 1;
    csync.push_back(i);
  }
  void mark_member(int i)
  {
    if (smark[i]) return;
    smark[i] = 1;
    smarked.push_back(i);
  }
  void member_share(int j, double kj, double m);
  void sync_changed();
  void ghost_share(int j, double v)
  {
    if (!tmark[j]) {
      tmark[j] = 1;
      gtouched.push_back(j);
      gsorted = false;
    }
    dh[j] += v;
  }
  void clear_changed();
  void sync_ghosts();
  void rebuild(bool fresh_ghosts);
  void site_field(double **f);
  void drift_check(EQCoordinateSource *src, const EQChangeSet *set);
  void virial_now();
  template <bool MOMENTS> void virial_pairs();
  void virial_pending();
  void skin_error(int i, int j, double du);
  void overlap_error(int i, int j);
  double kval(int itype, int jtype, double rsq, const double *del) const;
};

}    // namespace LAMMPS_NS

#endif
#endif
