/* A simple space's collision as ODE's own, without the pairs it tests for nothing
 * (simple_space.c); other spaces are collided by ODE. Used by guard.c only. */
#ifndef ODESYS_SIMPLE_SPACE_H
#define ODESYS_SIMPLE_SPACE_H

#include <ode/ode.h>

void odesys_space_collide(dSpaceID space, void *data, dNearCallback *callback);

#endif
