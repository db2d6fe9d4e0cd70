/* registry.c: finding and loading file-format plugins. */
#include "config.h"
#include "fileio/registry.h"

#include <dirent.h>
#include <fnmatch.h>
#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

void ms_registry_init(ms_registry *r) { memset(r, 0, sizeof *r); }

void ms_registry_free(ms_registry *r)
{
    for (size_t i = 0; i < r->n; i++) {
        if (r->handles[i]) dlclose(r->handles[i]);
        free(r->paths[i]);
        free(r->copies[i]);
    }
    free(r->copies);
    free(r->plugins);
    free(r->handles);
    free(r->paths);
    free(r->searched);
    ms_registry_init(r);
}

int ms_registry_add(ms_registry *r, const ms_plugin *p, void *handle, const char *from)
{
    if (ms_registry_find(r, p->name)) return 0;
    size_t cap = r->cap;
    if (ms_grow((void **)&r->plugins, &cap, r->n + 1, sizeof *r->plugins)) return -1;
    cap = r->cap;
    if (ms_grow((void **)&r->handles, &cap, r->n + 1, sizeof *r->handles)) return -1;
    cap = r->cap;
    if (ms_grow((void **)&r->paths, &cap, r->n + 1, sizeof *r->paths)) return -1;
    cap = r->cap;
    if (ms_grow((void **)&r->copies, &cap, r->n + 1, sizeof *r->copies)) return -1;
    r->cap = cap;
    r->copies[r->n] = NULL;
    r->plugins[r->n] = p;
    r->handles[r->n] = handle;
    r->paths[r->n] = ms_strdup(from ? from : "built in");
    r->n++;
    return 1;
}

const ms_plugin *ms_registry_upgrade(const ms_plugin *p, void **copy)
{
    *copy = NULL;
    if (!p || p->abi < MS_PLUGIN_ABI_MIN || p->abi > MS_PLUGIN_ABI) return NULL;
    if (p->abi >= 4) return p;
    ms_plugin *c = calloc(1, sizeof *c);   /* ABI 3 added only to the sink and the view */
    if (!c) return NULL;
    memcpy(c, p, p->abi >= 2 ? MS_PLUGIN_ABI3_SIZE : MS_PLUGIN_ABI1_SIZE);
    *copy = c;
    return c;
}

static void note_searched(ms_registry *r, const char *dir)
{
    size_t old = r->searched ? strlen(r->searched) : 0;
    char *s = realloc(r->searched, old + strlen(dir) + 3);
    if (!s) return;
    if (old) strcpy(s + old, ", ");
    else s[0] = '\0';
    strcat(s, dir);
    r->searched = s;
}

int ms_registry_load_file(ms_registry *r, const char *path, ms_error *err)
{
    void *h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        ms_error_set(err, "%s", dlerror());
        return -1;
    }
    ms_plugin_entry_fn entry;
    *(void **)&entry = dlsym(h, MS_PLUGIN_ENTRY_NAME);
    void *copy = NULL;
    const ms_plugin *p = ms_registry_upgrade(entry ? entry() : NULL, &copy);
    if (!p || !p->name) {
        ms_error_set(err, "not a molscope plugin of ABI %d to %d", MS_PLUGIN_ABI_MIN,
                     MS_PLUGIN_ABI);
        free(copy);
        dlclose(h);
        return -1;
    }
    int added = ms_registry_add(r, p, h, path);
    if (added <= 0) {
        free(copy);
        dlclose(h);
        return 0;
    }
    r->copies[r->n - 1] = copy;
    return 1;
}

int ms_registry_load_dir(ms_registry *r, const char *dir)
{
    DIR *d = opendir(dir);
    note_searched(r, dir);
    if (!d) return 0;
    int loaded = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t len = strlen(e->d_name);
        if (len < 4 || strcmp(e->d_name + len - 3, ".so") != 0) continue;
        char path[PATH_MAX];
        if (snprintf(path, sizeof path, "%s/%s", dir, e->d_name) >= (int)sizeof path) continue;
        ms_error err = {{0}};
        int rc = ms_registry_load_file(r, path, &err);
        if (rc < 0) fprintf(stderr, "molscope: plugin %s: %s\n", path, err.msg);
        else loaded += rc;
    }
    closedir(d);
    return loaded;
}

void ms_registry_load_default(ms_registry *r, const char *exe_path)
{
    const char *env = getenv("MOLSCOPE_PLUGINDIR");
    if (env && *env) {
        char *copy = ms_strdup(env), *save = NULL;
        for (char *dir = copy ? strtok_r(copy, ":", &save) : NULL; dir;
             dir = strtok_r(NULL, ":", &save))
            ms_registry_load_dir(r, dir);
        free(copy);
    }
    /* <prefix>/bin/molscope -> <prefix>/lib/molscope/plugins */
    if (exe_path) {
        char dir[PATH_MAX];
        snprintf(dir, sizeof dir, "%s", exe_path);
        char *slash = strrchr(dir, '/');
        if (slash) {
            *slash = '\0';
            char rel[PATH_MAX];
            if (snprintf(rel, sizeof rel, "%s/../lib/molscope/plugins", dir) < (int)sizeof rel) {
                char real[PATH_MAX];
                if (realpath(rel, real) && strcmp(real, MS_PLUGINDIR) != 0)
                    ms_registry_load_dir(r, real);
            }
        }
    }
    ms_registry_load_dir(r, MS_PLUGINDIR);
}

const ms_plugin *ms_registry_find(const ms_registry *r, const char *type)
{
    for (size_t i = 0; i < r->n; i++)
        if (strcasecmp(r->plugins[i]->name, type) == 0) return r->plugins[i];
    return NULL;
}

/* The plugin one of whose extension tokens `match` accepts, or NULL. */
static const ms_plugin *find_token(const ms_registry *r, const char *name,
                                   int (*match)(const char *tok, size_t len, const char *name))
{
    for (size_t i = 0; i < r->n; i++) {
        const char *list = r->plugins[i]->extensions;
        while (list && *list) {
            while (*list == ' ') list++;
            size_t len = strcspn(list, " ");
            if (len && match(list, len, name)) return r->plugins[i];
            list += len;
        }
    }
    return NULL;
}

/* An extension token ("pdb") against a file's extension, case-insensitively. */
static int match_ext(const char *tok, size_t len, const char *ext)
{
    return !memchr(tok, '*', len) && len == strlen(ext) && strncasecmp(tok, ext, len) == 0;
}

/* A name pattern ("POSCAR*") against a file's base name. */
static int match_glob(const char *tok, size_t len, const char *base)
{
    char pat[64];
    if (!memchr(tok, '*', len) || len >= sizeof pat) return 0;
    memcpy(pat, tok, len);
    pat[len] = '\0';
    return fnmatch(pat, base, 0) == 0;
}

const ms_plugin *ms_registry_for_path(const ms_registry *r, const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    const ms_plugin *p = dot && dot[1] ? find_token(r, dot + 1, match_ext) : NULL;
    return p ? p : find_token(r, base, match_glob);
}
