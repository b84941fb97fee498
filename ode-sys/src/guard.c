/* The last line of defence against ODE's internal failures.
 *
 * ODE 0.16 reports an internal error (a failed dIASSERT/dUASSERT/dAASSERT..., or
 * dError) by calling the process-wide debug or error handler, and aborts or exits the
 * process when that handler returns. The handlers installed here never return while a
 * guard is armed on the calling thread: they record the message and longjmp to the
 * setjmp of the guarded call that is running (dWorldStep, dWorldQuickStep,
 * dSpaceCollide or dCollide), which then returns a failure code instead.
 *
 * Rules that keep the jumps sound (argued in ars-core's `guard` module docs):
 * - only the functions in this file arm a guard, and each jumps back into its own
 *   frame: the frames jumped over are ODE's and libccd's (C and C++), never Rust's;
 * - while dSpaceCollide runs the Rust near callback, the guard is disarmed (an
 *   unguarded failure aborts, as ODE itself would) and the callback's own dCollide
 *   arms a nested guard of its own;
 * - the jump targets are per thread (ODE's handlers are process-wide);
 * - a simple space is collided by simple_space.c (ODE's own loop, in the same order,
 *   without the pairs that cannot touch), any other by dSpaceCollide: "dSpaceCollide"
 *   below means either;
 * - the plain collision (odesys_guarded_collide_plain) runs a near callback written
 *   here in C, so no Rust frame is ever between its guard and ODE: its dSpaceCollide
 *   and each of its dCollide calls have guards of their own, as on the Rust path;
 *   odesys_guarded_collide_and_step runs that collision and then dWorldStep under one
 *   guard, and says which of the two failed.
 *
 * Without an armed guard a failure is reported through the sink and the process
 * aborts, which is what ODE would do. */

#include <ode/ode.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "guard.h"
#include "simple_space.h"

/* GCC's and Clang's builtin setjmp saves only the frame and stack pointers and the
 * resume address (the compiler treats every register as clobbered at the receiver),
 * several times cheaper than libc's setjmp, which also saves the signal mask; the
 * guard needs neither the mask nor more registers. Other compilers use _setjmp. */
#if defined(__GNUC__)
typedef void *guard_env[5];
#define GUARD_SETJMP(env) __builtin_setjmp(env)
#define GUARD_LONGJMP(env) __builtin_longjmp(env, 1)
#else
typedef jmp_buf guard_env;
#define GUARD_SETJMP(env) _setjmp(env)
#define GUARD_LONGJMP(env) _longjmp(env, 1)
#endif

struct guard_frame {
    guard_env env;
    struct odesys_failure *failure;
};

/* The default TLS model, not initial-exec: in a program the linker makes the access
 * direct anyway, and a module loaded with dlopen (the Python extension) must not ask
 * for static TLS, which glibc may have no room left for ("cannot allocate memory in
 * static TLS block"). */
static _Thread_local struct guard_frame *armed = NULL;
static odesys_sink sink = NULL;

static void record(struct odesys_failure *f, int kind, int num, const char *fmt, va_list ap) {
    /* Every field is written: the Rust side reads the report only after a catch. */
    f->kind = kind;
    f->number = num;
    memset(f->message, 0, sizeof f->message);
    if (fmt == NULL) {
        snprintf(f->message, sizeof f->message, "(no message)");
    } else {
        vsnprintf(f->message, sizeof f->message, fmt, ap);
    }
    f->message[sizeof f->message - 1] = '\0';
}

static void on_failure(int kind, int num, const char *fmt, va_list ap) {
    struct guard_frame *frame = armed;
    if (frame != NULL) {
        record(frame->failure, kind, num, fmt, ap);
        armed = NULL;
        GUARD_LONGJMP(frame->env);
    }
    struct odesys_failure unguarded;
    record(&unguarded, kind, num, fmt, ap);
    if (sink != NULL) {
        sink(kind, num, unguarded.message);
    }
    fprintf(stderr, "ODE %s %d: %s\n(no guard was armed on this thread: aborting as ODE would)\n",
            kind == ODESYS_FAILURE_ERROR ? "error" : "internal error", num, unguarded.message);
    abort();
}

static void on_debug(int num, const char *fmt, va_list ap) { on_failure(ODESYS_FAILURE_DEBUG, num, fmt, ap); }

static void on_error(int num, const char *fmt, va_list ap) { on_failure(ODESYS_FAILURE_ERROR, num, fmt, ap); }

static void on_message(int num, const char *fmt, va_list ap) {
    struct odesys_failure text;
    record(&text, ODESYS_MESSAGE, num, fmt, ap);
    if (sink != NULL) {
        sink(ODESYS_MESSAGE, num, text.message);
    }
}

void odesys_install_handlers(odesys_sink message_sink) {
    sink = message_sink;
    dSetMessageHandler(on_message);
    dSetDebugHandler(on_debug);
    dSetErrorHandler(on_error);
}

/* Arms a guard around `call`; on an ODE failure the guard's setjmp returns 1 and the
 * previous guard (if any) is armed again. `frame` is address-taken, so its contents
 * are in memory, not in registers clobbered by longjmp. */
#define GUARDED(report, on_fail, call)             \
    do {                                           \
        struct guard_frame frame;                  \
        struct guard_frame *previous = armed;      \
        frame.failure = (report);                  \
        if (GUARD_SETJMP(frame.env) != 0) {        \
            armed = previous;                      \
            on_fail;                               \
        }                                          \
        armed = &frame;                            \
        call;                                      \
        armed = previous;                          \
    } while (0)

int odesys_guarded_world_step(dWorldID world, dReal step_size, int quick, struct odesys_failure *failure) {
    int ok = 0;
    GUARDED(failure, return ODESYS_CAUGHT,
            ok = quick ? dWorldQuickStep(world, step_size) : dWorldStep(world, step_size));
    return ok ? ODESYS_OK : ODESYS_REFUSED;
}

struct near_trampoline {
    void *data;
    dNearCallback *callback;
};

/* The Rust callback runs with the guard disarmed: a failure inside an ODE call that
 * it makes without a guard of its own aborts instead of jumping over Rust frames. */
static void near_trampoline(void *data, dGeomID o1, dGeomID o2) {
    struct near_trampoline *t = data;
    struct guard_frame *outer = armed;
    armed = NULL;
    t->callback(t->data, o1, o2);
    armed = outer;
}

int odesys_guarded_space_collide(dSpaceID space, void *data, dNearCallback *callback,
                                 struct odesys_failure *failure) {
    struct near_trampoline t = {data, callback};
    GUARDED(failure, return ODESYS_CAUGHT, odesys_space_collide(space, &t, near_trampoline));
    return ODESYS_OK;
}

int odesys_guarded_collide(dGeomID o1, dGeomID o2, int flags, dContactGeom *contacts, int skip, int *count,
                           struct odesys_failure *failure) {
    int n = 0;
    GUARDED(failure, return ODESYS_CAUGHT, n = dCollide(o1, o2, flags, contacts, skip));
    *count = n;
    return ODESYS_OK;
}

/* The plain collision: ARS's near callback for the common case, in C.
 *
 * The Rust near callback (ars-core's world/contact.rs) takes every pair through this
 * sequence when the world has no rays, no user collision hooks, no contact feedback
 * and no cylinder/capsule sizes far enough apart to need the libccd check; this is the
 * same sequence, step for step, so that the contact joints (and so the physics) are
 * bit-identical:
 * - two static geoms: no contact;
 * - bodies joined by a (non-contact) joint: no contact;
 * - dCollide under a guard of its own (a failure skips the remaining pairs and is
 *   reported with its pair, the world stays usable);
 * - one contact joint per finite contact point, with the default contact's surface,
 *   each point recorded in `out` for the Rust side (sensors read the contacts). */

static int contact_is_finite(const dContactGeom *c) {
    const dReal *p = c->pos, *n = c->normal;
    /* As contact_is_finite in contact.rs: a NaN or an infinity makes the sum so. */
    dReal sum = p[0] + p[1] + p[2] + n[0] + n[1] + n[2] + c->depth;
    return isfinite(sum) && n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.5;
}

/* Room for at least one more record; 0 when out of memory. */
static int reserve_record(struct odesys_contact_records *out) {
    if (out->len < out->capacity) {
        return 1;
    }
    size_t capacity = out->capacity == 0 ? 64 : 2 * out->capacity;
    struct odesys_contact_record *items = realloc(out->items, capacity * sizeof *items);
    if (items == NULL) {
        return 0;
    }
    out->items = items;
    out->capacity = capacity;
    return 1;
}

dBodyID odesys_contact_body(dBodyID body) {
    if (body == NULL || !dBodyIsKinematic(body)) {
        return body;
    }
    const dReal *v = dBodyGetLinearVel(body), *w = dBodyGetAngularVel(body);
    int resting = v[0] == 0 && v[1] == 0 && v[2] == 0 && w[0] == 0 && w[1] == 0 && w[2] == 0;
    return resting ? NULL : body;
}

static void plain_near(void *data, dGeomID o1, dGeomID o2) {
    struct odesys_plain_collision *p = data;
    if (p->stopped) {
        return;
    }
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (b1 == NULL && b2 == NULL) {
        return;
    }
    if (b1 != NULL && b2 != NULL && dAreConnectedExcluding(b1, b2, dJointTypeContact)) {
        return;
    }
    int n = 0;
    GUARDED(&p->pair_failure,
            {
                p->stopped = ODESYS_PLAIN_PAIR_FAILED;
                p->failed[0] = o1;
                p->failed[1] = o2;
                return;
            },
            n = dCollide(o1, o2, p->max_contacts, p->scratch, sizeof(dContactGeom)));
    if (n > p->max_contacts) {
        n = p->max_contacts;
    }
    for (int i = 0; i < n; i++) {
        const dContactGeom *c = &p->scratch[i];
        if (!contact_is_finite(c)) {
            continue;
        }
        if (!reserve_record(&p->out)) {
            p->stopped = ODESYS_PLAIN_OUT_OF_MEMORY;
            return;
        }
        p->contact.geom = *c;
        dBodyID a1 = odesys_contact_body(b1), a2 = odesys_contact_body(b2);
        /* Between two bodies that cannot move (kinematic at rest, or one static) a
         * contact joint would do nothing but join them in an island: recorded only. */
        if (a1 != NULL || a2 != NULL) {
            dJointID j = dJointCreateContact(p->world, p->group, &p->contact);
            dJointAttach(j, a1, a2);
        }
        struct odesys_contact_record *r = &p->out.items[p->out.len++];
        r->geom = *c;
        r->o1 = o1;
        r->o2 = o2;
    }
}

int odesys_guarded_collide_plain(dSpaceID space, struct odesys_plain_collision *plain,
                                 struct odesys_failure *failure) {
    plain->stopped = 0;
    plain->out.len = 0;
    GUARDED(failure, return ODESYS_CAUGHT, odesys_space_collide(space, plain, plain_near));
    return ODESYS_OK;
}

/* The collision of odesys_guarded_collide_and_step, then its step when the
 * collision went through and made at most `plain->contact_limit` contact points, then the
 * contact joints destroyed (as the Rust side would right after the step): returns
 * ODESYS_OK or ODESYS_REFUSED (the step's result) or ODESYS_NOT_STEPPED. */
static int collide_then_step(struct odesys_plain_collision *plain) {
    plain->phase = ODESYS_PHASE_COLLIDE;
    odesys_space_collide(plain->space, plain, plain_near);
    if (plain->stopped != 0 || plain->out.len > plain->contact_limit) {
        return ODESYS_NOT_STEPPED;
    }
    plain->phase = ODESYS_PHASE_STEP;
    int stepped = dWorldStep(plain->world, plain->step_size);
    dJointGroupEmpty(plain->group);
    return stepped ? ODESYS_OK : ODESYS_REFUSED;
}

int odesys_guarded_collide_and_step(struct odesys_plain_collision *plain) {
    int result = ODESYS_NOT_STEPPED;
    plain->stopped = 0;
    plain->out.len = 0;
    GUARDED(&plain->failure, return ODESYS_CAUGHT, result = collide_then_step(plain));
    return result;
}

void odesys_contact_records_free(struct odesys_contact_records *records) {
    free(records->items);
    records->items = NULL;
    records->len = 0;
    records->capacity = 0;
}

/* For tests of the guard itself: reports an ODE internal error through ODE's own
 * dDebug, exactly as a failed assertion inside ODE does. */
int odesys_guarded_debug_report(int num, const char *message, struct odesys_failure *failure) {
    GUARDED(failure, return ODESYS_CAUGHT, dDebug(num, "%s", message));
    return ODESYS_OK;
}
