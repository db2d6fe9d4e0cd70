/* args.h: the argument layer of every Tcl command: how a command is declared, and how its
 * words are matched, counted, read and refused. Someone adding a command reads only this.
 *
 * 1. A command is a table. Each entry gives a subcommand word, its handler, how many words
 *    may follow the subcommand word (min, max; MS_ARGS_ANY for no limit) and what they are
 *    (the usage, "" when there are none):
 *
 *        static const ms_subcmd frob_table[] = {
 *            {"list", frob_list, 0, 0, ""},
 *            {"rename", frob_rename, 2, 2, "<old> <new>"},
 *            {"add", frob_add, 1, MS_ARGS_ANY, "<name> ?<option> <value> ...?"},
 *            {NULL, NULL, 0, 0, NULL}};
 *        ms_cmdset_create(app, "frob", frob_table);          (commands.h)
 *
 *    A command without subcommands is one entry named like the command, made with
 *    ms_cmd_create (commands.h); its counts are of the words after the command.
 *
 * 2. The dispatcher finds the word with the keyword rule (3), checks the count once and
 *    calls the handler with all the words (objv[0] the command, objv[1] the subcommand).
 *    Its errors are made from the table:
 *
 *        frob: missing subcommand: must be list, rename, or add
 *        frob: unknown subcommand "lst": must be list, rename, or add
 *        frob rename: wrong # args: usage: frob rename <old> <new>
 *        frob list: takes no arguments
 *
 *    A handler never counts its words against the table again. Where the words have a
 *    shape the two counts cannot say (pairs, "1 or 3"), it returns ms_args_usage(interp)
 *    for the same message. Inside a handler, ms_args_where() is "frob rename": start every
 *    error with it (or the same words): "<command> <subcommand>: what is wrong".
 *    A word that picks among more subcommands (color change rgb|rgblist|namelist) is one
 *    more table, dispatched from the handler with ms_args_dispatch.
 *
 * 3. Keywords: ms_word_eq (base.h) is the one comparison of a word with a name: VMD's,
 *    case-insensitive over at most 15 characters (NewCartoon = newcartoon). Never strcmp or
 *    strcasecmp a keyword. A word that picks one of several values (by|to, x|y|z, a
 *    projection) is read with ms_arg_choice from a NULL-ended list of names; a word no name
 *    matches is refused as "bad value 'x' for <what>: must be a, b, or c". To find a word
 *    in a table without an error, ms_args_find.
 *
 * 4. Values: ms_arg_int, ms_arg_long, ms_arg_double, ms_arg_float, ms_arg_bool (on/off,
 *    yes/no, true/false, 1/0 and whatever else Tcl reads as a boolean), ms_arg_vec3, and
 *    ms_arg_long_or for a number or a word (frame <n>|first|last|now).
 *    A refused value reads "frob add: bad value 'x' for radius: must be a number".
 *
 * 5. Option lists ("-option value ..." or "key value ..."): a table of ms_opt saying, for
 *    each name, the type, where in the caller's struct the value goes and its bounds; one
 *    call to ms_args_options parses the words, refusing unknown options (`unknown option
 *    "x": must be ...`) and bad values as above (display's settings table, generalised):
 *
 *        typedef struct frob_args { float res; int quality, all; } frob_args;
 *        static const ms_opt frob_options[] = {
 *            {"-res", MS_OPT_FLOAT, offsetof(frob_args, res), 0, 0, MS_OPT_ABOVE, NULL},
 *            {"-quality", MS_OPT_INT, offsetof(frob_args, quality), 0, 3,
 *             MS_OPT_MIN | MS_OPT_MAX, NULL},
 *            {"-all", MS_OPT_FLAG, offsetof(frob_args, all), 0, 0, 0, NULL},
 *            {NULL, 0, 0, 0, 0, 0, NULL}};
 *        frob_args a = {1.0f, 3, 0};                         (the defaults)
 *        if (ms_args_options(interp, objc, objv, 3, frob_options, &a, NULL)) return TCL_ERROR;
 *
 * Everything here reports errors in the interpreter and returns TCL_ERROR (the readers of
 * section 3 and 4 only test the word when interp is NULL); TCL_OK otherwise. */
#ifndef MS_ARGS_H
#define MS_ARGS_H

#include <stddef.h>
#include <tcl.h>

#include "base/base.h"

typedef struct ms_app ms_app;

/* ---------------------------------------------------------------- subcommand tables */

#define MS_ARGS_ANY (-1)

/* A handler: objv[0] is the command, objv[1] the subcommand word (for a nested table,
 * objv[at] is its word). */
typedef int (*ms_subcmd_fn)(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[]);

typedef struct ms_subcmd {
    const char *name;
    ms_subcmd_fn fn;
    int min, max;          /* words after the subcommand word (max MS_ARGS_ANY: no limit) */
    const char *usage;     /* those words, as a user writes them; "" when none */
} ms_subcmd;

/* Set an error message and return TCL_ERROR. */
int ms_cmd_error(Tcl_Interp *interp, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The words objv[from..] joined with spaces, as VMD's combine_arguments (a Tcl_Obj with
 * refcount 0). */
Tcl_Obj *ms_args_joined(int objc, Tcl_Obj *const objv[], int from);

/* "<command> <subcommand>" of the handler running now ("" outside any). */
const char *ms_args_where(void);

/* The wrong-count error of the handler running now ("<where>: wrong # args: usage: <where>
 * <usage>", or "<where>: takes no arguments"); returns TCL_ERROR. */
int ms_args_usage(Tcl_Interp *interp);

/* Dispatch objv[at] over a table (ended by a NULL name), for a handler whose next word is
 * one more subcommand: the entry's handler gets all the words; its counts are of the words
 * after objv[at]. where: the words before objv[at] for messages, NULL for ms_args_where().
 * fallback (NULL: none) is called for a word no entry has; its counts include that word. */
int ms_args_dispatch(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int at,
                     const ms_subcmd *table, const ms_subcmd *fallback, const char *where);

/* ---------------------------------------------------------------- keywords */

/* A value from a NULL-ended list of names: "<where>: bad value 'x' for <what>: must be a,
 * b, or c" (what may be NULL). */
int ms_arg_choice(Tcl_Interp *interp, Tcl_Obj *word, const char *const *names, const char *what,
                  int *index);

/* ---------------------------------------------------------------- values */

/* Integers within [lo, hi]. */
int ms_arg_int(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, long lo, long hi, int *out);
int ms_arg_long(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, long lo, long hi, long *out);
/* A word from a NULL-ended list (*word its index) or else an integer within [lo, hi] (*word
 * -1, the number in *out): "start|end|<frame>" ("must be start, end, or an integer"). */
int ms_arg_long_or(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, const char *const *words,
                   long lo, long hi, int *word, long *out);
/* Finite numbers; _range: within [lo, hi]. */
int ms_arg_double(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, double *out);
int ms_arg_double_range(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, double lo, double hi,
                        double *out);
int ms_arg_float(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, float *out);
/* A boolean: on/off, yes/no, true/false, 1/0 (any case), as VMD reads them. */
int ms_arg_bool(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, int *out);
/* {x y z}: three finite numbers. */
int ms_arg_vec3(Tcl_Interp *interp, Tcl_Obj *obj, const char *what, float v[3]);

/* ---------------------------------------------------------------- option lists */

typedef enum ms_opt_type {
    MS_OPT_FLAG,      /* a word alone, no value: the int target becomes 1 */
    MS_OPT_BOOL,      /* int: 1 or 0 (ms_arg_bool) */
    MS_OPT_INT,       /* int */
    MS_OPT_LONG,      /* long */
    MS_OPT_DOUBLE,    /* double, finite */
    MS_OPT_FLOAT,     /* float, finite */
    MS_OPT_STRING,    /* const char *, into the word (valid as long as objv) */
    MS_OPT_OBJ,       /* Tcl_Obj *, the word itself (valid as long as objv) */
    MS_OPT_ENUM,      /* int: index of the value in choices */
    MS_OPT_IGNORE     /* a value accepted and not used (VMD compatibility) */
} ms_opt_type;

/* flags of a numeric option: which bounds apply, and how */
#define MS_OPT_MIN 1u      /* value >= lo */
#define MS_OPT_ABOVE 2u    /* value > lo */
#define MS_OPT_MAX 4u      /* value <= hi */
#define MS_OPT_CLAMP 8u    /* out of bounds is clamped to them, not refused */
/* flags of any option */
#define MS_OPT_ALIAS 16u   /* another name of the option before it: not listed in errors */
#define MS_OPT_ONCE 32u    /* given twice is an error */

typedef struct ms_opt {
    const char *name;               /* "-res", "first" ...: matched by the keyword rule */
    ms_opt_type type;
    size_t off;                     /* offsetof the target in the caller's struct */
    double lo, hi;                  /* bounds, as flags say */
    unsigned flags;
    const char *const *choices;     /* MS_OPT_ENUM: the values, NULL-ended */
} ms_opt;

/* Parse objv[first..objc-1] as options of table (ended by a NULL name) into the struct at
 * dst; targets not given keep their values (set the defaults first). Errors:
 *   "<where>: unknown option \"x\": must be a, b, or c"
 *   "<where>: no value for option \"x\""
 *   "<where>: bad value 'v' for x: must be ..."
 * With trailing, a last word left without a value that is not a flag is no error: it is
 * returned there (NULL when none), for commands that end with an optional molid. */
int ms_args_options(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int first,
                    const ms_opt *table, void *dst, Tcl_Obj **trailing);

/* ---------------------------------------------------------------- for dispatchers */

/* Dispatchers over tables of their own (selection methods) enter a call around the
 * handler, so ms_args_where and ms_args_usage work inside it: where is "<prefix> <name>"
 * (prefix alone when name is NULL; both must outlive the call); nargs is checked against
 * min/max (the usage error is set and the call not entered when it is outside).
 * ms_args_leave ends the call. */
typedef struct ms_args_frame {
    const char *prefix, *name, *usage;
    int max;
    char where[96];             /* made from prefix and name when first asked for */
    struct ms_args_frame *outer;
} ms_args_frame;

int ms_args_enter(ms_args_frame *c, Tcl_Interp *interp, const char *prefix, const char *name,
                  const char *usage, int nargs, int min, int max);
void ms_args_leave(ms_args_frame *c);
/* The index of word in a table of structs whose first member is the name (as
 * Tcl_GetIndexFromObjStruct reads one: stride is the struct's size, the table ends with a
 * NULL name; a list of names is a table of stride sizeof(char *)), or -1. */
int ms_args_find(const void *table, size_t stride, const char *word);
/* The error for a word no entry of the table has ("missing <what>" when word is NULL);
 * returns TCL_ERROR. */
int ms_args_unknown(Tcl_Interp *interp, const char *where, const char *what, const char *word,
                    const void *table, size_t stride);
/* Call entry e with the words objv[first..] counted against it: where "<prefix> <e name>",
 * or prefix alone when fallback. */
int ms_args_call(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], int first,
                 const ms_subcmd *e, const char *prefix, int fallback);

#endif
