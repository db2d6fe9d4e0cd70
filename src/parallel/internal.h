/* internal.h: what the files of src/parallel share and no one else needs. */
#ifndef MS_PARALLEL_INTERNAL_H
#define MS_PARALLEL_INTERNAL_H

#ifdef MS_HAVE_MPI
#include <mpi.h>
/* The duplicate of MPI_COMM_WORLD this copy of the layer talks on. */
MPI_Comm ms_par_comm(void);
/* Wait for a request, polling with ms_par_backoff (MPI's own waits spin on a core).
 * Returns 0, or -1 after timeout seconds (<= 0: no limit). */
int ms_par_wait(MPI_Request *req, double timeout);
#endif
/* Pause between polls of a message that has not come: nothing for the first hundred
 * polls, then 50 us, then 2 ms, so a waiting rank leaves the cores to those working. */
void ms_par_backoff(int *spins);

#endif
