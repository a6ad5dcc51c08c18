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
   FRICTION-EQ package as a LAMMPS plugin: registers every style of the
   package with a LAMMPS that was built with the PLUGIN package and
   without FRICTION-EQ (plugin load frictioneqplugin.so, or the folder
   of the file in LAMMPS_PLUGIN_PATH).  The list of styles is generated
   at configure time from the package's style headers (FixStyle(...),
   PairStyle(...), CommandStyle(...)), so the plugin carries exactly the
   styles that a build with the package compiled in has.
------------------------------------------------------------------------- */

#include "lammpsplugin.h"

#include "version.h"

#include "frictioneq_plugin_styles.h"    // generated: style headers, FEQ_PLUGIN_STYLES

using namespace LAMMPS_NS;

namespace {
template <class T> Fix *fix_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new T(lmp, narg, arg);
}
template <class T> Pair *pair_creator(LAMMPS *lmp)
{
  return new T(lmp);
}
template <class T> Command *command_creator(LAMMPS *lmp)
{
  return new T(lmp);
}

// registers one style at a time
struct Registrar {
  lammpsplugin_regfunc reg;
  void *lmp;
  void *handle;
  // LAMMPS keeps the record's strings as pointers: literals only
  void add(const char *style, const char *name, const char *info, lammpsplugin_factory1 *v1,
           lammpsplugin_factory2 *v2) const
  {
    lammpsplugin_t plugin;
    plugin.version = LAMMPS_VERSION;
    plugin.style = style;
    plugin.name = name;
    plugin.info = info;
    plugin.author = "FRICTION-EQ developers";
    if (v2) plugin.creator.v2 = v2;
    else plugin.creator.v1 = v1;
    plugin.handle = handle;
    (*reg)(&plugin, lmp);
  }
  template <class T> void fix(const char *name, const char *info) const
  {
    add("fix", name, info, nullptr, reinterpret_cast<lammpsplugin_factory2 *>(&fix_creator<T>));
  }
  template <class T> void pair(const char *name, const char *info) const
  {
    add("pair", name, info, reinterpret_cast<lammpsplugin_factory1 *>(&pair_creator<T>), nullptr);
  }
  template <class T> void command(const char *name, const char *info) const
  {
    add("command", name, info, reinterpret_cast<lammpsplugin_factory1 *>(&command_creator<T>),
        nullptr);
  }
};
}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  const Registrar r{(lammpsplugin_regfunc) regfunc, lmp, handle};
#define FEQ_REGISTER(kind, name, cls) r.kind<cls>(name, "FRICTION-EQ " #kind " " name);
  FEQ_PLUGIN_STYLES(FEQ_REGISTER)
#undef FEQ_REGISTER
}
