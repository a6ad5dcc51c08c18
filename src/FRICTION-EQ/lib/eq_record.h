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
   FRICTION-EQ package: the global restart record of a package fix.
   LAMMPS-free.

   A record is a row of doubles:

     MAGIC FORMAT nv v_1 .. v_nv ns s_1 .. s_ns

   v: the fix's values (breaks so far, the stage, ...); s: its signature,
   one 52-bit hash (exact in a double) per keyword that shapes the
   per-atom state the fix stores (stiffness, thresholds, direction,
   substrate shape, grid, ...).  A fix re-specified after read_restart
   compares its signature with the stored one keyword by keyword, so that
   a changed keyword is named instead of mixing the stored state with the
   new arguments; a record that is not one (garbled, another format)
   stops with an error before anything of it is used.
------------------------------------------------------------------------- */

#ifndef FEQ_RECORD_H
#define FEQ_RECORD_H

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace feq {

// an unusable record; keyword(): the keyword whose signature differs when
// only that is off (else empty)
class RecordError : public std::runtime_error {
 public:
  explicit RecordError(const std::string &what, std::string keyword = std::string()) :
      std::runtime_error(what), kw(std::move(keyword))
  {
  }
  const std::string &keyword() const { return kw; }

 private:
  std::string kw;
};

// "FEQE" and the layout version
constexpr double RECORD_MAGIC = 1178947909.0;
constexpr double RECORD_FORMAT = 1.0;

// FNV-1a of the text, cut to 52 bits: an integer a double holds exactly
inline double hash52(const std::string &text)
{
  uint64_t h = 1469598103934665603ULL;
  for (const unsigned char c : text) h = (h ^ c) * 1099511628211ULL;
  return static_cast<double>(h & ((1ULL << 52) - 1));
}

// what shapes a fix's stored state, keyword by keyword
struct Signature {
  std::vector<std::string> keywords;
  std::vector<double> hashes;
  void add(const std::string &keyword, const std::string &canonical)
  {
    keywords.push_back(keyword);
    hashes.push_back(hash52(canonical));
  }
};

inline std::vector<double> pack_record(const std::vector<double> &values, const Signature &sig)
{
  std::vector<double> r = {RECORD_MAGIC, RECORD_FORMAT, static_cast<double>(values.size())};
  r.insert(r.end(), values.begin(), values.end());
  r.push_back(static_cast<double>(sig.hashes.size()));
  r.insert(r.end(), sig.hashes.begin(), sig.hashes.end());
  return r;
}

// the values of a record with nvalues values and a signature of
// sig.hashes.size() keywords; RecordError when it is not such a record,
// naming the first keyword whose hash differs when only that is off
// (its keyword())
inline std::vector<double> unpack_record(const double *buf, int nvalues, const Signature &sig)
{
  if (buf[0] != RECORD_MAGIC || buf[1] != RECORD_FORMAT)
    throw RecordError("the record is not one this version of the package writes (garbled, or "
                      "written by another version)");
  if (buf[2] != static_cast<double>(nvalues))
    throw RecordError("the record holds " + std::to_string(buf[2]) + " values where " +
                      std::to_string(nvalues) + " are expected (garbled, or written by another "
                      "version)");
  const double *s = buf + 3 + nvalues;
  const int ns = static_cast<int>(sig.hashes.size());
  if (s[0] != static_cast<double>(ns))
    throw RecordError("the record's signature has " + std::to_string(s[0]) + " entries where " +
                      std::to_string(ns) + " are expected (garbled, or written by another "
                      "version)");
  for (int k = 0; k < ns; k++)
    if (s[1 + k] != sig.hashes[k])
      throw RecordError("the record's " + sig.keywords[k] + " differs", sig.keywords[k]);
  return std::vector<double>(buf + 3, buf + 3 + nvalues);
}

}    // namespace feq

#endif
