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
   FRICTION-EQ package for LAMMPS: package-wide set-up

   LAMMPS 29 Sep 2021 built with LAMMPS_EXCEPTIONS (which this build needs
   for its error tests) reports an error of a single rank (Error::one) to
   the buffered stdout and then calls MPI_Abort from main() without
   flushing it: when the output goes to a pipe or a file, the message is
   lost and the user sees only "MPI_ABORT was invoked".  Line-buffering
   stdout when the library is loaded makes every message reach the user
   (later LAMMPS versions flush before aborting).  The cost is one write
   per output line.
------------------------------------------------------------------------- */

#include <cstdio>

namespace {
struct LineBufferedStdout {
  LineBufferedStdout() { std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ); }
};
const LineBufferedStdout line_buffered_stdout;
}    // namespace
