/* Convex hulls whose bounding box costs O(1) per step.
 *
 * ODE's dConvex computes its bounding box from every vertex, every time its body moves
 * (dxConvex::computeAABB): with hulls of hundreds of vertices that is most of a step
 * of a mesh-heavy model. A hull geom here is a user geom class (dCreateGeomClass)
 * that stands for a plain dConvex, its `inner`, which is in no space and has no body:
 *
 * - its bounding box is the box of the hull's local bounding box turned by the geom's
 *   rotation, each half-extent clipped to the radius of a sphere holding the hull,
 *   and widened by far more than the roundings of ODE's own box: it contains the box
 *   ODE's dConvex would have, so the broad phase finds every pair it would find;
 * - to collide, the inner dConvex takes the geom's position and rotation (the same
 *   numbers a dConvex of the same offset would have) and ODE's own convex collider
 *   runs on it; the contacts then name the hull geom instead of the inner one. Two
 *   hull geoms collide through their two inner geoms in the order dCollide was given,
 *   as two dConvex would, so the contacts are the dConvex ones, bit for bit.
 *
 * Everything here runs inside ODE's collision, under ars-core's guards; nothing here
 * allocates but through ODE. */

#include "hull.h"

#include <math.h>
#include <stddef.h>

/* The class data of a hull geom. */
struct hull_proxy {
    dGeomID inner;     /* the dConvex it collides through (in no space, no body) */
    dReal centre[3];   /* the centre of the hull's bounding box, in the geom's frame */
    dReal half[3];     /* its half-extents */
    dReal radius;      /* a sphere about `centre` holding every point */
};

/* Relative widening of the box: ODE's box rounds each point's p + R v (a few units in
 * the last place of the coordinates); this is a thousand times more. */
#define HULL_BOX_SLACK 1e-12

static int hull_class = -1;

int odesys_hull_class(void) { return hull_class; }

static void hull_box(dGeomID g, dReal aabb[6]) {
    const struct hull_proxy *h = dGeomGetClassData(g);
    const dReal *p = dGeomGetPosition(g);
    const dReal *R = dGeomGetRotation(g); /* 3 rows of 4 */
    for (int i = 0; i < 3; i++) {
        const dReal *row = R + 4 * i;
        dReal c = p[i] + row[0] * h->centre[0] + row[1] * h->centre[1] + row[2] * h->centre[2];
        dReal e = fabs(row[0]) * h->half[0] + fabs(row[1]) * h->half[1] + fabs(row[2]) * h->half[2];
        if (h->radius < e) {
            e = h->radius;
        }
        e += HULL_BOX_SLACK * (e + fabs(c));
        aabb[2 * i] = c - e;
        aabb[2 * i + 1] = c + e;
    }
}

/* The inner dConvex at the hull geom's pose. */
static dGeomID hull_placed_inner(dGeomID g) {
    const struct hull_proxy *h = dGeomGetClassData(g);
    const dReal *p = dGeomGetPosition(g);
    dGeomSetPosition(h->inner, p[0], p[1], p[2]);
    dGeomSetRotation(h->inner, dGeomGetRotation(g));
    return h->inner;
}

/* Reverses contact points as dCollide does for a collider registered the other way. */
static void hull_reverse(dContactGeom *contact, int skip, int count) {
    for (int i = 0; i < count; i++) {
        dContactGeom *c = (dContactGeom *)((char *)contact + (size_t)i * (size_t)skip);
        c->normal[0] = -c->normal[0];
        c->normal[1] = -c->normal[1];
        c->normal[2] = -c->normal[2];
        dGeomID g = c->g1;
        c->g1 = c->g2;
        c->g2 = g;
        int side = c->side1;
        c->side1 = c->side2;
        c->side2 = side;
    }
}

/* Contact points that name `inner` name `outer` instead. */
static void hull_rename(dContactGeom *contact, int skip, int count, dGeomID inner, dGeomID outer) {
    for (int i = 0; i < count; i++) {
        dContactGeom *c = (dContactGeom *)((char *)contact + (size_t)i * (size_t)skip);
        if (c->g1 == inner) {
            c->g1 = outer;
        }
        if (c->g2 == inner) {
            c->g2 = outer;
        }
    }
}

/* A box holding a geom, in the geom's own frame, placed: its centre and axes
 * (columns) in the world, its half-extents. */
struct placed_box {
    dReal centre[3];
    dReal axis[3][3]; /* axis[j]: the box's j-th axis, world */
    dReal half[3];
};

/* The box of a hull geom (its hull's bounding box) or of a box, sphere, capsule or
 * cylinder (ODE's: a capsule's and a cylinder's axis is their frame's z), placed where
 * the geom is; 0 for a geom of another class. */
static int placed_box(dGeomID g, int class, struct placed_box *b) {
    dReal offset[3] = {0, 0, 0};
    if (class == hull_class) {
        const struct hull_proxy *h = dGeomGetClassData(g);
        for (int k = 0; k < 3; k++) {
            offset[k] = h->centre[k];
            b->half[k] = h->half[k];
        }
    } else if (class == dBoxClass) {
        dVector3 sides;
        dGeomBoxGetLengths(g, sides);
        for (int k = 0; k < 3; k++) {
            b->half[k] = 0.5 * sides[k];
        }
    } else if (class == dSphereClass) {
        dReal r = dGeomSphereGetRadius(g);
        b->half[0] = b->half[1] = b->half[2] = r;
    } else if (class == dCapsuleClass || class == dCylinderClass) {
        dReal r, length;
        if (class == dCapsuleClass) {
            dGeomCapsuleGetParams(g, &r, &length);
        } else {
            dGeomCylinderGetParams(g, &r, &length);
        }
        b->half[0] = b->half[1] = r;
        b->half[2] = 0.5 * length + (class == dCapsuleClass ? r : 0);
    } else {
        return 0;
    }
    const dReal *p = dGeomGetPosition(g);
    const dReal *R = dGeomGetRotation(g); /* 3 rows of 4 */
    for (int i = 0; i < 3; i++) {
        const dReal *row = R + 4 * i;
        b->centre[i] = p[i] + row[0] * offset[0] + row[1] * offset[1] + row[2] * offset[2];
        for (int j = 0; j < 3; j++) {
            b->axis[j][i] = row[j];
        }
    }
    return 1;
}

static dReal dot3(const dReal *u, const dReal *v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; }

/* Whether a hull geom's box (its hull's bounding box in its own frame) and the box of
 * geom `g2` (another hull's, or a box, sphere, capsule or cylinder: `placed_box`) lie
 * apart with room to spare, by the separating axis test over their 15 axes (their
 * faces' normals and their edges' cross products). Each geom lies within its box, so
 * apart boxes mean apart geoms, where ODE's collider finds no point: the pair is
 * skipped before that collider's support-point searches over every vertex of the
 * hull. The room (a ten-thousandth of the boxes' extents along the axis, and a
 * micrometre) keeps pairs that nearly touch for the collider, whatever its
 * tolerances. */
static int hull_boxes_apart(dGeomID g1, dGeomID g2, int class2) {
    struct placed_box A, B;
    if (!placed_box(g2, class2, &B)) {
        return 0;
    }
    placed_box(g1, hull_class, &A);
    const dReal *a = A.half, *b = B.half;
    dReal d[3] = {B.centre[0] - A.centre[0], B.centre[1] - A.centre[1], B.centre[2] - A.centre[2]};
    dReal R[3][3], Q[3][3], t[3];
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            R[i][j] = dot3(A.axis[i], B.axis[j]);
            /* Parallel edges make a cross product of zero: a little more than |R|
             * keeps those axes from separating anything by rounding. */
            Q[i][j] = fabs(R[i][j]) + 1e-12;
        }
        t[i] = dot3(d, A.axis[i]);
    }
#define APART(distance, ra, rb) (fabs(distance) > (ra) + (rb) + 1e-4 * ((ra) + (rb)) + 1e-6)
    for (int i = 0; i < 3; i++) {
        if (APART(t[i], a[i], b[0] * Q[i][0] + b[1] * Q[i][1] + b[2] * Q[i][2])) {
            return 1;
        }
    }
    for (int j = 0; j < 3; j++) {
        dReal distance = t[0] * R[0][j] + t[1] * R[1][j] + t[2] * R[2][j];
        if (APART(distance, a[0] * Q[0][j] + a[1] * Q[1][j] + a[2] * Q[2][j], b[j])) {
            return 1;
        }
    }
    for (int i = 0; i < 3; i++) {
        int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
        for (int j = 0; j < 3; j++) {
            int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
            /* The axis A_i × B_j. */
            dReal distance = t[i2] * R[i1][j] - t[i1] * R[i2][j];
            dReal ra = a[i1] * Q[i2][j] + a[i2] * Q[i1][j];
            dReal rb = b[j1] * Q[i][j2] + b[j2] * Q[i][j1];
            if (APART(distance, ra, rb)) {
                return 1;
            }
        }
    }
#undef APART
    return 0;
}

/* The collider of a hull geom `o1` with any geom `o2` (dCollide calls it with the hull
 * geom first, reversing the points itself when it was given the other way round). */
static int hull_collide(dGeomID o1, dGeomID o2, int flags, dContactGeom *contact, int skip) {
    int other = dGeomGetClass(o2);
    if (hull_boxes_apart(o1, o2, other)) {
        return 0;
    }
    dGeomID inner1 = hull_placed_inner(o1);
    int count;
    if (other == hull_class) {
        /* dCollide(a, b) of two hull geoms comes here as hull_collide(b, a) (ODE
         * registers a class's collider with itself reversed), and reverses what this
         * returns: collide a's dConvex with b's, as dCollide(a, b) of two dConvex
         * would, and give the reverse. */
        dGeomID inner2 = hull_placed_inner(o2);
        count = dCollide(inner2, inner1, flags, contact, skip);
        hull_reverse(contact, skip, count);
        hull_rename(contact, skip, count, inner2, o2);
    } else {
        if (other == dTriMeshClass || other == dHeightfieldClass) {
            /* These two colliders read the convex's bounding box (ODE's space would
             * have brought it up to date): bring it up to date. */
            dReal box[6];
            dGeomGetAABB(inner1, box);
        }
        count = dCollide(inner1, o2, flags, contact, skip);
    }
    hull_rename(contact, skip, count, inner1, o1);
    return count;
}

static dColliderFn *hull_collider_for(int num) {
    (void)num;
    return &hull_collide;
}

static void hull_destroy(dGeomID g) {
    struct hull_proxy *h = dGeomGetClassData(g);
    if (h->inner != NULL) {
        dGeomDestroy(h->inner);
        h->inner = NULL;
    }
}

static int is_space_class(int c) { return c >= dFirstSpaceClass && c <= dLastSpaceClass; }

int odesys_hull_register(void) {
    if (hull_class >= 0) {
        return hull_class;
    }
    dGeomClass c = {0};
    c.bytes = (int)sizeof(struct hull_proxy);
    c.collider = &hull_collider_for;
    c.aabb = &hull_box;
    c.aabb_test = NULL;
    c.dtor = &hull_destroy;
    hull_class = dCreateGeomClass(&c);
    /* Fill ODE's collider table now rather than at each pair's first collision (which
     * writes the process-wide table during a collision): with every geom class but
     * the spaces (which collide their geoms) and the geom transform. */
    for (int other = 0; other < dGeomNumClasses; other++) {
        if (!is_space_class(other) && other != dGeomTransformClass &&
            (other < dFirstUserClass || other == hull_class)) {
            dSetColliderOverride(hull_class, other, &hull_collide);
        }
    }
    return hull_class;
}

dGeomID odesys_hull_create(dSpaceID space, const dReal *planes, unsigned plane_count, const dReal *points,
                           unsigned point_count, const unsigned *polygons) {
    if (hull_class < 0 || point_count == 0) {
        return NULL;
    }
    dReal lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        lo[k] = hi[k] = points[k];
    }
    for (unsigned i = 1; i < point_count; i++) {
        for (int k = 0; k < 3; k++) {
            dReal v = points[3 * i + k];
            lo[k] = v < lo[k] ? v : lo[k];
            hi[k] = v > hi[k] ? v : hi[k];
        }
    }
    dGeomID inner = dCreateConvex(NULL, planes, plane_count, points, point_count, polygons);
    dGeomID g = dCreateGeom(hull_class);
    struct hull_proxy *h = dGeomGetClassData(g);
    h->inner = inner;
    for (int k = 0; k < 3; k++) {
        h->centre[k] = 0.5 * (lo[k] + hi[k]);
        h->half[k] = 0.5 * (hi[k] - lo[k]);
    }
    dReal r2 = 0;
    for (unsigned i = 0; i < point_count; i++) {
        dReal d[3] = {points[3 * i] - h->centre[0], points[3 * i + 1] - h->centre[1], points[3 * i + 2] - h->centre[2]};
        dReal s = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        r2 = s > r2 ? s : r2;
    }
    h->radius = sqrt(r2);
    if (space != NULL) {
        dSpaceAdd(space, g);
    }
    return g;
}

dGeomID odesys_hull_inner(dGeomID g) {
    if (hull_class < 0 || g == NULL || dGeomGetClass(g) != hull_class) {
        return NULL;
    }
    const struct hull_proxy *h = dGeomGetClassData(g);
    return h->inner;
}
