/* `count` bodies (alternately spheres r 0.2 and boxes 0.3 m, 1 kg each) on a 1 m grid,
 * 10 per row, 0.5 to 2.3 m high, dropped on the plane y = 0, in a hash space. */
#include "scenes.h"

void ars_c_drop_pile_position(int i, dReal out[3])
{
    out[0] = (i % 10) * 1.0 + 0.01 * (i % 7);
    out[1] = 0.5 + 0.2 * (i % 10) + 0.1 * (i / 10 % 3);
    out[2] = (i / 10) * 1.0 + 0.01 * (i % 3);
}

ArsCScene *ars_c_drop_pile_new(int count)
{
    ArsCScene *s = ars_c_scene_alloc(1);
    dCreatePlane(s->space, 0, 1, 0, 0);
    if (count > ARS_C_MAX_BODIES)
        count = ARS_C_MAX_BODIES;
    for (int i = 0; i < count; i++) {
        dReal p[3];
        dMass m;
        ars_c_drop_pile_position(i, p);
        dBodyID b = dBodyCreate(s->world);
        dMassSetZero(&m);
        dGeomID g;
        if (i % 2 == 0) {
            dMassSetSphereTotal(&m, 1.0, 0.2);
            dBodySetMass(b, &m);
            dBodySetPosition(b, p[0], p[1], p[2]);
            g = dCreateSphere(s->space, 0.2);
        } else {
            dMassSetBoxTotal(&m, 1.0, 0.3, 0.3, 0.3);
            dBodySetMass(b, &m);
            dBodySetPosition(b, p[0], p[1], p[2]);
            g = dCreateBox(s->space, 0.3, 0.3, 0.3);
        }
        dGeomSetBody(g, b);
        s->bodies[s->body_count++] = b;
    }
    return s;
}
