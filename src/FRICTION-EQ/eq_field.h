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
   FRICTION-EQ package for LAMMPS: the interfaces between its styles.

   No style of the package includes another's class: they meet here.
   (The destructors are protected and not virtual: a style is never
   deleted through these interfaces, and LAMMPS' own base classes differ
   between versions in the exception specification of theirs.)

   Ownership.  Every piece of state has one owner; the others read it
   through the calls below, and pull what they need when they need it:

   - EQCoordinateSource (fix eq/contacts, eq/substrate, eq/meso) owns the
     coordinates q_i of its atoms along its direction (the contacts'
     stretches and anchors, the blocks' sites and displacements), the
     break engine and the avalanche.  It counts its force evaluations and
     the versions of its coordinates, and keeps the last change set.
   - EQElasticField (pair_style eq/elastic) owns h_i = sum_j k_ij (q_i -
     q_j), K_i = sum_j k_ij, the cached pairs and the ghosts' coordinates.
     It reads the source's coordinates and change sets when it needs them
     (field_view(), its compute()); it never writes into the source.
   - EQEventDriver (fix eq/quasistatic) owns the slider's advance; it
     reads the distance to the next event from an EQEventSource (fix
     eq/contacts), which reads the driver's breaking tolerance in its own
     init().

   Partners are found afresh in every init() (eq_link.h): a style holds a
   partner's address and Fix/Pair instance number for that run (and the
   parts of it that follow without init: run N pre no every M), and finds
   the partner again and compares both before each use, so that a partner
   removed or replaced meanwhile ends in an error naming both styles,
   never in a dangling access.
------------------------------------------------------------------------- */

#ifndef LMP_EQ_FIELD_H
#define LMP_EQ_FIELD_H

#include "lmptype.h"

namespace LAMMPS_NS {

// coordinates that changed at fixed positions (the breaks of one
// avalanche round): local atoms list[0..n), by dq[list[m]].  exact: the
// source found every change, on every rank, small enough for an
// incremental update to follow to rounding (false: the field recomputes;
// the verdict is the same on all ranks, so that all take the same path).
// members: instead, the atoms of list joined the coupled set (their
// coordinate, source_coordinates(), is no longer NaN) or left it (it is
// NaN now): contacts that wait to re-form after a break, and re-form
// (dq unused); exact then says that every coordinate involved is small
// enough for the partners' fields to follow it incrementally
struct EQChangeSet {
  const int *list = nullptr;
  int n = 0;
  const double *dq = nullptr;
  bool exact = true;
  bool members = false;
};

class EQCoordinateSource {
 protected:
  ~EQCoordinateSource() = default;    // not deleted through this interface

 public:
  // "fix ID eq/contacts", for messages; the Fix's instance number (unique
  // for the life of the process)
  virtual const char *eq_name() const = 0;
  virtual int eq_instance() const = 0;
  // direction of the coordinates (0, 1, 2) and group bit of the coupled atoms
  virtual int source_dir() const = 0;
  virtual int source_groupbit() const = 0;
  // true: the distance between two coupled atoms is that of their sites
  // (position minus coordinate along dir: blocks around fixed lattice
  // sites), and the coordinates move with the positions only (q = x - w
  // with w fixed between list builds); false: that of the atoms (contacts
  // on a slider)
  virtual bool source_site_distance() const = 0;
  // force evaluations begun (setup, step, minimizer evaluation, r-RESPA
  // level): the positions may have changed since the previous value
  virtual bigint source_evaluation() const = 0;
  // changes of the coordinates at fixed positions (breaks, contacts
  // detached) within an evaluation
  virtual bigint source_version() const = 0;
  // the coordinates of the local atoms now (NaN: not coupled)
  virtual const double *source_coordinates() = 0;
  // the change from version `since` to the current one, if it is one
  // change set at fixed positions; false: recompute from the coordinates.
  // In a set of members every atom joins or leaves (a member whose
  // coordinate changes otherwise makes the set not exact); a set of
  // joiners only may also come with a new evaluation: the other atoms
  // moved with the positions, those in it joined there
  virtual bool source_changes(bigint since, EQChangeSet &set) const = 0;
};

// what a field holds for the local atoms (valid until the source changes)
struct EQFieldView {
  const double *h = nullptr;    // h_i
  const double *k = nullptr;    // K_i = sum_j k_ij
  // the local atoms whose h_i changed in the field's last update, if that
  // update was a change set of the source (an atom may appear more than
  // once; nullptr: the update was of another kind and any h_i may have
  // changed).  A reader that looked before that update, and not since,
  // finds every change here.
  const int *changed = nullptr;
  int nchanged = 0;
};

class EQElasticField {
 protected:
  ~EQElasticField() = default;    // not deleted through this interface

 public:
  // "pair_style eq/elastic", the Pair's instance number, and that of the
  // source it couples (set by its init_style(), which runs before the
  // fixes' init())
  virtual const char *eq_name() const = 0;
  virtual int eq_instance() const = 0;
  virtual int field_source_instance() const = 0;
  // h and K for the source's coordinates at the current positions: the
  // field pulls from the source what changed since it last looked
  virtual EQFieldView field_view() = 0;
  // end of a run (the source's post_run): what the updates cost, and
  // their drift against recomputed fields
  virtual void field_report() = 0;
};

class EQEventSource {
 protected:
  ~EQEventSource() = default;    // not deleted through this interface

 public:
  virtual const char *eq_name() const = 0;
  virtual int eq_instance() const = 0;
  // direction and group bit of the atoms whose advance drives the events
  virtual int event_dir() const = 0;
  virtual int event_groupbit() const = 0;
  // advance of all atoms along +dir that brings the first one to its
  // event; global minimum over ranks (infinite: no event can happen)
  virtual double next_event() = 0;
};

class EQEventDriver {
 protected:
  ~EQEventDriver() = default;    // not deleted through this interface

 public:
  virtual const char *eq_name() const = 0;
  virtual int eq_instance() const = 0;
  // the fix ID of the event source this driver advances
  virtual const char *driver_target() const = 0;
  // relative tolerance of the source's event test (the driver lands
  // exactly on an event, up to rounding)
  virtual double driver_tolerance() const = 0;
};

// a partner held for one run (eq_link.h finds it again before each use):
// its address as interface T and as the Fix or Pair it is, and its
// instance number
template <class T> class EQHeld {
 public:
  void set(T *p, const void *style)
  {
    ptr = p;
    raw = p ? style : nullptr;
    inst = p ? p->eq_instance() : -1;
  }
  void clear() { set(nullptr, nullptr); }
  T *get() const { return ptr; }
  const void *address() const { return raw; }
  int instance() const { return inst; }
  explicit operator bool() const { return ptr != nullptr; }
  // t (a live style found by address) is the held one: same object, same instance
  T *same(T *t) const { return (t && t == ptr && t->eq_instance() == inst) ? t : nullptr; }

 private:
  T *ptr = nullptr;
  const void *raw = nullptr;
  int inst = -1;
};

}    // namespace LAMMPS_NS

#endif
