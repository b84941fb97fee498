/* The headers ode-sys binds: all of ODE, plus vsnprintf to format the va_list that
 * ODE's message, debug and error handlers receive. */
#include <ode/ode.h>
#include <stdio.h>
