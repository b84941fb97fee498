/* The thesis' falling ball: sphere r 0.5, 1 kg, centre (1,1,1), plane y = 0. */
#include "scenes.h"

ArsCScene *ars_c_falling_sphere_new(void)
{
    ArsCScene *s = ars_c_scene_alloc(0);
    dCreatePlane(s->space, 0, 1, 0, 0);

    dMass m;
    dBodyID ball = dBodyCreate(s->world);
    dMassSetZero(&m);
    dMassSetSphereTotal(&m, 1.0, 0.5);
    dBodySetMass(ball, &m);
    dBodySetPosition(ball, 1, 1, 1);
    dGeomID g = dCreateSphere(s->space, 0.5);
    dGeomSetBody(g, ball);
    s->bodies[s->body_count++] = ball;
    return s;
}
