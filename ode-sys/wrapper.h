/* The headers ode-sys binds: all of ODE, the guarded calls of src/guard.c, the hull geoms of src/hull.c and the plane test of src/simple_space.c. */
#include <ode/ode.h>
#include "src/guard.h"
#include "src/hull.h"
#include "src/simple_space.h"
