/* parm.c: VMD's type `parm` (.parm, AMBER topologies of the older kind): parm7.c, which
 * reads both header styles, under that name. */
#define PARM_TYPE_NAME "parm"
#define PARM_DESCRIPTION "AMBER parameter/topology file (old or new style)"
#define PARM_EXTENSIONS "parm"
#include "parm7.c"
