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
#define ODESYS_NOT_STEPPED 2 /* odesys_guarded_collide_and_step collided but did not step */

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
/* One contact point of the plain collision, with the geoms of its pair as ODE gave
 * them to the near callback. */
struct odesys_contact_record {
    dContactGeom geom;
    dGeomID o1;
    dGeomID o2;
};

/* A growable array of records, allocated here (realloc) and freed with
 * odesys_contact_records_free. */
struct odesys_contact_records {
    struct odesys_contact_record *items;
    size_t len;
    size_t capacity;
};

/* Why the plain collision stopped before the last pair (0: it did not). */
#define ODESYS_PLAIN_PAIR_FAILED 1   /* dCollide failed: `failed`, `pair_failure` say so */
#define ODESYS_PLAIN_OUT_OF_MEMORY 2 /* the records could not grow */

/* What the plain near callback needs: filled by the Rust side, except the results.
 * The Rust side keeps one for a world from one collision to the next (its parameters
 * change only with the world's default surface), so that a collision passes one
 * pointer; nothing in it points into itself. */
struct odesys_plain_collision {
    dWorldID world;
    dJointGroupID group;
    /* The default contact: its surface is used, its geometry overwritten per point. */
    dContact contact;
    /* Most contact points per pair; room for that many in `scratch`. */
    int max_contacts;
    dContactGeom *scratch;
    struct odesys_contact_records out;
    /* Results. */
    int stopped;
    dGeomID failed[2];
    struct odesys_failure pair_failure; /* written when a pair fails */
    /* What odesys_guarded_collide_and_step does: collide `space`, then step by
     * `step_size` when the collision made at most `contact_limit` contact points. */
    dSpaceID space;
    dReal step_size;
    size_t contact_limit;
    /* What odesys_guarded_collide_and_step was doing when it caught a failure, and
     * the failure. */
    int phase;
    struct odesys_failure failure;
};

#define ODESYS_PHASE_COLLIDE 1
#define ODESYS_PHASE_STEP 2

/* dSpaceCollide with the plain near callback (see guard.c), under a guard. */
int odesys_guarded_collide_plain(dSpaceID space, struct odesys_plain_collision *plain,
                                 struct odesys_failure *failure);
/* The plain collision of `plain->space`, then dWorldStep by `plain->step_size` when
 * the collision went through and made at most `plain->contact_limit` contact points
 * (else ODESYS_NOT_STEPPED), then (once the world has stepped) the contact joints
 * destroyed, under one guard: a caught failure is reported in `plain->failure`, and
 * `plain->phase` says whether it was the collision or the step. */
int odesys_guarded_collide_and_step(struct odesys_plain_collision *plain);
void odesys_contact_records_free(struct odesys_contact_records *records);
/* The body a contact joint is attached to for `body` (NULL: the world): the world for
 * a kinematic body at rest (velocities exactly 0), which then behaves as the world in
 * the contact's row to the bit, and does not join the islands of everything it
 * touches; the body itself otherwise. */
dBodyID odesys_contact_body(dBodyID body);
int odesys_guarded_debug_report(int num, const char *message, struct odesys_failure *failure);

#endif
