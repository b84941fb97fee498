/* A simple space's collision as ODE's own, without the pairs it tests for nothing
 * (simple_space.c); other spaces are collided by ODE. Used by guard.c; the plane test
 * also by ars-core's near callback, for the other spaces. */
#ifndef ODESYS_SIMPLE_SPACE_H
#define ODESYS_SIMPLE_SPACE_H

#include <ode/ode.h>

void odesys_space_collide(dSpaceID space, void *data, dNearCallback *callback);

/* 1 when the bounding box `aabb` (ODE's six bounds) lies wholly on the open side of
 * the plane `plane` (a, b, c, d: a·x + b·y + c·z = d, unit normal), where no collider
 * of ODE's finds a point (each reports only depths >= 0); else 0 (also for NaN). */
int odesys_box_above_plane(const dReal *plane, const dReal *aabb);

#endif
