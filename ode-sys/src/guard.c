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
 * - the jump targets are per thread (ODE's handlers are process-wide).
 *
 * Without an armed guard a failure is reported through the sink and the process
 * aborts, which is what ODE would do. */

#include <ode/ode.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "guard.h"

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
#define GUARDED(failure, on_fail, call)            \
    do {                                           \
        struct guard_frame frame;                  \
        struct guard_frame *previous = armed;      \
        frame.failure = (failure);                 \
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
    GUARDED(failure, return ODESYS_CAUGHT, dSpaceCollide(space, &t, near_trampoline));
    return ODESYS_OK;
}

int odesys_guarded_collide(dGeomID o1, dGeomID o2, int flags, dContactGeom *contacts, int skip, int *count,
                           struct odesys_failure *failure) {
    int n = 0;
    GUARDED(failure, return ODESYS_CAUGHT, n = dCollide(o1, o2, flags, contacts, skip));
    *count = n;
    return ODESYS_OK;
}

/* For tests of the guard itself: reports an ODE internal error through ODE's own
 * dDebug, exactly as a failed assertion inside ODE does. */
int odesys_guarded_debug_report(int num, const char *message, struct odesys_failure *failure) {
    GUARDED(failure, return ODESYS_CAUGHT, dDebug(num, "%s", message));
    return ODESYS_OK;
}
