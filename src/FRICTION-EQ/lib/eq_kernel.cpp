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
   FRICTION-EQ: interaction kernel k(r) (see eq_kernel.h)
------------------------------------------------------------------------- */

#include "eq_kernel.h"

#include "eq_distribution.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace feq {

double Kernel::range() const
{
  if (kind == CROSSOVER) return std::numeric_limits<double>::infinity();
  if (kind == TABLE) return r.back();
  return 0.0;
}

double Kernel::eval_table(double rr, double cos2phi) const
{
  const size_t n = r.size();
  if (rr > r[n - 1]) return 0.0;
  double a0, a2;    // r k0 and r k2 at rr
  if (rr <= r[0]) {
    a0 = r[0] * k0[0];
    a2 = k2.empty() ? 0.0 : r[0] * k2[0];
  } else {
    const size_t hi = std::upper_bound(r.begin(), r.end(), rr) - r.begin();
    const size_t j = hi >= n ? n - 1 : hi;
    const size_t i = j - 1;
    const double t = (rr - r[i]) / (r[j] - r[i]);
    a0 = (1.0 - t) * r[i] * k0[i] + t * r[j] * k0[j];
    a2 = k2.empty() ? 0.0 : (1.0 - t) * r[i] * k2[i] + t * r[j] * k2[j];
  }
  return (a0 + a2 * cos2phi) / rr;
}

Kernel make_crossover(double ftilde, double lambda)
{
  if (!(ftilde >= 0.0) || !std::isfinite(ftilde))
    throw SpecError("ftilde must be >= 0 (got " + std::to_string(ftilde) + ")");
  if (!(lambda > 0.0) || !std::isfinite(lambda))
    throw SpecError("lambda_c must be > 0 (got " + std::to_string(lambda) + ")");
  Kernel k;
  k.kind = Kernel::CROSSOVER;
  k.ftilde = ftilde;
  k.lambda = lambda;
  k.source = "crossover";
  return k;
}

namespace {
// a number of a kernel table, by the rules of threshold and substrate
// tables (feq::parse_number: the whole token, finite, normal or 0); a
// subnormal or out-of-range value is named with its cause
double table_number(const std::string &s, const std::string &where)
{
  try {
    return parse_number(s);
  } catch (const NumberError &e) {
    throw SpecError(where + ": " + e.what());
  } catch (const SpecError &) {
    throw SpecError(where + ": not a finite number");
  }
}
}    // namespace

Kernel read_kernel_table(const std::string &text, const std::string &path,
                         const std::string &keyword)
{
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  bool found = false;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ws(line);
    std::string word;
    if ((ws >> word) && word == keyword) {
      found = true;
      break;
    }
  }
  if (!found)
    throw SpecError("keyword '" + keyword + "' not found in table file '" + path + "'");
  auto where = [&]() { return "table file '" + path + "' line " + std::to_string(lineno); };

  long n = -1;
  bool aniso = false;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ws(line);
    std::string word, flag, extra;
    if (!(ws >> word) || word[0] == '#') continue;
    if (word != "N" || !(ws >> n) || n < 2)
      throw SpecError(where() + ": expected 'N <count> [aniso]' with count >= 2 after keyword '" +
                      keyword + "'");
    if (ws >> flag) {
      if (flag != "aniso" || (ws >> extra))
        throw SpecError(where() + ": unknown flag '" + flag + "' after 'N " + std::to_string(n) +
                        "'; allowed: aniso");
      aniso = true;
    }
    break;
  }
  if (n < 0)
    throw SpecError("table file '" + path + "': missing 'N <count>' after '" + keyword + "'");

  Kernel k;
  k.kind = Kernel::TABLE;
  k.source = path + " " + keyword;
  const size_t ncol = aniso ? 4 : 3;
  while (static_cast<long>(k.r.size()) < n && std::getline(in, line)) {
    ++lineno;
    std::istringstream ws(line);
    std::vector<std::string> tok;
    std::string t;
    while (ws >> t) tok.push_back(t);
    if (tok.empty() || tok[0][0] == '#') continue;
    char *end = nullptr;
    const long idx = std::strtol(tok[0].c_str(), &end, 10);
    if (*end != '\0') break;    // next section: too few points
    if (tok.size() != ncol)
      throw SpecError(where() + (aniso ? ": expected 'index r k0 k2'" : ": expected 'index r k'"));
    if (idx != static_cast<long>(k.r.size()) + 1)
      throw SpecError(where() + ": index " + tok[0] + " out of sequence (expected " +
                      std::to_string(k.r.size() + 1) + ")");
    const double rv = table_number(tok[1], where());
    const double kv = table_number(tok[2], where());
    const double k2v = aniso ? table_number(tok[3], where()) : 0.0;
    if (!(rv > 0.0)) throw SpecError(where() + ": r must be > 0");
    if (!k.r.empty() && !(rv > k.r.back()))
      throw SpecError(where() + ": r must increase strictly");
    k.r.push_back(rv);
    k.k0.push_back(kv);
    if (aniso) k.k2.push_back(k2v);
  }
  if (static_cast<long>(k.r.size()) < n)
    throw SpecError("table file '" + path + "' section '" + keyword + "': expected " +
                    std::to_string(n) + " points, found " + std::to_string(k.r.size()));
  // a point line after the last one: the section has more points than its
  // 'N n' line says (they would be dropped silently)
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ws(line);
    std::string a;
    if (!(ws >> a) || a[0] == '#') continue;
    char *end = nullptr;
    std::strtol(a.c_str(), &end, 10);
    if (end != a.c_str() && *end == '\0')
      throw SpecError("table file '" + path + "' section '" + keyword + "': more points than 'N " +
                      std::to_string(n) + "' says (" + where() + ")");
    break;    // the next section's keyword
  }
  return k;
}

}    // namespace feq
