/* Guarded ODE calls: an ODE internal error becomes a return code (see guard.c). */
#ifndef ODESYS_GUARD_H
#define ODESYS_GUARD_H

#include <ode/ode.h>

/* Kinds of report. */
#define ODESYS_MESSAGE 0       /* a warning (dMessage): ODE goes on */
#define ODESYS_FAILURE_DEBUG 1 /* a failed internal assertion (dDebug) */
#define ODESYS_FAILURE_ERROR 2 /* an error (dError) */

/* Results of a guarded call. */
#define ODESYS_OK 1      /* the call returned normally */
#define ODESYS_REFUSED 0 /* the call returned failure (a step out of memory) */
#define ODESYS_CAUGHT -1 /* ODE reported an internal error; `failure` says which */

struct odesys_failure {
    int kind;
    int number;
    char message[512];
};

/* Receives warnings, and failures that no guard catches (before the abort). It must
 * not unwind. */
typedef void (*odesys_sink)(int kind, int number, const char *message);

void odesys_install_handlers(odesys_sink sink);
int odesys_guarded_world_step(dWorldID world, dReal step_size, int quick, struct odesys_failure *failure);
int odesys_guarded_space_collide(dSpaceID space, void *data, dNearCallback *callback,
                                 struct odesys_failure *failure);
int odesys_guarded_collide(dGeomID o1, dGeomID o2, int flags, dContactGeom *contacts, int skip, int *count,
                           struct odesys_failure *failure);
int odesys_guarded_debug_report(int num, const char *message, struct odesys_failure *failure);

#endif
