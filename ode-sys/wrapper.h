/* The headers ode-sys binds: all of ODE, and the guarded calls of src/guard.c. */
#include <ode/ode.h>
#include "src/guard.h"
