/* A simple space's collision, as ODE's own (dxSimpleSpace::collide in
 * collision_space.cpp), without the pairs it tests for nothing.
 *
 * ODE's simple space tests every pair of enabled geoms in the order of its list
 * (the geoms moved since the last collision first, then the others) and calls the
 * near callback for each pair that is not on one body, whose category and collide
 * bits match and whose bounding boxes overlap. This does the same, in the same
 * order, so that the callback sees the same pairs one after the other and the
 * contact joints (and every later bit) are the same, but:
 * - it leaves out the pairs of two static geoms (no body) that are not rays: ARS's
 *   near callbacks (plain_near in guard.c, `pair_may_touch` in ars-core) make
 *   nothing of them, and a scene's static geoms (terrain, arenas, furniture, and the
 *   many geoms of an imported model's world body) make most of the pairs;
 * - it leaves out a plane's pairs with a geom (not a ray) whose bounding box lies
 *   wholly on the plane's open side, where no collider of ODE's finds a point (each
 *   reports only depths >= 0; `odesys_box_above_plane`, which ars-core's near callback
 *   uses in the other spaces), before the near callback rather than in it (a floor's AABB is infinite: every geom's box
 *   overlaps it);
 * - it tests the remaining pairs on a compact array rather than through ODE's
 *   linked list and virtual calls. A geom class's AABBTest is not called: only
 *   user classes can override it, and ARS's one (the convex hull in hull.c) does
 *   not.
 * (Geoms whose category and collide bits are both 0 are not in the space at all:
 * ars-core keeps them out, `keep_in_space` in world/geom.rs.) A space that holds
 * another space is collided by ODE itself. */

#include <ode/ode.h>
#include <stdlib.h>

#include "simple_space.h"

struct simple_entry {
    dReal aabb[6];
    dGeomID geom;
    dBodyID body;
    unsigned long category;
    unsigned long collide;
    /* Static and not a ray: pairs with another such geom are left out. */
    int fixed;
    int ray;
    /* A plane's parameters (a, b, c, d: a·x + b·y + c·z = d), when `plane`. */
    int plane;
    dReal plane_params[4];
    /* The index of the first entry at or after this one that is not fixed. */
    int next_moving;
};

/* A space of up to this many geoms is collided with its entries on the stack (about
 * 5 KB); a larger one allocates them for the collision and frees them after (nothing
 * is kept from one collision to the next, nor per thread). */
#define ON_STACK 64

/* ODE's test, with its comparisons (a NaN bound overlaps everything there too). */
static int boxes_disjoint(const dReal *b1, const dReal *b2) {
    return b1[0] > b2[1] || b1[1] < b2[0] || b1[2] > b2[3] || b1[3] < b2[2] || b1[4] > b2[5] || b1[5] < b2[4];
}

/* Its lowest corner's height over the plane (n·x less d) is above 0. */
int odesys_box_above_plane(const dReal *p, const dReal *aabb) {
    dReal lowest = 0;
    for (int i = 0; i < 3; i++) {
        lowest += p[i] * (p[i] >= 0 ? aabb[2 * i] : aabb[2 * i + 1]);
    }
    return lowest - p[3] > 0;
}

static void test_pair(const struct simple_entry *e1, const struct simple_entry *e2, void *data,
                      dNearCallback *callback) {
    if (e1->body == e2->body && e1->body != NULL) {
        return;
    }
    if (((e1->category & e2->collide) || (e2->category & e1->collide)) == 0) {
        return;
    }
    if (boxes_disjoint(e1->aabb, e2->aabb)) {
        return;
    }
    if ((e1->plane && !e2->ray && odesys_box_above_plane(e1->plane_params, e2->aabb)) ||
        (e2->plane && !e1->ray && odesys_box_above_plane(e2->plane_params, e1->aabb))) {
        return;
    }
    callback(data, e1->geom, e2->geom);
}

/* 0 when the space must be collided by ODE (not a simple space, a space inside it,
 * or no memory). */
static int collide_simple(dSpaceID space, void *data, dNearCallback *callback) {
    if (dSpaceGetClass(space) != dSimpleSpaceClass) {
        return 0;
    }
    /* As dxSimpleSpace::collide: the moved geoms' boxes brought up to date, their
     * dirty marks cleared (which keeps the list's order as ODE's collision would). */
    dSpaceClean(space);
    int count = dSpaceGetNumGeoms(space);
    struct simple_entry on_stack[ON_STACK];
    struct simple_entry *entries = on_stack;
    if (count > ON_STACK) {
        entries = malloc((size_t)count * sizeof *entries);
        if (entries == NULL) {
            return 0;
        }
    }
    int n = 0;
    for (int i = 0; i < count; i++) {
        /* In the list's order: dSpaceGetGeom walks it one step per call. */
        dGeomID g = dSpaceGetGeom(space, i);
        if (dGeomIsSpace(g)) {
            if (entries != on_stack) {
                free(entries);
            }
            return 0;
        }
        if (!dGeomIsEnabled(g)) {
            continue;
        }
        struct simple_entry *e = &entries[n];
        e->category = dGeomGetCategoryBits(g);
        e->collide = dGeomGetCollideBits(g);
        dGeomGetAABB(g, e->aabb);
        e->geom = g;
        e->body = dGeomGetBody(g);
        int class = dGeomGetClass(g);
        e->ray = class == dRayClass;
        e->fixed = e->body == NULL && !e->ray;
        e->plane = class == dPlaneClass;
        if (e->plane) {
            dGeomPlaneGetParams(g, e->plane_params);
        }
        n++;
    }
    int next = n;
    for (int i = n - 1; i >= 0; i--) {
        if (!entries[i].fixed) {
            next = i;
        }
        entries[i].next_moving = next;
    }
    for (int i = 0; i < n; i++) {
        const struct simple_entry *e1 = &entries[i];
        if (e1->fixed) {
            for (int j = i + 1 < n ? entries[i + 1].next_moving : n; j < n; j = j + 1 < n ? entries[j + 1].next_moving : n) {
                test_pair(e1, &entries[j], data, callback);
            }
        } else {
            for (int j = i + 1; j < n; j++) {
                test_pair(e1, &entries[j], data, callback);
            }
        }
    }
    /* An ODE failure in a callback that the outer guard catches jumps over this: the
     * entries of a large space are then lost once (a failed collision, not a step). */
    if (entries != on_stack) {
        free(entries);
    }
    return 1;
}

void odesys_space_collide(dSpaceID space, void *data, dNearCallback *callback) {
    if (!collide_simple(space, data, callback)) {
        dSpaceCollide(space, data, callback);
    }
}
