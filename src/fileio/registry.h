/* registry.h: the file-format plugins molscope knows: loaded from shared objects at run
 * time (from MOLSCOPE_PLUGINDIR, the install tree next to the program, and the configured
 * plugin directory), found by type name or by file extension. */
#ifndef MS_REGISTRY_H
#define MS_REGISTRY_H

#include "base/base.h"
#include "ms_plugin.h"

typedef struct ms_registry {
    const ms_plugin **plugins;
    void **handles;            /* dlopen handles (NULL for plugins added directly) */
    char **paths;              /* where each came from ("built in" for direct ones) */
    void **copies;             /* the host's full-size copy of an older ABI's description */
    size_t n, cap;
    char *searched;            /* the directories searched, for error messages */
} ms_registry;

void ms_registry_init(ms_registry *r);
void ms_registry_free(ms_registry *r);

/* Add a plugin description directly (tests, fuzzers). A plugin whose name is already known
 * is ignored: the first one found wins. */
int ms_registry_add(ms_registry *r, const ms_plugin *p, void *handle, const char *from);
/* The description of a plugin of ABI MS_PLUGIN_ABI_MIN..MS_PLUGIN_ABI as a full current one:
 * p itself when current, else a malloc'd zero-padded copy of its shorter struct (*copy is
 * set to it, for the caller to free). NULL for an ABI the host does not know. */
const ms_plugin *ms_registry_upgrade(const ms_plugin *p, void **copy);
/* Load the plugin of one shared object: 1 added, 0 when a plugin of its name is known
 * already (the first one found wins), -1 with err (dlopen's reason, which names the file,
 * or "not a molscope plugin ..."). */
int ms_registry_load_file(ms_registry *r, const char *path, ms_error *err);
/* Load every *.so of a directory. Returns the number loaded; bad files are skipped with a
 * line on stderr naming them. */
int ms_registry_load_dir(ms_registry *r, const char *dir);
/* The default search: MOLSCOPE_PLUGINDIR (colon-separated), <prefix>/lib/molscope/plugins
 * relative to the running program, then the configured directory. */
void ms_registry_load_default(ms_registry *r, const char *exe_path);

const ms_plugin *ms_registry_find(const ms_registry *r, const char *type);
/* The plugin for a file name's extension (".pdb" -> pdb), else for its base name by the
 * name patterns among the plugins' extensions ("POSCAR*": files without an extension);
 * NULL when none matches. */
const ms_plugin *ms_registry_for_path(const ms_registry *r, const char *path);

#endif
