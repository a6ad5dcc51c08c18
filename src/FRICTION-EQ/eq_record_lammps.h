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
   FRICTION-EQ package for LAMMPS: the global restart records of the
   package's fixes (lib/eq_record.h) on the LAMMPS side: written by rank 0,
   read back with the signature of the re-specified fix, and the errors
   that name the keyword a re-specified fix changed.  Include from .cpp
   files only.
------------------------------------------------------------------------- */

#ifndef LMP_EQ_RECORD_LAMMPS_H
#define LMP_EQ_RECORD_LAMMPS_H

#include "eq_distribution.h"
#include "eq_record.h"

#include "comm.h"
#include "error.h"
#include "fix.h"
#include "lammps.h"

#include <cstdio>
#include <string>
#include <vector>

namespace LAMMPS_NS {
namespace EQRecord {

  // canonical text of a number and of a distribution for a signature (a
  // table's numbers enter through its moments)
  inline std::string number(double v) { return fmt::format("{:.17g}", v); }
  inline std::string distribution(const feq::DistributionSpec &spec)
  {
    if (!spec.dist) return "none";
    return fmt::format("{}|{:.17g}|{:.17g}", spec.text, spec.dist->mean(), spec.dist->variance());
  }

  inline void write(LAMMPS *lmp, FILE *fp, const std::vector<double> &values,
                    const feq::Signature &sig)
  {
    const std::vector<double> rec = feq::pack_record(values, sig);
    if (lmp->comm->me == 0) {
      const int size = static_cast<int>(rec.size() * sizeof(double));
      fwrite(&size, sizeof(int), 1, fp);
      fwrite(rec.data(), sizeof(double), rec.size(), fp);
    }
  }

  // the values of the record in buf, or an error naming the fix and what
  // is wrong: the keyword that differs from the writing run's (stored:
  // what the fix keeps per atom, e.g. "contacts"), or an unusable record
  inline std::vector<double> read(LAMMPS *lmp, const Fix *fix, const char *buf, int nvalues,
                                  const feq::Signature &sig, const char *stored)
  {
    try {
      return feq::unpack_record(reinterpret_cast<const double *>(buf), nvalues, sig);
    } catch (const feq::RecordError &e) {
      const std::string &kw = e.keyword();
      if (!kw.empty()) {
        lmp->error->all(FLERR, "Fix {} {}: {} differs from that of the run that wrote the restart "
                               "file: the stored {} were made with the other {}; re-specify {} as "
                               "in that run (or define the fix under another ID to start afresh)",
                        fix->id, fix->style, kw, stored, kw, kw);
      }
      lmp->error->all(FLERR, "Fix {} {}: the restart file's record of this fix is unusable: {}",
                      fix->id, fix->style, e.what());
    }
    return {};
  }

}    // namespace EQRecord
}    // namespace LAMMPS_NS

#endif
