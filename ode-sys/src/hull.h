/* Convex hulls whose bounding box costs O(1) per step (see hull.c). */
#ifndef ODESYS_HULL_H
#define ODESYS_HULL_H

#include <ode/ode.h>

/* Registers the hull geom class with ODE, once per process, after dInitODE2 and before
 * any other thread uses ODE; returns its class number (a later call returns the same). */
int odesys_hull_register(void);

/* The hull class's number, or -1 before odesys_hull_register. */
int odesys_hull_class(void);

/* A convex hull geom in `space` (none when null), with dCreateConvex's arrays (which it
 * points into, copying none: they must outlive the geom) and the same meaning: the
 * geom's origin inside the hull. Null when the class is not registered or there are
 * no points. dGeomDestroy frees all of it. */
dGeomID odesys_hull_create(dSpaceID space, const dReal *planes, unsigned plane_count, const dReal *points,
                           unsigned point_count, const unsigned *polygons);

/* The plain dConvex that a hull geom collides through (for tests comparing the two);
 * null when `g` is not a hull geom. */
dGeomID odesys_hull_inner(dGeomID g);

#endif
