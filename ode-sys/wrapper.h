/* The headers ode-sys binds: all of ODE, the guarded calls of src/guard.c and the hull geoms of src/hull.c. */
#include <ode/ode.h>
#include "src/guard.h"
#include "src/hull.h"
