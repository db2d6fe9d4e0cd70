/* crdbox.c: AMBER's ASCII trajectory with a box line after each frame, VMD's type `crdbox`:
 * crd.c built with the box. */
#define CRD_WITH_BOX 1
#define CRD_TYPE_NAME "crdbox"
#define CRD_DESCRIPTION "AMBER ASCII trajectory (mdcrd) with a periodic box"
#define CRD_EXTENSIONS "crdbox"
#include "crd.c"
