/* -*- c++ -*- ----------------------------------------------------------
   FRICTION-EQ package for LAMMPS: the interfaces between its styles.

   No style of the package includes another's class: they meet here.
   (The destructors are protected and not virtual: a style is never
   deleted through these interfaces, and LAMMPS' own base classes differ
   between versions in the exception specification of theirs.)

   - EQCoordinateSource: a fix whose atoms carry one coordinate q_i along
     a direction (fix eq/contacts: the contacts' stretches; fix
     eq/substrate: the blocks' displacements).
   - EQElasticField: the elastic interaction h_i = sum_j k_ij (q_i - q_j)
     between the atoms of a source (pair eq/elastic).  The field owns h_i
     and K_i = sum_j k_ij; the pair style applies -h_i along the source's
     direction.
   - EQEventSource: a fix that can tell how far a rigid slider may advance
     before the next event (fix eq/contacts, for fix eq/quasistatic).

   Control flows one way: the source drives every force evaluation.  Before
   the pair style computes (setup_pre_force, pre_force, min_pre_force, or
   pre_force_respa at the pair's level) it hands the field the coordinates
   of its local atoms at the current positions (field_update), or, for
   sources whose coordinates move with their atoms (blocks), lets the field
   follow the positions (field_advance); after
   breaks at fixed positions it hands it the changes (field_change).  The
   pair style's compute() only reads what the field holds: it never calls
   the source.
------------------------------------------------------------------------- */

#ifndef LMP_EQ_FIELD_H
#define LMP_EQ_FIELD_H

namespace LAMMPS_NS {

class EQCoordinateSource {
 protected:
  ~EQCoordinateSource() = default;    // not deleted through this interface

 public:
  // direction of the coordinates (0, 1, 2) and group bit of the coupled atoms
  virtual int source_dir() const = 0;
  virtual int source_groupbit() const = 0;
  // "fix ID eq/contacts", for messages
  virtual const char *source_name() const = 0;
  // true: the distance between two coupled atoms is that of their sites
  // (position minus coordinate along dir: blocks that move around fixed
  // lattice sites); false: that of the atoms (contacts on a slider)
  virtual bool source_site_distance() const = 0;
};

class EQElasticField {
 protected:
  ~EQElasticField() = default;    // not deleted through this interface

 public:
  // the source this field couples (found and checked by the field's init)
  virtual const EQCoordinateSource *field_source() const = 0;
  // coordinates q[i] of all local atoms at the current positions (NaN: not
  // coupled); h and K follow.  full: recompute everything (the set of
  // coupled atoms changed)
  virtual void field_update(const double *q, bool full = false) = 0;
  // the coordinates changed only through the motion of the atoms since the
  // last field_update (x - q along dir fixed for every atom: blocks between
  // two list builds): the field follows the positions itself, without an
  // array.  false: it needs field_update now (a list build, a new run, a
  // drift check); all ranks answer alike
  virtual bool field_advance() = 0;
  // atoms list[0..n) changed their coordinate by dq[list[m]] at fixed
  // positions (breaks): h and K of every partner follow
  virtual void field_change(const int *list, int n, const double *dq) = 0;
  // h_i and K_i of local atoms (valid after field_update or field_advance;
  // after field_advance the field may compute h only when it is asked for
  // or when the pair style computes its forces)
  virtual const double *field_h() = 0;
  virtual const double *field_k() const = 0;
  // end of a run: report what the incremental updates cost and their drift
  virtual void field_report() = 0;
};

class EQEventSource {
 protected:
  ~EQEventSource() = default;    // not deleted through this interface

 public:
  // direction and group bit of the atoms whose advance drives the events
  virtual int event_dir() const = 0;
  virtual int event_groupbit() const = 0;
  virtual const char *event_name() const = 0;
  // advance of all atoms along +dir that brings the first one to its
  // event; global minimum over ranks (infinite: no event can happen)
  virtual double next_event() = 0;
  // relative tolerance of the event test (the driver lands exactly on it)
  virtual void set_event_tolerance(double tol) = 0;
};

}    // namespace LAMMPS_NS

#endif
